#include "host/mts/worst_case.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <memory>

#include "host/base/errors.h"
#include "host/model/frame_setup.h"
#include "host/mts/mts_bound.h"
#include "host/mts/mts_evaluator.h"
#include "host/mts/mts_search.h"
#include "host/mts/refinement.h"

namespace depthprec {

namespace {

// A separation clean below one that fought: the row is not monotone there (the first such bracket
// is the one it reports).
void note_non_monotone(MtsRow& row, double clean, double fight) {
  row.non_monotone = true;
  if (std::isnan(row.monotone_fight)) {
    row.monotone_clean = clean;
    row.monotone_fight = fight;
  }
}

// Another search's work, added to the row that takes it in.
void add_work(MtsRow& row, const MtsRow& search) {
  row.probes += search.probes;
  row.frames += search.frames;
  row.fragment_pairs += search.fragment_pairs;
  row.launches += search.launches;
  row.seconds += search.seconds;
  row.kernel_seconds += search.kernel_seconds;
  row.clipped_probes += search.clipped_probes;
}

// A search that continues a row's bracket over other orientations: its work always, its bracket
// when it rose above the row's, its flags when it saw them. paper: the orientation is one of the
// paper's frames, which the row's answer must hold for as one search over them all would.
void take_search(MtsRow& row, const MtsRow& found, bool paper) {
  add_work(row, found);
  row.non_finite |= found.non_finite;
  row.uncovered |= found.uncovered;
  // An orientation that fights at every separation up to the search's limit makes the worst case
  // unresolvable. One whose separations above the bracket were clipped or left pixels uncovered
  // leaves the answer to the orientations that could be measured; its flags say so -- except a
  // paper frame: no separation is clean over all of them, as the one search would find.
  if (found.unresolvable && (paper || (!found.clipped && !found.uncovered && !found.non_finite))) {
    row.unresolvable = true;
    row.clipped |= found.clipped;
    row.mts = row.hi = row.mts_seen = std::numeric_limits<double>::infinity();
    return;
  }
  if (found.unresolvable) return;
  if (!(found.hi > row.hi)) {
    if (paper) {  // it failed at the row's MTS and is clean at or below it: not monotone there
      row.clean_min = std::min(row.clean_min, found.hi);
      note_non_monotone(row, found.hi, row.hi);
    }
    return;
  }
  // Below its bracket, where it is clean again, the orientation alone fights no more and the
  // earlier ones already did not: fights are not monotone there, for the row as for it.
  row.non_monotone |= found.non_monotone;
  if (std::isnan(row.monotone_fight)) {
    row.monotone_clean = found.monotone_clean;
    row.monotone_fight = found.monotone_fight;
  }
  row.lo = found.lo;
  row.hi = row.mts = found.hi;
  row.mts_seen = found.mts_seen;
  row.below_one_code = found.below_one_code;
  row.code_width = found.code_width;
  // The old clean minimum fights in the new orientation: the bracket is the search's.
  row.fight_max = std::max(row.fight_max, found.fight_max);
  row.clean_min = found.clean_min;
}

// A probe of a chunk at separation s (the row's MTS): its work and what it saw. It is the row's
// only probe in its launches, so their launches are its own.
void take_probe(MtsRow& row, double s, const ProbeResult& r) {
  if (r.outcome == Outcome::fight) row.fight_max = std::max(row.fight_max, s);
  ++row.probes;
  row.add_probe_work(r);
  row.launches += r.launches;
  if (r.outcome == Outcome::non_finite) row.non_finite = true;
}

// The first step above a bracket that one orientation is known to fight at: fights between
// chunks rise by a few tens of percent, so an eighth up brackets most of them at once.
constexpr double kFirstStep = 1.125;

// The MTS under refinement: a slot is a row (an item too), its answer the row's MTS (hi); a
// probe at it fails when it fights, and the fighting orientation is searched alone upwards from
// the row's bracket.
class MtsRefinement : public Refinement<ProbeEvaluator> {
 public:
  MtsRefinement(const Scene& scene, const EvalPair& pair, std::vector<MtsRow>& rows,
                const std::function<bool()>& stop)
      : scene_(scene), pair_(pair), rows_(rows), stop_(stop) {}

