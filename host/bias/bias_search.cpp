#include "host/bias/bias_search.h"

#include <fmt/format.h>

#include <cmath>

#include "host/base/binary32_error.h"
#include "host/base/json_number.h"
#include "host/model/resolve.h"
#include "host/mts/mts_bound.h"

namespace depthprec {

namespace {

std::string failure_of(const ProbeResult& r) {
  if (r.outcome == Outcome::non_finite || r.any_non_finite) return "non_finite";
  if (r.outcome == Outcome::clipped || r.any_clipped) return "clipped";
  if (r.any_uncovered) return "uncovered";
  return "";  // a fight: the bias was too small
}

}  // namespace

bool bias_passes(const ProbeResult& r) {
  return r.outcome == Outcome::clean && !r.any_clipped && !r.any_uncovered && !r.any_non_finite;
}

bool BiasSearch::record_opening(const ProbeResult& r) {
  ++probes_;
  const bool pass = bias_passes(r);
  if (!pass && probes_ == 1) first_failure_ = failure_of(r);
  if (pass) {
    hi_ = next_;
  } else {
    lo_ = std::max(lo_, next_);
    failed_ = true;
  }
  if (hi_ < std::numeric_limits<double>::infinity()) return false;
  if (next_ * 2 > limit_)
    done_ = true;
  else
    next_ *= 2;
  return true;
}

BiasAnswer BiasSearch::answer() const {
  BiasAnswer a;
  a.probes = probes_;
  if (hi_ == std::numeric_limits<double>::infinity()) {
    a.verdict = first_failure_.empty() ? "unresolvable" : first_failure_;
    return a;
  }
  a.value = hi_;
  if (failed_) a.next_down = lo_;
  return a;
}

void IntegerBiasSearch::record(const ProbeResult& r) {
  if (record_opening(r)) return;
  if (!failed_) {  // 1 passed: is no bias at all enough?
    next_ = 0;
    if (hi_ == 0) done_ = true;
    return;
  }
  if (hi_ - lo_ <= 1) {
    done_ = true;
    return;
  }
  next_ = std::floor((lo_ + hi_) / 2);
}

void RealBiasSearch::record(const ProbeResult& r) {
  if (record_opening(r)) return;
  if (!failed_) {  // every probe so far passed: halve toward the floor
    if (next_ / 2 < 1 / limit_) {
      done_ = true;
      return;
    }
    next_ /= 2;
    return;
  }
  if ((hi_ - lo_) / hi_ <= rel_) {
    done_ = true;
    return;
  }
  next_ = 0.5 * (lo_ + hi_);
}

namespace {

// The slope factor is searched to 1/64 (1.6 %): finer than anyone sets it.
constexpr double kFactorPrecision = 1.0 / 64;
// Largest slope factor tried: beyond it the slope term is not what separates the planes (a
// camera-facing plane's slope is all but 0).
constexpr double kFactorLimit = 1 << 24;

// The units search's limit: once r * units passes the whole depth range, more cannot help.
double units_limit(const BiasRule& rule) {
  return rule.float_rule ? std::ldexp(1.0, 25) : std::ceil(2 / rule.r_fixed);
}

}  // namespace

std::vector<BiasAnswers> search_bias(BiasEvaluator& evaluator, const Scene& scene,
                                     const EvalPair& pair, const BiasOptions& options,
                                     const std::vector<double>& distances, unsigned kinds) {
  const BiasRule rule = bias_rule(options, scene.storage_format(pair));
  const double sign = bias_sign(scene, pair);
  const size_t n = distances.size();
  std::vector<IntegerBiasSearch> units(n, IntegerBiasSearch(units_limit(rule))),
      with_factor(n, IntegerBiasSearch(units_limit(rule)));
  std::vector<RealBiasSearch> factor(n, RealBiasSearch(kFactorLimit, kFactorPrecision));
  std::vector<BiasAnswers> out(n);
  const bool want_units = kinds & kBiasUnits, want_factor = kinds & kBiasFactor,
             want_with = (kinds & kBiasWithFactor) && options.set_factor > 0;
  // A round: the next probe of every search not done, all in one evaluator call.
  while (true) {
    std::vector<BiasProbe> probes;
    std::vector<std::pair<size_t, int>> owner;  // (distance, search)
    for (size_t k = 0; k < n; ++k) {
      if (want_units && !units[k].done()) {
        probes.push_back({distances[k], sign * units[k].next(), 0});
        owner.push_back({k, 0});
      }
      if (want_factor && !factor[k].done()) {
        probes.push_back({distances[k], 0, sign * factor[k].next()});
        owner.push_back({k, 1});
      }
      if (want_with && !with_factor[k].done()) {
        probes.push_back({distances[k], sign * with_factor[k].next(), sign * options.set_factor});
        owner.push_back({k, 2});
      }
    }
    if (probes.empty()) break;
    const std::vector<ProbeResult> results = evaluator.run(probes);
    for (size_t i = 0; i < probes.size(); ++i) {
      const auto [k, which] = owner[i];
      out[k].seconds += results[i].seconds;
      if (which == 0)
        units[k].record(results[i]);
      else if (which == 1)
        factor[k].record(results[i]);
      else
        with_factor[k].record(results[i]);
    }
  }
  for (size_t k = 0; k < n; ++k) {
    if (want_units) out[k].units = units[k].answer();
    if (want_factor) out[k].factor = factor[k].answer();
    if (want_with) out[k].with_factor = with_factor[k].answer();
    out[k].orientations = static_cast<uint64_t>(scene.frames);
  }
  return out;
}

BiasProbe bias_probe(const Scene& scene, const EvalPair& pair, const BiasOptions& options,
                     unsigned kind, double z, double value) {
  const double sign = bias_sign(scene, pair);
  if (kind == kBiasUnits) return {z, sign * value, 0};
  if (kind == kBiasFactor) return {z, 0, sign * value};
  return {z, sign * value, sign * options.set_factor};
}

std::vector<nlohmann::json> bias_pair_rows(BiasEvaluator& evaluator, const Scene& scene,
                                           const EvalPair& pair, const BiasOptions& options,
                                           const std::vector<double>& distances,
                                           const std::vector<double>& mts) {
  return bias_rows(scene, pair, options, evaluator.source(), distances,
                   search_bias(evaluator, scene, pair, options, distances), mts);
}

namespace {

// The constant bias under the guaranteed MTS's model (host/mts/mts_bound.h coplanar_spread): the
// two surfaces' stored depths lie within the spread of each other at every kernel pixel, in every
// orientation, on every implementation of the model, so an offset beyond the spread and its own
// roundings (r units, and its sum with the depth: half an ulp of each) keeps B in front
// everywhere. r is the smallest the plane's depths give (the float rule's r grows with the
// exponent of the primitive's largest depth). Null where the model has no bound or the clamp
// stops the offset short of it. A slope factor has no such bound: a plane facing the eye has no
// slope to scale.
nlohmann::json units_under_bound(const Scene& scene, const EvalPair& pair, const BiasRule& rule,
                                 const BiasOptions& options, double z) {
  const CoplanarSpread cs = coplanar_spread(scene, pair, z);
  if (std::isnan(cs.spread)) return nullptr;
  const double r = rule.float_rule ? rule.r_at(static_cast<float>(cs.depth_min)) : rule.r_fixed;
  const double need = cs.spread + 2 * binary32_error::half_ulp(cs.depth_max);
  const double units = std::floor(need / r * (1 + 0x1.0p-20)) + 1;
  const double sign = bias_sign(scene, pair);
  if (clamp_binds(options.clamp, static_cast<int>(sign)) && options.clamp != 0 &&
      std::fabs(options.clamp) <= need)
    return nullptr;
  return sign * units;
}

}  // namespace

std::vector<nlohmann::json> bias_rows(const Scene& scene, const EvalPair& pair,
                                      const BiasOptions& options, RowSource source,
                                      const std::vector<double>& distances,
                                      const std::vector<BiasAnswers>& answers,
                                      const std::vector<double>& mts) {
  const BiasRule rule = bias_rule(options, scene.storage_format(pair));
  const double sign = bias_sign(scene, pair);
  const size_t n = distances.size();
  std::vector<nlohmann::json> rows;
  for (size_t k = 0; k < n; ++k) {
    const double z = distances[k];
    const BiasAnswer &u = answers[k].units, &f = answers[k].factor;
    nlohmann::json j = pair.fields();
    j["z"] = z;
    j["verdict"] = u.verdict;
    const auto signed_or_null = [sign](double v) -> nlohmann::json {
      return std::isnan(v) ? nlohmann::json(nullptr) : nlohmann::json(v == 0 ? 0.0 : sign * v);
    };
    j["units"] = signed_or_null(u.value);
    j["units_fails"] = signed_or_null(u.next_down);
    j["factor"] = signed_or_null(f.value);
    // The constant term found an offset that separates the planes, and no slope factor up to
    // 2^24 reached it: the slope is all but 0 (at tilt 0 the planes face the camera; far away
    // their binary32 depths no longer differ across a triangle). Nothing for the factor to scale
    // is no failure of the bias, and says so rather than "unresolvable".
    j["factor_verdict"] = f.verdict == "unresolvable" && u.resolved() && !std::isnan(u.value)
                              ? std::string(kNoSlope)
                              : f.verdict;
    if (options.set_factor > 0) {
      const BiasAnswer& s = answers[k].with_factor;
      j["set_factor"] = sign * options.set_factor;
      j["set_units"] = signed_or_null(s.value);
      j["set_verdict"] = s.verdict;
    }
    // What the constant bias amounts to at z: the offset r * units in window depth (r of z's own
    // binade for float storage), signed as the units and clamped as the API clamps it, and the
    // eye distance it moves a fragment toward the camera. Rendered rows leave them out: their r
    // is the driver's.
    if (source == RowSource::emulated) {
      j["r"] = rule.r_text;
      j["offset"] = nullptr;
      j["eye_separation"] = nullptr;
      if (u.resolved()) {
        const ResolveSetup setup =
            mapping_at(pair.technique, scene.near, scene.far, scene.params, z);
        const double d = depth_of_distance(setup.technique, setup.near, setup.far, setup.params, z);
        const double offset =
            clamped(sign * rule.r_at(static_cast<float>(d)) * u.value, options.clamp);
        const double moved = d + offset;
        j["offset"] = offset == 0 ? 0.0 : offset;
        // Past the depth range the offset has moved the fragment beyond the near plane (or
        // far): every distance nearer than z, an infinite separation.
        j["eye_separation"] =
            json_number((moved >= 0 && moved <= 1) ? distance_gap(setup, d, moved)
                                                   : std::numeric_limits<double>::infinity());
      }
    }
    if (source == RowSource::emulated)
      j["units_bound"] = units_under_bound(scene, pair, rule, options, z);
    j["mts"] = std::isnan(mts[k]) ? nlohmann::json(nullptr) : nlohmann::json(mts[k]);
    j["probes"] = u.probes + f.probes + answers[k].with_factor.probes;
    j["seconds"] = answers[k].seconds;
    if (scene.sampling == Sampling::worst_case) {
      j["orientations"] = answers[k].orientations;
      j["convergence"] = json_number(answers[k].convergence);
    }
    rows.push_back(j);
  }
  return rows;
}

}  // namespace depthprec
