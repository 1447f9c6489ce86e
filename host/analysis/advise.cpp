#include "host/analysis/advise.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <functional>

#include "host/base/errors.h"
#include "host/base/json_number.h"
#include "host/model/frame_setup.h"
#include "host/mts/emulator.h"
#include "host/mts/worst_case.h"

namespace depthprec {

// Under worst-case sampling an answer must also hold this many times farther on its safe side
// (a larger near plane, a smaller far plane): the MTS is not monotone in the planes, and a user
// rounds and adjusts what advise prints.
constexpr double kSafetyFactors[] = {1.0, 1.01, 1.1, 2.0};

void validate(const AdviseRequest& r, const Scene& scene) {
  if (!(r.z_min > 0) || !std::isfinite(r.z_max) || !(r.z_max >= r.z_min))
    throw InputError(
        fmt::format("--range {},{}: the content's distances must be 0 < nearest <= farthest < inf",
                    r.z_min, r.z_max));
  check_content_request(scene, r.z_max, r.separation);
}

void check_content_request(const Scene& scene, double farthest, double separation) {
  if (!(separation > 0) || !std::isfinite(separation))
    throw InputError(
        fmt::format("the separation needed must be positive and finite, not {}", separation));
  for (const auto& pair : scene.evaluate)
    if (has_far_plane(pair.technique) && !(scene.far > farthest))
      throw InputError(
          fmt::format("{}: the far plane ({}) must lie beyond the farthest content ({}); set --far",
                      pair.label(), scene.far, farthest));
}

double near_top(const Scene& scene, const AdviseRequest& r) {
  return nearest_vertex_distance(scene, r.z_min) * (1 - 0x1.0p-10);
}

double tight_far(const Scene& scene, const AdviseRequest& r) {
  return farthest_vertex_distance(scene, r.z_max + r.separation_at(r.z_max)) * (1 + 0x1.0p-10);
}

std::vector<double> advise_distances(const AdviseRequest& r) {
  std::vector<double> zs;
  for (double z = r.z_min; z < r.z_max; z *= 2) zs.push_back(z);
  zs.push_back(r.z_max);
  return zs;
}

Scene with_near(const Scene& scene, double n, double f) {
  nlohmann::json j = scene.json;
  j["near"] = n;
  if (f > 0) j["far"] = f;
  Scene s = scene_from_json(j, scene.source);
  s.name = scene.name;
  return s;
}

namespace {

// Bisection in log scale between a plane that holds (good) and one that fails (bad), in either
// order, until they are within precision of each other: the last good and bad, and a distance
// where bad failed (where, updated when a probe fails).
struct LogBracket {
  double good, bad, where;
};
LogBracket bisect_log(double good, double bad, double where, double precision,
                      const std::function<bool(double, double*)>& holds) {
  while (std::max(good, bad) / std::min(good, bad) > 1 + precision) {
    const double mid = std::sqrt(good * bad);
    double at = 0;
    if (holds(mid, &at))
      good = mid;
    else {
      bad = mid;
      where = at;
    }
  }
  return {good, bad, where};
}

}  // namespace

bool near_holds(OpenClRuntime& rt, const Scene& scene, const EvalPair& pair, const AdviseRequest& r,
                double n, double* worst, double f) {
  const Scene s = with_near(scene, n, f);
  const std::unique_ptr<ProbeEvaluator> ev = emulator(rt, s, pair);
  std::vector<Probe> probes;
  for (double z : advise_distances(r)) probes.push_back({z, r.separation_at(z)});
  const auto results = ev->run(probes);
  for (size_t k = 0; k < results.size(); ++k) {
    const ProbeResult& p = results[k];
    if (p.outcome != Outcome::clean || p.any_uncovered || p.any_clipped || p.any_non_finite) {
      if (worst) *worst = probes[k].z;
      return false;
    }
  }
  return true;
}

bool mts_within(OpenClRuntime& rt, const Scene& scene, const EvalPair& pair, const AdviseRequest& r,
                double n, double f) {
  const Scene s = with_near(scene, n, f);
  for (const MtsRow& row : search_sampled(rt, s, pair, advise_distances(r)))
    if (row.verdict() != Verdict::resolved || row.mts > r.separation_at(row.z)) return false;
  return true;
}

double round_printed(double v, bool up) {
  if (!(v > 0) || !std::isfinite(v)) return v;
  const double unit = std::pow(10.0, std::floor(std::log10(v)) - 3);
  const double q = v / unit;
  // q is within an ulp or so of a whole number when v already prints as itself
  const double whole = std::abs(q - std::round(q)) < 1e-9 * q ? std::round(q)
                       : up                                   ? std::ceil(q)
                                                              : std::floor(q);
  double out = std::strtod(fmt::format("{:.4g}", whole * unit).c_str(), nullptr);
  if (up ? out < v : out > v) out = std::nextafter(out, up ? INFINITY : 0.0);
  return out;
}

bool holds_beyond(OpenClRuntime& rt, const Scene& scene, const EvalPair& pair,
                  const AdviseRequest& r, double n, double f, bool near_side, double limit) {
  for (const double k : kSafetyFactors) {
    const double v = near_side ? n * k : f / k;
    if (near_side ? v > limit : v < limit) break;  // past the last value worth checking
    if (!(near_side ? mts_within(rt, scene, pair, r, v, f) : mts_within(rt, scene, pair, r, n, v)))
      return false;
  }
  return true;
}

static void far_search(OpenClRuntime& rt, const Scene& scene, const EvalPair& pair,
                       const AdviseRequest& r, nlohmann::json& j, double base_far) {
  // With the near plane found, how far out can the far plane go? A farther far plane never gains
  // precision (it spreads the same codes over more depth), so the set-up holds up to some far
  // plane: the largest. (The smallest is the farthest content itself, and never worse.) The
  // near plane was found with base_far, which holds; the search runs from there to a ceiling,
  // and the MTS search confirms the answer as it does the near plane's.
  const double n = j["smallest_near"].get<double>();
  const double ceiling = std::max(scene.far, r.z_max) * r.far_ceiling_ratio;
  int steps = 0;
  const auto holds = [&](double f, double* where) {
    ++steps;
    return near_holds(rt, scene, pair, r, n, where, f);
  };
  double where = 0, f = ceiling, above = 0;
  if (!holds(ceiling, &where)) {
    const LogBracket b = bisect_log(base_far, ceiling, where, r.near_precision, holds);
    f = b.good;
    above = b.bad;
    where = b.where;
  }
  int lowered = 0;
  // base_far needs no check: the near plane's MTS search ran with it.
  while (f > base_far && !mts_within(rt, scene, pair, r, n, f)) {
    above = f;
    f = std::max(base_far, f / (1 + r.near_precision));
    ++lowered;
  }
  // Worst-case sampling: the far plane as printed (rounded down) and the values below it
  // down to base_far must hold; where one does not, the far plane comes in in growing steps.
  if (scene.sampling == Sampling::worst_case && f > base_far) {
    double step = r.near_precision;
    for (f = round_printed(f, false); f > base_far; f = round_printed(f / (1 + step), false)) {
      if (holds_beyond(rt, scene, pair, r, n, f, false, base_far)) break;
      above = f;
      step *= 2;
      ++lowered;
    }
    f = std::max(f, base_far);
  }
  j["largest_far"] = f;
  j["far_holds_to_ceiling"] = above == 0;
  if (above > 0) {
    j["next_far"] = above;
    if (where > 0) j["far_fails_at"] = where;
  }
  j["far_steps"] = steps;
  j["far_lowered_by_mts_check"] = lowered;
}

// The near plane's answer with the far plane at f (0: the scene's): smallest_near and the fields
// that go with it (advise_record).
static nlohmann::json near_answer(OpenClRuntime& rt, const Scene& scene, const EvalPair& pair,
                                  const AdviseRequest& r, double f) {
  nlohmann::json j = nlohmann::json::object();
  int steps = 0;
  double fails_at = 0;
  const auto holds = [&](double n, double* where) {
    ++steps;
    return near_holds(rt, scene, pair, r, n, where, f);
  };
  // A larger near plane never costs precision at a given z (it only clips what is nearer), so
  // each set-up holds from some near plane up: the answer is the smallest. The largest tried
  // keeps the nearest content's tilted planes clear of the near plane.
  double lo = r.z_min * r.near_floor_ratio, hi = near_top(scene, r);
  if (holds(lo, &fails_at)) {
    j["smallest_near"] = lo;
    j["holds_from_floor"] = true;
  } else if (!holds(hi, &fails_at)) {
    j["holds_from_floor"] = false;  // not even next to the content: the set-up cannot meet it
    j["fails_at"] = fails_at;
  } else {
    // lo fails, hi holds: bisect in log(near), keeping a distance where lo failed.
    const LogBracket b = bisect_log(hi, lo, fails_at, r.near_precision, holds);
    j["smallest_near"] = b.good;
    j["next_near"] = b.bad;
    j["fails_at"] = b.where;
    j["holds_from_floor"] = false;
  }
  // The probe at exactly the separation can be clean while a larger one fights (near the MTS,
  // where fights depend on how z + s rounds), so the answer is confirmed by the MTS search itself,
  // as `mts` would run it at that near plane: every checked distance's MTS within the separation.
  // Where one is not, the near plane moves up a step until it is.
  if (j.contains("smallest_near")) {
    double n = j["smallest_near"].get<double>(), below = 0;
    const double top = near_top(scene, r);
    int raised = 0;
    bool within = mts_within(rt, scene, pair, r, n, f);
    while (!within && n < top) {
      below = n;
      n = std::min(top, n * (1 + r.near_precision));
      ++raised;
      within = mts_within(rt, scene, pair, r, n, f);
    }
    // Worst-case sampling: the near plane as printed (rounded up to the digits text shows) must
    // hold, and so must the nearer-safe values beyond it; where one does not, the near plane
    // moves up in growing steps until all do.
    if (within && scene.sampling == Sampling::worst_case) {
      double step = r.near_precision;
      for (n = round_printed(n, true); n <= top; n = round_printed(n * (1 + step), true)) {
        if (holds_beyond(rt, scene, pair, r, n, f, true, top)) break;
        below = n;
        step *= 2;
        ++raised;
      }
      within = n <= top;
    }
    if (within) {
      if (raised) {
        j["next_near"] = below;
        j["holds_from_floor"] = false;
      }
      j["smallest_near"] = n;
    } else {
      j.erase("smallest_near");  // the probes held but the MTS search says otherwise up to z_min
      j.erase("next_near");
    }
    j["raised_by_mts_check"] = raised;
  }
  j["near_steps"] = steps;
  return j;
}

nlohmann::json advise_record(OpenClRuntime& rt, const Scene& scene, const EvalPair& pair,
                             const AdviseRequest& r) {
  nlohmann::json j = pair.fields();
  j.update(near_answer(rt, scene, pair, r, 0));
  double far_used = scene.far;
  // A set-up with a far plane may fail only because the scene's far plane spreads its codes too
  // thin (linear depth in unorm, say): then try the tightest far plane the content allows.
  const double tight = tight_far(scene, r);
  if (!j.contains("smallest_near") && has_far_plane(pair.technique) && tight < scene.far) {
    const nlohmann::json t = near_answer(rt, scene, pair, r, tight);
    const int steps = j["near_steps"].get<int>() + t["near_steps"].get<int>();
    if (t.contains("smallest_near")) {
      j.update(t);
      j.erase("fails_at");
      if (t.contains("fails_at")) j["fails_at"] = t["fails_at"];
      j["far_tightened"] = true;
      far_used = tight;
    }
    j["near_steps"] = steps;
  }
  if (j.contains("smallest_near") && has_far_plane(pair.technique))
    far_search(rt, scene, pair, r, j, far_used);
  j["distances_checked"] = advise_distances(r).size();
  return j;
}

}  // namespace depthprec