  std::vector<size_t> slots(const std::vector<size_t>& open) const override {
    std::vector<size_t> live;  // an orientation that fights at any separation ends a row
    for (const size_t i : open)
      if (!rows_[i].unresolvable) live.push_back(i);
    return live;
  }
  double z(size_t slot) const override { return rows_[slot].z; }
  // A row's plane A is filled once, whatever the window, as search_pair takes them.
  size_t window(ProbeEvaluator& ev) const override { return ev.distances_at_once(); }
  void check_stop() const override {
    if (stop_ && stop_()) throw Error(ExitCode::interrupted, "interrupted");
  }
  std::vector<ProbeResult> probe(ProbeEvaluator& ev, const std::vector<size_t>& slots) override {
    std::vector<Probe> probes;
    for (const size_t i : slots) probes.push_back({rows_[i].z, rows_[i].hi});
    std::vector<ProbeResult> results = ev.run(probes);
    for (size_t k = 0; k < slots.size(); ++k) {
      take_probe(rows_[slots[k]], probes[k].s, results[k]);
      // clipped or uncovered over the paper's frames with no one frame to blame: the one search
      if (paper_ && fails(slots[k], results[k]) && results[k].deciding_frame < 0)
        one_search_.push_back(slots[k]);
    }
    return results;
  }
  // The rounds: a fight. The paper's frames: anything the one search would not take as clean.
  bool fails(size_t, const ProbeResult& r) const override {
    return paper_ ? search_outcome(r) != Outcome::clean : r.outcome == Outcome::fight;
  }
  std::vector<bool> search(ProbeEvaluator& single, const Scene& one,
                           const std::vector<size_t>& slots) override {
    std::vector<bool> rose(slots.size(), false);
    std::vector<size_t> pending(slots.size());
    for (size_t k = 0; k < slots.size(); ++k) pending[k] = k;
    if (paper_) pending = search_slots(single, one, slots, pending, false, rose);
    search_slots(single, one, slots, pending, true, rose);
    return rose;
  }
  // The paper's frames' stiffness probes, over all of them as the one search runs them.
  void window_done(ProbeEvaluator& ev, const std::vector<size_t>& slots) override {
    if (paper_) stiffness_probes(ev, slots);
  }
  // The refinement of the paper's frames (search_paper_frames): a frame that fails is searched
  // from scratch, on the bisection's own grid, and the rules are the one search's.
  void set_paper(bool on) { paper_ = on; }
  // Rows the paper's frames left to the one search over them all.
  const std::vector<size_t>& one_search() const { return one_search_; }
  void chunk_done(const std::vector<size_t>&, const std::vector<size_t>& slots, size_t n) override {
    for (const size_t i : slots) rows_[i].orientations += n;
  }
  void round_begin(const std::vector<size_t>& open) override {
    before_.clear();  // each open row's MTS before the round
    for (const size_t i : open) before_.push_back(rows_[i].hi);
  }
  std::vector<size_t> round_end(int round, const std::vector<size_t>& open) override {
    std::vector<size_t> still;
    for (size_t k = 0; k < open.size(); ++k) {
      MtsRow& row = rows_[open[k]];
      if (row.unresolvable) continue;  // nothing left to converge
      row.convergence = (row.hi - before_[k]) / before_[k];
      // A round samples as many orientations as all before it: stop once doubling them no longer
      // raises the MTS by more than the tolerance.
      if (round < scene_.worst_case.min_rounds || row.convergence > scene_.worst_case.tolerance)
        still.push_back(open[k]);
    }
    return still;
  }

