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

#include "host/bias/bias_probe.h"
#include "host/bias/bias_rule.h"
#include "host/model/scene.h"
#include "host/mts/probe.h"

namespace depthprec {

// factor_verdict of a row whose slope factor alone found nothing to scale: the units alone
// resolve it, no factor up to the search's limit does (docs/bias.md, "Verdicts").
constexpr const char* kNoSlope = "no_slope";

// The answer of one search, as a magnitude (the row signs it).
struct BiasAnswer {
  std::string verdict = "resolved";  // or unresolvable, clipped, uncovered, non_finite
  double value = std::numeric_limits<double>::quiet_NaN();      // smallest that passed
  double next_down = std::numeric_limits<double>::quiet_NaN();  // largest that failed below it
  int probes = 0;
  bool resolved() const { return verdict == "resolved"; }
};

// What both searches share: the bracket [lo, hi] of the largest value that failed and the
// smallest that passed, and the opening phase: 1, 2, 4, ... until one passes (giving up past
// limit). Each search decides what follows.
class BiasSearch {
 public:
  explicit BiasSearch(double limit) : limit_(limit) {}
  bool done() const { return done_; }
  double next() const { return next_; }
  BiasAnswer answer() const;

 protected:
  // Records the probe at next(); true when it decided the step (still doubling, or done).
  bool record_opening(const ProbeResult& r);

  double limit_, next_ = 1, lo_ = 0, hi_ = std::numeric_limits<double>::infinity();
  bool done_ = false, failed_ = false;  // failed_: some probe failed (lo_ is one)
  int probes_ = 0;
  std::string first_failure_;  // why the first probe failed, when it did
};

// Smallest whole number u >= 0 that passes: the opening, then bisection on the integers; u = 0
// is probed when 1 passes.
class IntegerBiasSearch : public BiasSearch {
 public:
  using BiasSearch::BiasSearch;
  void record(const ProbeResult& r);
};

// Smallest real f > 0 that passes, to a relative precision: the opening, or halving (to 1/limit)
// when 1 passes, then bisection until (hi - lo) / hi <= rel.
class RealBiasSearch : public BiasSearch {
 public:
  RealBiasSearch(double limit, double rel) : BiasSearch(limit), rel_(rel) {}
  void record(const ProbeResult& r);

 private:
  double rel_;
};

// A probe passes when the overlay won at every pixel of every frame and nothing was clipped,
// uncovered or non-finite.
bool bias_passes(const ProbeResult& r);

// The searches of one distance: the smallest constant bias, slope factor, and units with the set
// factor (left as constructed where not searched), their evaluators' seconds, the orientations they
// rest on and, under worst-case sampling, the largest relative rise of the three in the last round.
struct BiasAnswers {
  BiasAnswer units, factor, with_factor;
  double seconds = 0;
  uint64_t orientations = 0;
  double convergence = 0;
  BiasAnswer& of(unsigned kind) { return kind == 1 ? units : kind == 2 ? factor : with_factor; }
};
// The searches, as bits: run_bias's three kinds.
constexpr unsigned kBiasUnits = 1, kBiasFactor = 2, kBiasWithFactor = 4;

// Runs the searches `kinds` asks for (with_factor only with a set factor) at every distance, all
// distances' probes sharing each launch round.
std::vector<BiasAnswers> search_bias(BiasEvaluator& evaluator, const Scene& scene,
                                     const EvalPair& pair, const BiasOptions& options,
                                     const std::vector<double>& distances,
                                     unsigned kinds = kBiasUnits | kBiasFactor | kBiasWithFactor);

// The probe of search `kind` at magnitude `value` (signed as the pair's bias).
BiasProbe bias_probe(const Scene& scene, const EvalPair& pair, const BiasOptions& options,
                     unsigned kind, double z, double value);

// One record per distance from the answers (fields in docs/bias.md). mts: the pair's MTS at each
// distance (NaN where it has none), for the comparison column.
std::vector<nlohmann::json> bias_rows(const Scene& scene, const EvalPair& pair,
                                      const BiasOptions& options, RowSource source,
                                      const std::vector<double>& distances,
                                      const std::vector<BiasAnswers>& answers,
                                      const std::vector<double>& mts);

// Everything `bias` reports for one pair: one record per distance (fields in docs/bias.md).
// mts: the pair's MTS at each distance (NaN where it has none), for the comparison column.
std::vector<nlohmann::json> bias_pair_rows(BiasEvaluator& evaluator, const Scene& scene,
                                           const EvalPair& pair, const BiasOptions& options,
                                           const std::vector<double>& distances,
                                           const std::vector<double>& mts);

}  // namespace depthprec
