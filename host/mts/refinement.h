// The one worst-case refinement (docs/mts.md, "The worst case") that the MTS (its rows, also
// render's and the attribution's) and depth bias (its answers) run: rounds of orientations
// (round_chunks), each chunk probed at every open answer; an orientation that fails there is
// searched alone, upwards from the answer's bracket, and the chunk probed again at the raised
// answer, until it passes. Every orientation of the chunk then passes at the answer, as the earlier
// chunks' do (each passed at a smaller one; the searches assume a failure does not return above a
// passing value). A measurement plugs in what its answers are, what probing one at its value and
// searching one alone mean (upwards from its bracket; the MTS's paper frames: from scratch), and
// when a round has converged. refine_chunk also runs one chunk alone (the paper's frames).
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "host/model/frame_setup.h"
#include "host/model/scene.h"
#include "host/mts/probe.h"
#include "host/mts/sampler.h"

namespace depthprec {

class OpenClRuntime;

// Where the refinement's evaluators come from: the caller's kind of evaluator (emulated, exact,
// rendered), built and accounted as the caller's own. The scene outlives the evaluator.
template <class Evaluator>
class EvaluatorSource {
 public:
  virtual ~EvaluatorSource() = default;
  // An evaluator of the pair for scene (its frames the paper's, a chunk's or one orientation's)
  // over the orientations sampled (none: the paper's path).
  virtual std::unique_ptr<Evaluator> make(const Scene& scene, const Orientations& orientations) = 0;
  // Takes the evaluator's statistics once it has run.
  virtual void retire(Evaluator& evaluator) { (void)evaluator; }
};

// The evaluators a constructor Concrete(runtime, scene, pair, orientations) makes for one pair,
// nobody's accounts kept: the emulator's (search_sampled) and the binary64 pipeline's
// (attribution).
template <class Evaluator, class Concrete>
class PairSource : public EvaluatorSource<Evaluator> {
 public:
  PairSource(OpenClRuntime& rt, const EvalPair& pair) : rt_(rt), pair_(pair) {}
  std::unique_ptr<Evaluator> make(const Scene& scene, const Orientations& o) override {
    return std::make_unique<Concrete>(rt_, scene, pair_, o);
  }

 private:
  OpenClRuntime& rt_;
  const EvalPair& pair_;
};

// A measurement under refinement. Items are what converges (a row, a distance), slots the answers
// refined (a row's MTS; a distance's units, factor and both): indices the measurement defines.
template <class Evaluator>
class Refinement {
 public:
  virtual ~Refinement() = default;

