#include "host/mts/worst_case.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include "host/base/errors.h"
#include "host/model/frame_setup.h"
#include "host/mts/mts_evaluator.h"
#include "host/mts/mts_search.h"

namespace depthprec {

namespace {

// Point n of the R3 sequence in [0, 1)^3 (M. Roberts, "The unreasonable effectiveness of
// quasirandom sequences", 2018): x_i = frac(1/2 + n / g^(i+1)), g the real root of
// x^4 = x + 1. Its points fill the cube evenly at every length, so a round's points lie between
// the earlier rounds' rather than on them.
std::array<double, 3> r3(uint64_t n) {
  constexpr double g = 1.2207440846057594754;
  std::array<double, 3> x{};
  double a = 1;
  for (int i = 0; i < 3; ++i) {
    a /= g;
    const double v = 0.5 + a * static_cast<double>(n);
    x[i] = v - std::floor(v);
  }
  return x;
}

}  // namespace

size_t round_size(const Scene& scene, int round) {
  return static_cast<size_t>(scene.worst_case.round_size) << (round - 1);
}

std::vector<Angles> round_orientations(const Scene& scene, int round) {
  const double r = std::abs(scene.rotation_range_deg) * M_PI / 180.0;
  // Each axis as the paper's path distributes it, r sin(phase) with the phase uniform: a sine
  // dwells near its extremes, where the planes are steepest.
  const auto in_cube = [r](const std::array<double, 3>& u) {
    Angles a{};
    for (int i = 0; i < 3; ++i) a[i] = r * std::sin(M_PI * (u[i] - 0.5));
    return a;
  };
  const size_t n = round_size(scene, round);
  std::vector<Angles> out;
  out.reserve(n);
  // Round 1 starts with the cube's corners (every axis at its limit: the steepest planes).
  const size_t corners = round == 1 ? std::min<size_t>(8, n) : 0;
  for (size_t c = 0; c < corners; ++c)
    out.push_back({c & 1 ? r : -r, c & 2 ? r : -r, c & 4 ? r : -r});
  // The sequence's points so far: the earlier rounds' sizes less the corners.
  uint64_t next = 0;
  for (int k = 1; k < round; ++k) next += round_size(scene, k);
  if (round > 1) next -= std::min<size_t>(8, round_size(scene, 1));
  while (out.size() < n) out.push_back(in_cube(r3(next++)));
  return out;
}

std::vector<std::vector<Angles>> round_chunks(const Scene& scene, int round) {
  const std::vector<Angles> list = round_orientations(scene, round);
  const auto chunk = static_cast<size_t>(scene.worst_case.round_size);
  std::vector<std::vector<Angles>> out;
  for (size_t first = 0; first < list.size(); first += chunk) {
    const auto from = list.begin() + static_cast<long>(first);
    out.emplace_back(from, from + static_cast<long>(std::min(chunk, list.size() - first)));
  }
  return out;
}

namespace {

// A search that continues a row's bracket over other orientations: its work always, its bracket
// when it rose above the row's, its flags when it saw them.
void take_search(MtsRow& row, const MtsRow& found) {
  row.probes += found.probes;
  row.frames += found.frames;
  row.fragment_pairs += found.fragment_pairs;
  row.launches += found.launches;
  row.seconds += found.seconds;
  row.kernel_seconds += found.kernel_seconds;
  row.clipped_probes += found.clipped_probes;
  row.non_finite |= found.non_finite;
  row.uncovered |= found.uncovered;
  // An orientation that fights at every separation up to the search's limit makes the worst case
  // unresolvable. One whose separations above the bracket were clipped or left pixels uncovered
  // leaves the answer to the orientations that could be measured; its flags say so.
  if (found.unresolvable && !found.clipped && !found.uncovered && !found.non_finite) {
    row.unresolvable = true;
    row.mts = row.hi = row.mts_seen = std::numeric_limits<double>::infinity();
    return;
  }
  if (found.unresolvable || !(found.hi > row.hi)) return;
  // Below its bracket, where it is clean again, the orientation alone fights no more and the
  // earlier ones already did not: fights are not monotone there, for the row as for it.
  row.non_monotone |= found.non_monotone;
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

// refine_chunk for the rows of one window, with the chunk's evaluator (below).
void refine_window(ProbeEvaluator& ev, const Scene& scene, const EvalPair& pair,
                   const std::vector<Angles>& part, std::vector<MtsRow>& rows,
                   const std::vector<size_t>& window, const WithEvaluator& with_evaluator,
                   const std::function<bool()>& stop) {
  std::vector<size_t> pending = window;
  while (!pending.empty()) {
    if (stop && stop()) throw Error(ExitCode::interrupted, "interrupted");
    std::vector<Probe> probes;
    for (const size_t i : pending) probes.push_back({rows[i].z, rows[i].hi});
    const std::vector<ProbeResult> results = ev.run(probes);
    Scene one = scene;  // each fighting orientation alone, at its row's distance
    one.frames = 1;
    Orientations alone;
    std::vector<size_t> fought;
    std::vector<double> zs;
    std::vector<SearchStart> starts;
    for (size_t k = 0; k < pending.size(); ++k) {
      MtsRow& row = rows[pending[k]];
      take_probe(row, probes[k].s, results[k]);
      if (results[k].outcome != Outcome::fight || results[k].deciding_frame < 0) continue;
      fought.push_back(pending[k]);
      zs.push_back(row.z);
      starts.push_back({row.hi, row.hi * kFirstStep});
      alone.at[row.z] = {part[static_cast<size_t>(results[k].deciding_frame)]};
    }
    if (fought.empty()) break;
    std::vector<MtsRow> found;
    with_evaluator(one, alone, [&](ProbeEvaluator& single) {
      found = search_pair(single, one, pair, zs, {}, stop, starts);
    });
    pending.clear();
    for (size_t k = 0; k < fought.size(); ++k) {
      MtsRow& row = rows[fought[k]];
      const double before = row.hi;
      take_search(row, found[k]);
      if (row.hi > before && !row.unresolvable)
        pending.push_back(fought[k]);  // probe the chunk again above it
    }
  }
}

// Refines the open rows over one chunk of orientations: each row's probe at its MTS runs over
// the chunk; an orientation that fights there is searched alone, upwards from the row's bracket,
// and the chunk probed again at the raised MTS, until it is clean (or shows no fight to follow).
// Every orientation of the chunk is then clean at the row's MTS, as are the earlier chunks'
// (each was clean at a lower one; the search assumes fights do not return above a clean
// separation, which the stiffness probes check near each bracket).
void refine_chunk(const WithEvaluator& with_evaluator, const Scene& scene, const EvalPair& pair,
                  const std::vector<Angles>& part, std::vector<MtsRow>& rows,
                  const std::vector<size_t>& open, const std::function<bool()>& stop) {
  Scene chunk_scene = scene;
  chunk_scene.frames = static_cast<int>(part.size());
  Orientations sampled;
  for (const size_t i : open) sampled.at[rows[i].z] = part;
  with_evaluator(chunk_scene, sampled, [&](ProbeEvaluator& ev) {
    // Rows in windows the evaluator's plane-A cache holds at once, as search_pair takes them: a
    // row's plane A is filled once, whatever the window, and its launches do not depend on how
    // many rows share the device.
    const size_t window = std::max<size_t>(1, ev.distances_at_once());
    for (size_t from = 0; from < open.size(); from += window) {
      const auto first = open.begin() + static_cast<long>(from);
      refine_window(ev, scene, pair, part, rows,
                    std::vector<size_t>(
                        first, first + static_cast<long>(std::min(window, open.size() - from))),
                    with_evaluator, stop);
    }
  });
  for (const size_t i : open) rows[i].orientations += part.size();
}

}  // namespace

void refine_worst_case(const WithEvaluator& with_evaluator, const Scene& scene,
                       const EvalPair& pair, std::vector<MtsRow>& rows,
                       const std::function<bool()>& stop) {
  std::vector<size_t> open;  // rows still refined
  for (size_t i = 0; i < rows.size(); ++i) {
    const MtsRow& r = rows[i];
    if (!r.unresolvable && !r.beyond_far && !r.before_near) open.push_back(i);
  }
  for (int round = 1; round <= scene.worst_case.max_rounds && !open.empty(); ++round) {
    std::vector<double> before;  // each open row's MTS before the round
    for (const size_t i : open) before.push_back(rows[i].hi);
    // Each chunk continues the brackets the chunks before it left. Every row takes the same
    // orientations: a row's answer depends on its own rounds only, whichever rows share its
    // launches.
    for (const std::vector<Angles>& part : round_chunks(scene, round)) {
      std::vector<size_t> live;  // an orientation that fights at any separation ends a row
      for (const size_t i : open)
        if (!rows[i].unresolvable) live.push_back(i);
      refine_chunk(with_evaluator, scene, pair, part, rows, live, stop);
    }
    std::vector<size_t> still;
    for (size_t k = 0; k < open.size(); ++k) {
      MtsRow& row = rows[open[k]];
      if (row.unresolvable) continue;  // nothing left to converge
      row.convergence = (row.hi - before[k]) / before[k];
      // A round samples as many orientations as all before it: stop once doubling them no longer
      // raises the MTS by more than the tolerance.
      if (round < scene.worst_case.min_rounds || row.convergence > scene.worst_case.tolerance)
        still.push_back(open[k]);
    }
    open = std::move(still);
  }
}

std::vector<MtsRow> search_sampled(OpenClRuntime& rt, const Scene& scene, const EvalPair& pair,
                                   const std::vector<double>& distances,
                                   const std::function<bool()>& stop) {
  const WithEvaluator with = [&rt, &pair](const Scene& s, const Orientations& o,
                                          const std::function<void(ProbeEvaluator&)>& use) {
    MtsEvaluator ev(rt, s, pair, o);
    use(ev);
  };
  std::vector<MtsRow> rows;
  with(scene, {},
       [&](ProbeEvaluator& ev) { rows = search_pair(ev, scene, pair, distances, {}, stop); });
  if (scene.sampling == Sampling::worst_case) refine_worst_case(with, scene, pair, rows, stop);
  return rows;
}

}  // namespace depthprec
