#include "host/analysis/world_bound.h"

#include <algorithm>
#include <cmath>

#include "host/mts/mts_bound.h"

namespace depthprec {

namespace {

// mts_bound with camera and planes at world distance R along the request's direction.
double bound_at(const Scene& scene, const EvalPair& pair, const WorldRequest& r, Transform t,
                double R) {
  double len = 0;
  for (const double c : r.direction) len += c * c;
  len = std::sqrt(len);
  std::array<double, 3> at{};
  for (int i = 0; i < 3; ++i) at[i] = R * r.direction[i] / len;
  return mts_bound(with_world(scene, at, t), pair, r.z).s;
}

}  // namespace

nlohmann::json world_bound(const Scene& scene, const EvalPair& pair, const WorldRequest& r,
                           Transform t) {
  nlohmann::json j = nlohmann::json::object();
  const double origin = bound_at(scene, pair, r, t, 0);
  j["mts_bound_at_origin"] = origin;
  if (!(origin <= r.separation)) return j;
  const double limit = world_distance_limit(r);
  // R per unit of the largest coordinate: along (1, 1, 1) a coordinate reaches 2^k at
  // R = 2^k sqrt(3), where the sampled limit's binades begin too.
  double len = 0, largest = 0;
  for (const double c : r.direction) {
    len += c * c;
    largest = std::max(largest, std::fabs(c));
  }
  const double per_coordinate = std::sqrt(len) / largest;
  // Binade [C, 2C) of the largest coordinate: the coordinates' magnitudes lie within one binade
  // each (or reach the next one, when the plane's centre offset adds to them), so the bound at the
  // binade's top, just below 2C, is the largest in it; the plane's own offsets (z, its reach)
  // are why the first binades are taken from 2^-10 of z on.
  for (double R =
           std::ldexp(1.0, static_cast<int>(std::floor(std::log2(r.z))) - 10) * per_coordinate;
       R < limit; R *= 2) {
    const double top = std::nextafter(std::min(2 * R, limit), 0.0);
    if (!(bound_at(scene, pair, r, t, top) <= r.separation) ||
        !(bound_at(scene, pair, r, t, R) <= r.separation)) {
      j["limit_bound"] = R;
      j["limit_bound_to_limit"] = false;
      return j;
    }
  }
  j["limit_bound"] = limit;
  j["limit_bound_to_limit"] = true;
  return j;
}

}  // namespace depthprec