  // The slots of the open items that the next chunk refines.
  virtual std::vector<size_t> slots(const std::vector<size_t>& open) const = 0;
  // Plane A's distance of a slot.
  virtual double z(size_t slot) const = 0;
  // How many slots share the evaluator's launches at once (all, unless it caches per distance).
  virtual size_t window(Evaluator& evaluator) const {
    (void)evaluator;
    return SIZE_MAX;
  }
  // Throws to end the refinement (an interrupt), checked before each probe of a chunk.
  virtual void check_stop() const {}
  // Probes the slots over the chunk, each at its answer, and records the probes' work.
  virtual std::vector<ProbeResult> probe(Evaluator& evaluator,
                                         const std::vector<size_t>& slots) = 0;
  // Whether the probe result fails the slot's answer.
  virtual bool fails(size_t slot, const ProbeResult& result) const = 0;
  // Slots of different groups are searched apart (bias: an answer's kind), in group order.
  virtual int groups() const { return 1; }
  virtual int group(size_t slot) const {
    (void)slot;
    return 0;
  }
  // Searches each slot alone in its orientation (one: the scene of one frame), upwards from its
  // bracket or as the measurement says, and takes the result: for each slot whether its answer rose
  // (the chunk is probed again at it).
  virtual std::vector<bool> search(Evaluator& single, const Scene& one,
                                   const std::vector<size_t>& slots) = 0;
  // A window of slots passes over the chunk's evaluator (each answer clean there): what the
  // measurement also asks of them over the same orientations.
  virtual void window_done(Evaluator& evaluator, const std::vector<size_t>& slots) {
    (void)evaluator;
    (void)slots;
  }
  // A chunk of n orientations is done for the open items (slots: what it refined).
  virtual void chunk_done(const std::vector<size_t>& open, const std::vector<size_t>& slots,
                          size_t n) = 0;
  // Round bookkeeping: before it, and after it the items still open (not yet converged).
  virtual void round_begin(const std::vector<size_t>& open) = 0;
  virtual std::vector<size_t> round_end(int round, const std::vector<size_t>& open) = 0;
};

namespace refinement_detail {

// One window of slots over one chunk: probe, search each failing orientation alone, probe again.
template <class Evaluator>
void refine_window(Refinement<Evaluator>& m, EvaluatorSource<Evaluator>& source, Evaluator& ev,
                   const Scene& scene, const std::vector<Angles>& part,
                   std::vector<size_t> pending) {
  while (!pending.empty()) {
    m.check_stop();
    const std::vector<ProbeResult> results = m.probe(ev, pending);
    std::vector<size_t> raised;
    for (int g = 0; g < m.groups(); ++g) {
      Scene one = scene;  // each failing orientation alone, at its slot's distance
      one.frames = 1;
      Orientations alone;
      std::vector<size_t> failed;
      for (size_t k = 0; k < pending.size(); ++k) {
        if (m.group(pending[k]) != g) continue;
        if (!m.fails(pending[k], results[k]) || results[k].deciding_frame < 0) continue;
        failed.push_back(pending[k]);
        alone.at[m.z(pending[k])] = {part[static_cast<size_t>(results[k].deciding_frame)]};
      }
      if (failed.empty()) continue;
      const std::unique_ptr<Evaluator> single = source.make(one, alone);
      const std::vector<bool> rose = m.search(*single, one, failed);
      source.retire(*single);
      for (size_t k = 0; k < failed.size(); ++k)
        if (rose[k]) raised.push_back(failed[k]);
    }
    pending = std::move(raised);
  }
}

}  // namespace refinement_detail

// Refines the open items' answers over one chunk of orientations: probes each at its answer,
// searches every failing orientation alone, and probes again, until the chunk passes.
template <class Evaluator>
void refine_chunk(Refinement<Evaluator>& m, EvaluatorSource<Evaluator>& source, const Scene& scene,
                  const std::vector<size_t>& open, const std::vector<Angles>& part) {
  const std::vector<size_t> slots = m.slots(open);
  if (!slots.empty()) {
    Scene chunk = scene;
    chunk.frames = static_cast<int>(part.size());
    Orientations sampled;
    sampled.chunk = true;
    for (const size_t s : slots) sampled.at[m.z(s)] = part;
    const std::unique_ptr<Evaluator> ev = source.make(chunk, sampled);
    // Slots in windows the evaluator's per-distance cache holds at once: a distance's plane
    // A is filled once, whatever the window, and its launches do not depend on how many
    // slots share the device.
    const size_t window = std::max<size_t>(1, m.window(*ev));
    for (size_t from = 0; from < slots.size(); from += window) {
      const auto first = slots.begin() + static_cast<long>(from);
      const std::vector<size_t> in_window(
          first, first + static_cast<long>(std::min(window, slots.size() - from)));
      refinement_detail::refine_window(m, source, *ev, scene, part, in_window);
      m.window_done(*ev, in_window);
    }
    source.retire(*ev);
  }
  m.chunk_done(open, slots, part.size());
}

// Refines the open items' answers over the scene's rounds until each converges or max_rounds ran.
template <class Evaluator>
void refine_rounds(Refinement<Evaluator>& m, EvaluatorSource<Evaluator>& source, const Scene& scene,
                   std::vector<size_t> open) {
  for (int round = 1; round <= scene.worst_case.max_rounds && !open.empty(); ++round) {
    m.round_begin(open);
    // Each chunk continues the answers the chunks before it left. Every item takes the same
    // orientations: its answer depends on its own rounds only, whichever items share launches.
    for (const std::vector<Angles>& part : round_chunks(scene, round))
      refine_chunk(m, source, scene, open, part);
    open = m.round_end(round, open);
  }
}

}  // namespace depthprec
