#include "host/shadow/shadow_setup.h"

#include <fmt/format.h>

#include <cmath>

#include "host/base/errors.h"
#include "host/model/matrix.h"

namespace depthprec {

namespace {}  // namespace

ShadowFilter parse_shadow_filter(const std::string& s) {
  if (s == "nearest") return {s, 0.5};
  if (s == "pcf2x2") return {s, 1.0};
  for (const char* prefix : {"pcf", "tent"}) {
    const std::string p(prefix);
    if (s.rfind(p, 0) != 0 || s.size() == p.size()) continue;
    const std::string digits = s.substr(p.size());
    if (digits.find_first_not_of("0123456789") != std::string::npos || digits.size() > 2) break;
    const int n = std::stoi(digits);
    if (n < 3 || n % 2 == 0)
      throw InputError(fmt::format("filter '{}': {}N takes an odd N of at least 3", s, p));
    return {s, p == "pcf" ? (n + 1) / 2.0 : n / 2.0};
  }
  throw InputError(fmt::format(
      "unknown filter '{}': expected nearest, pcf2x2 (hardware bilinear comparison), pcfN (N x N "
      "hardware comparisons one texel apart, N odd: pcf3, pcf5, ...) or tentN (Unity's N x N "
      "tent: tent3, tent5, tent7)",
      s));
}

std::vector<ShadowCascade> cascades_from_splits(const std::vector<double>& splits,
                                                double camera_near, double fov_deg, double aspect,
                                                double caster_padding) {
  if (!(fov_deg > 0 && fov_deg < 180) || !(aspect > 0) || !std::isfinite(aspect))
    throw InputError(fmt::format(
        "--fov {} --aspect {}: the camera's vertical field of view lies in (0, 180) degrees and "
        "its aspect is positive",
        fov_deg, aspect));
  if (!(caster_padding >= 0) || !std::isfinite(caster_padding))
    throw InputError(fmt::format("--caster-padding {}: metres, 0 or more", caster_padding));
  const double ty = std::tan(radians(fov_deg) / 2), tx = ty * aspect;
  const double k2 = tx * tx + ty * ty;  // a slice corner at distance z is z*sqrt(k2) off axis
  std::vector<ShadowCascade> out;
  double a = camera_near;
  for (size_t i = 0; i < splits.size(); ++i) {
    const double b = splits[i];
    if (!(b > a) || !std::isfinite(b))
      throw InputError(fmt::format(
          "--splits: split {} is {} m, not beyond {} m: the splits are camera distances, "
          "increasing, beyond --camera-near",
          i + 1, b, a));
    // The smallest sphere holding both end rectangles: centred on the axis where the two corner
    // distances agree, (a + b)(1 + k2)/2, or at b when that lies beyond the slice.
    const double c = std::min(b, (a + b) * (1 + k2) / 2);
    const double r =
        std::max(std::hypot(c - a, a * std::sqrt(k2)), std::hypot(b - c, b * std::sqrt(k2)));
    ShadowCascade sc;
    sc.extent = 2 * r;
    sc.near = -(r + caster_padding);
    sc.far = r;
    sc.split_near = a;
    sc.split_far = b;
    out.push_back(sc);
    a = b;
  }
  return out;
}

void validate(const ShadowSetup& s) {
  if (s.cascades.empty()) throw InputError("shadow: no cascade (give --splits or --extent)");
  for (size_t i = 0; i < s.cascades.size(); ++i) {
    const ShadowCascade& c = s.cascades[i];
    if (!(c.extent > 0) || !std::isfinite(c.extent))
      throw InputError(fmt::format(
          "cascade {}: extent {} m: a cascade's extent is the side of its square seen from the "
          "light, positive and finite",
          i + 1, c.extent));
    if (!(c.near < c.far) || !std::isfinite(c.near) || !std::isfinite(c.far))
      throw InputError(fmt::format(
          "cascade {}: light-space near {} m and far {} m: near must lie below far, both finite",
          i + 1, c.near, c.far));
  }
  if (s.resolution < 16 || s.resolution > 65536)
    throw InputError(
        fmt::format("--resolution {}: texels per side, from 16 to 65536", s.resolution));
  if (!(s.slope_max >= 0 && s.slope_max < 90))
    throw InputError(fmt::format(
        "--slope-max {}: degrees between a receiver's normal and the light, from 0 to below 90 "
        "(at 90 the receiver is edge-on to the light and no finite bias removes its acne)",
        s.slope_max));
  const std::string& f = s.format.name();
  if (f != "unorm16" && f != "unorm24" && f != "float32")
    throw InputError(fmt::format(
        "--format {}: a shadow map's depth format is unorm16 (D16), unorm24 (D24) or float32 "
        "(D32F)",
        f));
  if (!(s.light_elevation > 0 && s.light_elevation <= 90) || !std::isfinite(s.light_azimuth))
    throw InputError(fmt::format(
        "--light-elevation {}: degrees above the horizon, in (0, 90]; --light-azimuth finite",
        s.light_elevation));
  for (double p : s.world_position)
    if (!std::isfinite(p) || std::fabs(p) > 1e9)
      throw InputError(fmt::format("--world-position: {} m lies beyond 1e9 m", p));
}

LightMatrix light_matrix(const ShadowSetup& s, size_t cascade) {
  const double el = radians(s.light_elevation), az = radians(s.light_azimuth);
  // World y is up; the light travels down toward the ground.
  const std::array<double, 3> forward{-std::cos(el) * std::cos(az), -std::sin(el),
                                      -std::cos(el) * std::sin(az)};
  const std::array<double, 3> ref = std::fabs(forward[1]) > 0.999 ? std::array<double, 3>{0, 0, 1}
                                                                  : std::array<double, 3>{0, 1, 0};
  const std::array<double, 3> right = normalized(cross(forward, ref));
  const std::array<double, 3> up = cross(right, forward);
  const ShadowCascade& c = s.cascades[cascade];
  LightMatrix L;
  L.basis = {right, up, forward};
  L.centre = s.world_position;
  const double sx = 2 / c.extent;
  for (int r = 0; r < 2; ++r) {
    const auto& axis = r == 0 ? right : up;
    for (int j = 0; j < 3; ++j) L.m[r][j] = static_cast<float>(sx * axis[j]);
    L.m[r][3] = static_cast<float>(-sx * dot(axis, L.centre));
  }
  // Window depth (forward . (p - centre) - near) / range, or 1 minus that when reversed.
  const double range = c.depth_range(), sign = s.reversed ? -1 : 1;
  for (int j = 0; j < 3; ++j) L.m[2][j] = static_cast<float>(sign * forward[j] / range);
  const double offset = (-dot(forward, L.centre) - c.near) / range;
  L.m[2][3] = static_cast<float>(s.reversed ? 1 - offset : offset);
  return L;
}

}  // namespace depthprec
