#include "host/analysis/advise_bound.h"

#include <algorithm>
#include <cmath>

#include "host/model/technique.h"
#include "host/mts/mts_bound.h"

namespace depthprec {

namespace {

// The bound holds at v and beyond it on the safe side (near: v 1.01, 1.1, 2 up to limit; far:
// divided by them down to limit).
bool holds_onwards(const std::function<bool(double)>& holds, double v, bool up, double limit) {
  for (const double k : {1.0, 1.01, 1.1, 2.0}) {
    const double x = up ? v * k : v / k;
    if (up ? x > limit : x < limit) break;
    if (!holds(x)) return false;
  }
  return true;
}

// The value where `holds` turns: bisection in log scale from a value that holds (good) to one
// that fails (bad), to precision, then moved to the digits text prints and onwards (up: a near
// plane, rounded up; else a far plane, rounded down) until it holds there and beyond.
double turning_point(double good, double bad, double precision, bool up, double limit,
                     const std::function<bool(double)>& holds) {
  while (std::max(good, bad) / std::min(good, bad) > 1 + precision) {
    const double mid = std::sqrt(good * bad);
    (holds(mid) ? good : bad) = mid;
  }
  double step = precision;
  for (double v = round_printed(good, up);;
       v = round_printed(up ? v * (1 + step) : v / (1 + step), up)) {
    if (up ? v > limit : v < limit) return good;
    if (holds_onwards(holds, v, up, limit)) return v;
    step *= 2;
  }
}

}  // namespace

bool bound_within(const Scene& scene, const EvalPair& pair, const AdviseRequest& r, double n,
                  double f) {
  const Scene s = with_near(scene, n, f);
  for (const double z : advise_distances(r)) {
    const MtsBound b = mts_bound(s, pair, z);
    if (!(b.s <= r.separation_at(z))) return false;
  }
  return true;
}

nlohmann::json bound_answer(const Scene& scene, const EvalPair& pair, const AdviseRequest& r) {
  nlohmann::json j = nlohmann::json::object();
  const double floor = r.z_min * r.near_floor_ratio, top = near_top(scene, r);
  const auto near_ok = [&](double n) { return bound_within(scene, pair, r, n); };
  double n = 0;
  if (near_ok(floor)) {
    n = floor;
    j["near_bound_from_floor"] = true;
  } else if (near_ok(top)) {
    n = turning_point(top, floor, r.near_precision, true, top, near_ok);
    j["near_bound_from_floor"] = false;
  } else {
    j["near_bound_from_floor"] = false;
    return j;
  }
  j["near_bound"] = n;
  if (!has_far_plane(pair.technique)) return j;
  const double base = scene.far, ceiling = std::max(scene.far, r.z_max) * r.far_ceiling_ratio;
  const auto far_ok = [&](double f) { return bound_within(scene, pair, r, n, f); };
  if (far_ok(ceiling)) {
    j["far_bound"] = ceiling;
    j["far_bound_to_ceiling"] = true;
  } else {
    j["far_bound"] = turning_point(base, ceiling, r.near_precision, false, base, far_ok);
    j["far_bound_to_ceiling"] = false;
  }
  return j;
}

}  // namespace depthprec
