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

#include "host/mts/mts_evaluator.h"

namespace depthprec {

class Bisection {
 public:
  // coincide_below: separations below it put plane B on plane A (the vertex bound).
  Bisection(double z, double rel_precision, double max_separation_factor, double coincide_below);
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

// What a row finally says: a number (resolved) or why there is none.
enum class Verdict {
  resolved,
  unresolvable,
  non_finite,
  clipped,
  uncovered,
  below_vertex_bound,
  beyond_far_plane,
  nearer_than_near_plane,
};
const char* to_string(Verdict v);  // "resolved", ..., "below vertex bound", "beyond far plane"

struct MtsRow {
  EvalPair pair;
  double z = 0;
  double mts = 0;  // hi: the smallest separation seen that never fought; +inf if unresolvable
  double lo = 0, hi = 0;
  double mts_seen = 0;  // fl32(z + mts) - fl32(z)
  double vertex_bound = 0;
  int probes = 0;
  uint64_t frames = 0;
  uint64_t fragment_pairs = 0;
  // Kernel launches its probes took part in. Launches render the probes of every distance of a
  // pair at once, so rows share them: a row never counts more than the run made, and the rows of
  // a run add up to more than its total (the footer's "kernel launches").
  uint64_t launches = 0;
  double seconds = 0;         // attributed wall time of the launches (by fragment pairs)
  double kernel_seconds = 0;  // attributed device time of the launches (profiling events)
  int clipped_probes = 0;     // probes in which some fragment left the clip volume
  // clipped: the row has no MTS because every separation that did not fight was clipped.
  bool non_finite = false, clipped = false, unresolvable = false, non_monotone = false,
       uncovered = false;
  bool beyond_far = false;  // z past the far plane of a technique that has one: not searched
  bool before_near =
      false;  // z nearer than the near plane of a technique that clips there: not searched
  // A resolved MTS (as seen, mts_seen) below the width of the code interval holding z (less the
  // bisection's precision twice over): the planes' depths in the kernel did not span one code,
  // so where z falls between two codes decided the answer, and a z nearby can need up to
  // code_width (docs/mts.md, "Below one code").
  bool below_one_code = false;
  double code_width = 0;  // that width, when below_one_code
  // Over every probe (search and stiffness): the largest separation that fought and the
  // smallest clean one. fight_max > clean_min is a non-monotone bracket; fight_max is then the
  // upper MTS (every clean answer lies above it). 0 / +inf when there is none.
  double fight_max = 0, clean_min = std::numeric_limits<double>::infinity();
  // MTS attribution (table --attribute; NaN when not computed): the MTS of the storage-limited
  // pipeline (exact up to binary64, then stored) and of the arithmetic-limited one (the binary32
  // pipeline, no storage quantisation); the vertex bound is the third factor.
  double storage_mts = std::numeric_limits<double>::quiet_NaN();
  double arithmetic_mts = std::numeric_limits<double>::quiet_NaN();
  bool attributed() const { return !std::isnan(storage_mts); }
  // The largest factor: "storage", "arithmetic" or "vertex" ("" when not attributed). The
  // binary32 pipeline holds the vertex rounding too, so its factor never falls below the vertex
  // bound: "vertex" is named when neither other factor exceeds it by more than the bisection's
  // resolution (set_dominant).
  std::string dominant;
  void set_dominant(double rel_precision);
  // A factor larger than the MTS itself (by more than the bisection's precision twice over):
  // the factors interact, and rounding errors can cancel (docs/stability.md).
  bool factor_above_mts(double rel_precision) const;
  std::string flags() const;  // "non_finite,clipped" or "" when none
  Verdict verdict() const;
};

// Searches every distance of one pair, all distances' probes batched into shared launches.
// on_row is called as each distance finishes (in finishing order); the return is in the order
// of `distances`. When stop() turns true the search ends after the current launch round with an
// Error(ExitCode::interrupted): rows already passed to on_row are the finished ones.
std::vector<MtsRow> search_pair(ProbeEvaluator& evaluator, const Scene& scene, const EvalPair& pair,
                                const std::vector<double>& distances,
                                const std::function<void(const MtsRow&)>& on_row = {},
                                const std::function<bool()>& stop = {});

}  // namespace depthprec
