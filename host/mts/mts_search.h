// The MTS search of docs/spec.md 5.2, driven by the host: per distance, start at s = z, double
// while it fights (giving up past max_separation_factor * z), treat s = 0 as fighting, then bisect
// at the midpoint until (hi - lo) / hi <= rel_precision. Exactly this probe sequence, so results
// compare with any other implementation of the measurement.
//
// Clipped probes (a fragment of either plane left the clip volume) and uncovered ones (a kernel
// pixel that a plane does not cover, so nothing was compared there) are never accepted as MTS:
// before a clean separation is known they bound the search from above like a ceiling; once one
// is known they count as not clean. Non-finite probes count as fighting and flag the row. A
// ceiling below the vertex bound ends the search: below it plane B coincides with plane A, so
// no separation there can be clean (the row's verdict is then `clipped`).
//
// After a resolved search, stiffness probes (scene.stiffness_probes per side) test a few
// separations just above MTS and just below lo: fights(z, s) is not always monotone in s
// (docs/stability.md), and a disagreeing probe sets non_monotone with the bracket it found.
#pragma once

#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "host/model/scene.h"
#include "host/mts/mts_row.h"
#include "host/mts/probe.h"

namespace depthprec {

class Bisection {
 public:
  // coincide_below: separations below it put plane B on plane A (the vertex bound).
  Bisection(double z, double rel_precision, double max_separation_factor, double coincide_below);
  // A search that continues a known bracket over other frames (worst-case sampling): lo fought
  // in earlier frames, so it counts as fighting here too; the first probe is at hi, and the
  // search doubles from there while it fights.
  Bisection(double z, double rel_precision, double max_separation_factor, double coincide_below,
            double lo, double hi);
  bool done() const { return done_; }
  double next() const { return next_; }  // the separation to probe now
  void record(Outcome o);

  double lo() const { return lo_; }
  double hi() const { return hi_; }  // +inf while no clean separation is known
  bool resolved() const { return hi_ < std::numeric_limits<double>::infinity(); }
  bool saw_clipped() const { return clipped_; }
  bool saw_uncovered() const { return uncovered_; }
  bool saw_non_finite() const { return non_finite_; }
  bool non_monotone() const { return non_monotone_; }
  int probes() const { return probes_; }
  const std::vector<std::pair<double, Outcome>>& history() const { return history_; }

 private:
  void advance();
  double z_, rel_, limit_, coincide_;
  double lo_ = 0, hi_ = std::numeric_limits<double>::infinity(),
         ceil_ = std::numeric_limits<double>::infinity();
  double next_;
  bool doubling_ = true, done_ = false, clipped_ = false, uncovered_ = false, non_finite_ = false,
       non_monotone_ = false;
  int probes_ = 0;
  std::vector<std::pair<double, Outcome>> history_;
};

// A probe's outcome at separation s in the row's record: the largest fighting (or non-finite) and
// smallest clean separation probed, and the non_finite flag.
void note_outcome(MtsRow& row, double s, Outcome o);
// Where a clean separation lies below a fighting one, the row is non_monotone with that bracket.
void take_monotone_bracket(MtsRow& row);

// Separations of the stiffness probes: n above hi, n below lo, at relative offsets r, 8r, 64r...
// (r the bisection's precision; below lo at most halfway to 0).
std::vector<double> stiffness_separations(double lo, double hi, double r, int n);

// Where a distance's search starts when it continues an earlier one (worst-case sampling).
struct SearchStart {
  double lo, hi;  // the bracket found so far: lo fought, hi did not
};

// Searches every distance of one pair, all distances' probes batched into shared launches.
// on_row is called as each distance finishes (in finishing order); the return is in the order
// of `distances`. When stop() turns true the search ends after the current launch round with an
// Error(ExitCode::interrupted): rows already passed to on_row are the finished ones.
// starts (empty, or one per distance): each distance continues that bracket; its stiffness probes
// run only when the search rose above it.
std::vector<MtsRow> search_pair(ProbeEvaluator& evaluator, const Scene& scene, const EvalPair& pair,
                                const std::vector<double>& distances,
                                const std::function<void(const MtsRow&)>& on_row = {},
                                const std::function<bool()>& stop = {},
                                const std::vector<SearchStart>& starts = {});

}  // namespace depthprec