 private:
  // search_pair's stiffness probes of each resolved slot, over the evaluator's frames, taken as
  // finish_row takes them (host/mts/mts_search.cpp).
  void stiffness_probes(ProbeEvaluator& ev, const std::vector<size_t>& slots) {
    std::vector<Probe> probes;
    std::vector<size_t> owner;
    for (const size_t i : slots) {
      const MtsRow& row = rows_[i];
      if (row.unresolvable || scene_.stiffness_probes <= 0 ||
          std::find(one_search_.begin(), one_search_.end(), i) != one_search_.end())
        continue;
      for (const double s :
           stiffness_separations(row.lo, row.hi, scene_.rel_precision, scene_.stiffness_probes)) {
        probes.push_back({row.z, s});
        owner.push_back(i);
      }
    }
    if (probes.empty()) return;
    check_stop();
    const std::vector<ProbeResult> results = ev.run(probes);
    std::map<size_t, uint64_t> launches;  // a row's share: its busiest probe's
    for (size_t k = 0; k < probes.size(); ++k) {
      MtsRow& row = rows_[owner[k]];
      const ProbeResult& r = results[k];
      ++row.probes;
      row.add_probe_work(r);
      launches[owner[k]] = std::max(launches[owner[k]], r.launches);
      note_outcome(row, probes[k].s, search_outcome(r));
    }
    for (const auto& [i, n] : launches) {
      rows_[i].launches += n;
      take_monotone_bracket(rows_[i]);
    }
  }

  // Searches the slots at positions `which` of `slots` alone, upwards from each row's bracket or
  // (from_bracket false) from scratch, and takes what rose; returns the positions that did not.
  std::vector<size_t> search_slots(ProbeEvaluator& single, const Scene& one,
                                   const std::vector<size_t>& slots,
                                   const std::vector<size_t>& which, bool from_bracket,
                                   std::vector<bool>& rose) {
    if (which.empty()) return {};
    std::vector<double> zs;
    std::vector<SearchStart> starts;
    for (const size_t k : which) {
      const MtsRow& row = rows_[slots[k]];
      zs.push_back(row.z);
      if (from_bracket) starts.push_back({row.hi, row.hi * kFirstStep});
    }
    const std::vector<MtsRow> found = search_pair(single, one, pair_, zs, {}, stop_, starts);
    std::vector<size_t> stayed;
    for (size_t j = 0; j < which.size(); ++j) {
      MtsRow& row = rows_[slots[which[j]]];
      const double before = row.hi;
      take_search(row, found[j], paper_);
      rose[which[j]] = row.hi > before && !row.unresolvable;  // probe the chunk again above it
      if (!rose[which[j]] && !row.unresolvable) stayed.push_back(which[j]);
    }
    return stayed;
  }

