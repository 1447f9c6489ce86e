// The storage-limited pipeline of MTS attribution (kernels/mts_exact.cl): the same probes and
// frames as MtsEvaluator, with everything before storage exact up to binary64 -- plane B at
// z + s itself, not fl32(z + s) -- so a search over it measures what storage alone allows.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "host/model/frame_setup.h"
#include "host/model/scene.h"
#include "host/mts/probe.h"
#include "host/runtime/opencl_runtime.h"

namespace depthprec {

class ExactEvaluator : public ProbeEvaluator {
 public:
  // orientations: the frames' sampled ones where a distance has them (worst-case sampling).
  // shortcuts: rows decided clean from their end pixels where that is certain
  // (kernels/mts_exact.cl, ROW_ENDS), plane A's cache (below) and pixels decided clean from the
  // planes' chords (CHORDS: B's against A's cached codes, or against A's chords before the cache
  // is filled); off only to check that they never change a result.
  ExactEvaluator(OpenClRuntime& rt, const Scene& scene, const EvalPair& pair,
                 const Orientations& orientations = {}, bool shortcuts = true);
  std::vector<ProbeResult> run(const std::vector<Probe>& probes) override;
  // Plane A does not depend on the separation: from a distance's second run on, its codes and
  // status at every pixel of every frame come from a cache filled once (kernels/mts_exact.cl,
  // mts_exact_a), which holds this many distances within its budget (0: none, every probe
  // computes plane A itself; an evaluator of more frames than one distance's share holds).
  size_t distances_at_once() const override { return slots_ > 0 ? slots_ : SIZE_MAX; }
  // Kernel rows (of every probe and frame run) whose pixels were, some or all, decided clean
  // from end pixels.
  uint64_t rows_decided_from_ends() const { return rows_from_ends_; }
  // Kernel rows whose pixels were, some or all, decided clean from the planes' chords
  // (kernels/mts_exact.cl, CHORDS), with plane A's cache or without.
  uint64_t rows_decided_from_chords() const { return rows_from_chords_; }
  // Test only: per probe, the largest (|D_c - chord| + 8u) / margin over its frames' kernel rows
  // where the chords apply (kernels/exact/chords.cl, CHORD_AUDIT: D_c either plane's depth as the
  // pixel loop computes it); -1 where none do. Needs the shortcuts.
  std::vector<double> chord_audit(const std::vector<Probe>& probes);
  // Distances whose plane A was filled into the cache (each time it was).
  uint64_t cache_fills() const { return cache_fills_; }

 private:
  OpenClRuntime& rt_;
  const Scene& scene_;
  EvalPair pair_;
  Orientations orientations_;
  cl::Kernel kernel_;
  uint64_t rows_from_ends_ = 0, rows_from_chords_ = 0, cache_fills_ = 0;

  // Plane A's cache: slots of a distance's frames x kernel rows x kw_pad_ pixels, a code and a
  // status byte each; which distance each slot holds, and how often each distance ran.
  std::string options_;
  size_t slots_ = 0, kw_pad_ = 0;
  cl::Kernel cached_, fill_;
  cl::Buffer a_code_, a_bits_;
  std::vector<double> slot_z_;
  std::map<double, int> runs_at_;
  // The planes of `count` frames from `first` of each probe, as both kernels read them.
  std::vector<double> plane_records(const std::vector<Probe>& probes,
                                    const std::vector<size_t>& which, int first, int count) const;
  // The slot of each probe's distance with plane A filled, or empty where the cache is not used.
  std::vector<size_t> cache_slots(const std::vector<Probe>& probes);
  // Launches a kernel over items work-items in launches of one width (see the .cpp).
  void launch(cl::Kernel& k, size_t items);
};

}  // namespace depthprec
