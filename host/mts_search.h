// The MTS search of SPEC 5.2, driven by the host: per distance, start at s = z, double while it
// fights (giving up past max_separation_factor * z), treat s = 0 as fighting, then bisect at the
// midpoint until (hi - lo) / hi <= rel_precision. Exactly this probe sequence, so results compare
// with any other implementation of the measurement.
//
// Clipped probes (a fragment of either plane left the clip volume) are never accepted as MTS:
// before a clean separation is known they bound the search from above like a ceiling; once one
// is known they count as not clean. Non-finite probes count as fighting and flag the row.
#pragma once

#include <cstdint>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "host/mts_evaluator.h"

namespace depthprec {

class Bisection {
 public:
  Bisection(double z, double rel_precision, double max_separation_factor);
  bool done() const { return done_; }
  double next() const { return next_; }  // the separation to probe now
  void record(Outcome o);

  double lo() const { return lo_; }
  double hi() const { return hi_; }  // +inf while no clean separation is known
  bool resolved() const { return hi_ < std::numeric_limits<double>::infinity(); }
  bool saw_clipped() const { return clipped_; }
  bool saw_non_finite() const { return non_finite_; }
  bool non_monotone() const { return non_monotone_; }
  int probes() const { return probes_; }
  const std::vector<std::pair<double, Outcome>>& history() const { return history_; }

 private:
  void advance();
  double z_, rel_, limit_;
  double lo_ = 0, hi_ = std::numeric_limits<double>::infinity(),
         ceil_ = std::numeric_limits<double>::infinity();
  double next_;
  bool doubling_ = true, done_ = false, clipped_ = false, non_finite_ = false, non_monotone_ = false;
  int probes_ = 0;
  std::vector<std::pair<double, Outcome>> history_;
};

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
  uint64_t launches = 0;      // kernel launches its probes took part in (shared with other rows)
  double seconds = 0;         // attributed wall time of the launches (by fragment pairs)
  double kernel_seconds = 0;  // attributed device time of the launches (profiling events)
  int clipped_probes = 0;  // probes in which some fragment left the clip volume
  // clipped: the row has no MTS because every separation that did not fight was clipped.
  bool non_finite = false, clipped = false, unresolvable = false, non_monotone = false,
       uncovered = false;
  std::string flags() const;  // "non_finite,clipped" or "" when none
};

// Searches every distance of one pair, all distances' probes batched into shared launches.
// on_row is called as each distance finishes (in finishing order); the return is in the order
// of `distances`. When stop() turns true the search ends after the current launch round with an
// Error(ExitCode::interrupted): rows already passed to on_row are the finished ones.
std::vector<MtsRow> search_pair(MtsEvaluator& evaluator, const Scene& scene, const EvalPair& pair,
                                const std::vector<double>& distances,
                                const std::function<void(const MtsRow&)>& on_row = {},
                                const std::function<bool()>& stop = {});

}  // namespace depthprec