  const Scene& scene_;
  const EvalPair& pair_;
  std::vector<MtsRow>& rows_;
  const std::function<bool()>& stop_;
  bool paper_ = false;
  std::vector<size_t> one_search_;
  std::vector<double> before_;
};

}  // namespace

std::vector<MtsRow> search_paper_frames(EvaluatorSource<ProbeEvaluator>& source, const Scene& scene,
                                        const EvalPair& pair, const std::vector<double>& distances,
                                        const std::function<bool()>& stop) {
  std::vector<Angles> paper;
  for (int f = 0; f < scene.frames; ++f) paper.push_back(frame_angles(scene, f));
  // The single frames' searches run no stiffness probes: the one search's run over all frames
  // once the chunk is clean (MtsRefinement::window_done).
  Scene quiet = scene;
  quiet.stiffness_probes = 0;
  std::vector<MtsRow> rows;
  {
    Scene one = quiet;
    one.frames = 1;
    Orientations first;
    for (const double z : distances) first.at[z] = {paper.front()};
    const std::unique_ptr<ProbeEvaluator> ev = source.make(one, first);
    rows = search_pair(*ev, one, pair, distances, {}, stop);
    source.retire(*ev);
  }
  std::vector<size_t> open;
  for (size_t i = 0; i < rows.size(); ++i) {
    MtsRow& r = rows[i];
    if (r.unresolvable || r.beyond_far || r.before_near) continue;
    open.push_back(i);
    r.orientations = 0;  // the chunks below count every frame, the first one too
  }
  MtsRefinement refinement(scene, pair, rows, stop);
  refinement.set_paper(true);
  // One chunk, as the one search's probes are: the answer is probed clean over every frame.
  refine_chunk<ProbeEvaluator>(refinement, source, quiet, open, paper);
  // Where the frames were clipped or left pixels uncovered with no one frame to search (near the
  // far plane, at the plane's edge), the one search over them all decides the row, its work added.
  if (!refinement.one_search().empty()) {
    std::vector<double> zs;
    for (const size_t i : refinement.one_search()) zs.push_back(rows[i].z);
    const std::unique_ptr<ProbeEvaluator> ev = source.make(scene, {});
    const std::vector<MtsRow> found = search_pair(*ev, scene, pair, zs, {}, stop);
    source.retire(*ev);
    for (size_t k = 0; k < zs.size(); ++k) {
      MtsRow& row = rows[refinement.one_search()[k]];
      MtsRow taken = found[k];
      add_work(taken, row);
      row = taken;
    }
  }
  for (MtsRow& r : rows) r.mts_paper = r.mts;
  return rows;
}

void refine_worst_case(EvaluatorSource<ProbeEvaluator>& source, const Scene& scene,
                       const EvalPair& pair, std::vector<MtsRow>& rows,
                       const std::function<bool()>& stop) {
  std::vector<size_t> open;  // rows still refined
  for (size_t i = 0; i < rows.size(); ++i) {
    const MtsRow& r = rows[i];
    if (!r.unresolvable && !r.beyond_far && !r.before_near) open.push_back(i);
  }
  MtsRefinement refinement(scene, pair, rows, stop);
  refine_rounds<ProbeEvaluator>(refinement, source, scene, std::move(open));
}

std::vector<MtsRow> search_sampled(EvaluatorSource<ProbeEvaluator>& source, const Scene& scene,
                                   const EvalPair& pair, const std::vector<double>& distances,
                                   const std::function<void(const MtsRow&)>& on_row,
                                   const std::function<bool()>& stop) {
  const bool worst_case = scene.sampling == Sampling::worst_case;
  // The guaranteed MTS belongs to a final row, not to the searches the refinement runs inside
  // it: each row gets it once, as it is handed on (or returned).
  std::map<double, MtsRow> handed_on;  // paper sampling: rows bounded as they were handed on
  std::function<void(const MtsRow&)> final_row;
  if (on_row && !worst_case)
    final_row = [&](const MtsRow& r) {
      MtsRow bounded = r;
      set_mts_bound(bounded, scene);
      on_row(bounded);
      handed_on.emplace(r.z, bounded);
    };
  std::vector<MtsRow> rows;
  if (worst_case) {
    rows = search_paper_frames(source, scene, pair, distances, stop);
    refine_worst_case(source, scene, pair, rows, stop);
  } else {
    const std::unique_ptr<ProbeEvaluator> ev = source.make(scene, {});
    rows = search_pair(*ev, scene, pair, distances, final_row, stop);
    source.retire(*ev);
  }
  for (MtsRow& r : rows) {
    const auto it = handed_on.find(r.z);
    if (it != handed_on.end())
      r = it->second;
    else
      set_mts_bound(r, scene);
  }
  if (on_row && worst_case)
    for (const MtsRow& r : rows) on_row(r);
  return rows;
}

std::vector<MtsRow> search_sampled(OpenClRuntime& rt, const Scene& scene, const EvalPair& pair,
                                   const std::vector<double>& distances,
                                   const std::function<bool()>& stop) {
  PairSource<ProbeEvaluator, MtsEvaluator> source(rt, pair);
  return search_sampled(source, scene, pair, distances, {}, stop);
}

}  // namespace depthprec
