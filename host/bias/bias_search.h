// The depth-bias searches of `depthprec bias` (docs/bias.md), driven by the host as the MTS search
// is: per (pair, distance) the smallest constant bias (units, factor 0: a whole number, as D3D's
// integer DepthBias and every engine's settings take it), the smallest slope factor (units 0),
// and the units needed with the slope factor a user would set beside them. Every distance's
// searches share each launch round.
#pragma once

#include <functional>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "host/bias/bias_evaluator.h"
#include "host/mts/probe.h"

namespace depthprec {

// The answer of one search, as a magnitude (the row signs it).
struct BiasAnswer {
  std::string verdict = "resolved";  // or unresolvable, clipped, uncovered, non_finite
  double value = std::numeric_limits<double>::quiet_NaN();      // smallest that passed
  double next_down = std::numeric_limits<double>::quiet_NaN();  // largest that failed below it
  int probes = 0;
  bool resolved() const { return verdict == "resolved"; }
};

// Smallest whole number u >= 0 that passes: u = 1, 2, 4, ... until one passes (giving up past
// limit), then bisection on the integers; u = 0 is probed when 1 passes.
class IntegerBiasSearch {
 public:
  explicit IntegerBiasSearch(double limit) : limit_(limit) {}
  bool done() const { return done_; }
  double next() const { return next_; }
  void record(const ProbeResult& r);
  BiasAnswer answer() const;

 private:
  double limit_, next_ = 1, lo_ = -1, hi_ = std::numeric_limits<double>::infinity();
  bool done_ = false;
  int probes_ = 0;
  std::string first_failure_;  // why the first failing probe failed
};

// Smallest real f > 0 that passes, to a relative precision: f = 1, then doubling (to limit) or
// halving (to 1/limit) until the outcome changes, then bisection until (hi - lo) / hi <= rel.
class RealBiasSearch {
 public:
  RealBiasSearch(double limit, double rel) : limit_(limit), rel_(rel) {}
  bool done() const { return done_; }
  double next() const { return next_; }
  void record(const ProbeResult& r);
  BiasAnswer answer() const;

 private:
  double limit_, rel_, next_ = 1, lo_ = 0, hi_ = std::numeric_limits<double>::infinity();
  bool done_ = false;
  int probes_ = 0;
  std::string first_failure_;
};

// A probe passes when the overlay won at every pixel of every frame and nothing was clipped,
// uncovered or non-finite.
bool bias_passes(const ProbeResult& r);

// Everything `bias` reports for one pair: one record per distance (fields in docs/bias.md).
// mts: the pair's MTS at each distance (NaN where it has none), for the comparison column.
std::vector<nlohmann::json> bias_pair_rows(BiasEvaluator& evaluator, const Scene& scene,
                                           const EvalPair& pair, const BiasOptions& options,
                                           const std::vector<double>& distances,
                                           const std::vector<double>& mts);

}  // namespace depthprec
