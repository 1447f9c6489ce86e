#include "host/analysis/world_sweep.h"

#include <fmt/format.h>

#include <cmath>

#include "host/analysis/advise.h"
#include "host/base/errors.h"
#include "host/mts/worst_case.h"

namespace depthprec {

namespace {

std::array<double, 3> unit(const std::array<double, 3>& d) {
  const double n = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  return {d[0] / n, d[1] / n, d[2] / n};
}

// The MTS at eye distance z with the world at distance R along the direction (infinite when the
// search does not resolve it), and how many searches ran.
struct WorldProbe {
  const WorldRequest& r;
  OpenClRuntime& rt;
  const Scene& scene;
  const EvalPair& pair;
  Transform t;
  int searches = 0;

  double mts_at(double R) {
    const auto d = unit(r.direction);
    const Scene s = with_world(scene, {R * d[0], R * d[1], R * d[2]}, t);
    ++searches;
    const std::vector<MtsRow> rows = search_sampled(rt, s, pair, {r.z});
    const MtsRow& row = rows.at(0);
    return row.verdict() == Verdict::resolved ? row.mts : INFINITY;
  }
};

nlohmann::json sweep(WorldProbe& probe) {
  const WorldRequest& r = probe.r;
  nlohmann::json j;
  const double origin = probe.mts_at(0);
  j["mts_at_origin"] = origin;
  const auto holds = [&](double mts) { return mts <= r.separation; };
  if (!holds(origin)) {
    j["holds_to_limit"] = false;
    j["searches"] = probe.searches;
    return j;
  }
  const double limit = world_distance_limit(r);
  double good = 0, good_mts = origin, bad = 0, bad_mts = 0;
  // Powers of two up to the limit, then the limit itself.
  for (double R = 1; bad == 0 && good < limit; R = std::min(2 * R, limit)) {
    const double m = probe.mts_at(R);
    if (!holds(m)) {
      bad = R;
      bad_mts = m;
      break;
    }
    good = R;
    good_mts = m;
  }
  if (bad > 0 && good > 0) {
    while (bad / good > 1 + r.precision) {
      const double mid = std::sqrt(good * bad);
      const double m = probe.mts_at(mid);
      if (holds(m)) {
        good = mid;
        good_mts = m;
      } else {
        bad = mid;
        bad_mts = m;
      }
    }
  }
  j["largest_world_distance"] = good;
  j["mts_there"] = good_mts;
  j["holds_to_limit"] = bad == 0;
  if (bad > 0) {
    j["fails_at"] = bad;
    j["mts_at_fail"] = bad_mts;
  }
  j["searches"] = probe.searches;
  return j;
}

}  // namespace

void validate(const WorldRequest& r, const Scene& scene) {
  if (!(r.z > 0) || !std::isfinite(r.z))
    throw InputError(fmt::format("--distance {}: the content's eye distance must be > 0", r.z));
  const auto& d = r.direction;
  if (!(d[0] * d[0] + d[1] * d[1] + d[2] * d[2] > 0) || !std::isfinite(d[0] + d[1] + d[2]))
    throw InputError(
        fmt::format("--direction {},{},{}: must be a finite, non-zero vector", d[0], d[1], d[2]));
  if (r.transforms.empty()) throw InputError("--transforms: name at least one transform");
  check_content_request(scene, r.z, r.separation);
}

Scene with_world(const Scene& scene, const std::array<double, 3>& world_position, Transform t) {
  nlohmann::json j = scene.json;
  j["world_position"] = world_position;
  j["pipeline"]["transform"] = to_string(t);
  Scene s = scene_from_json(j, scene.source);
  s.name = scene.name;
  return s;
}

double world_distance_limit(const WorldRequest& r) {
  const auto d = unit(r.direction);
  const double m = std::max({std::abs(d[0]), std::abs(d[1]), std::abs(d[2])});
  return kMaxWorldCoordinate / m;
}

nlohmann::json world_record(OpenClRuntime& rt, const Scene& scene, const EvalPair& pair,
                            const WorldRequest& r) {
  nlohmann::json rec = pair.fields();
  for (const Transform t : r.transforms) {
    WorldProbe probe{r, rt, scene, pair, t};
    rec["transforms"][to_string(t)] = sweep(probe);
  }
  return rec;
}

}  // namespace depthprec
