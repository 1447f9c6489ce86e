#include "host/shadow/shadow_setup.h"

#include <fmt/format.h>

#include <cmath>

#include "host/base/errors.h"
#include "host/model/matrix.h"
#include "host/model/technique.h"

namespace depthprec {

namespace {}  // namespace

const char* to_string(LightType t) {
  return t == LightType::spot ? "spot" : "directional";
}

std::vector<ShadowCascade> spot_rows(const std::vector<double>& distances, double near, double far,
                                     double angle_deg) {
  std::vector<ShadowCascade> out;
  for (double d : distances) {
    ShadowCascade c;
    c.distance = d;
    c.near = near;
    c.far = far;
    c.extent = 2 * d * std::tan(radians(angle_deg) / 2);
    out.push_back(c);
  }
  return out;
}

Technique spot_mapping(const ShadowSetup& s) {
  return s.reversed ? Technique::reversed : Technique::standard;
}

double depth_per_metre(const ShadowSetup& s, size_t cascade) {
  const ShadowCascade& c = s.cascades[cascade];
  if (s.light == LightType::directional) return 1 / c.depth_range();
  // |D'(w)| = f n / ((f - n) w^2) for both mappings
  return c.far * c.near / (c.depth_range() * c.distance * c.distance);
}

double metres_of_depth(const ShadowSetup& s, size_t cascade, double depth) {
  const ShadowCascade& c = s.cascades[cascade];
  if (s.light == LightType::directional) return depth * c.depth_range();
  const TechniqueParams params;
  const Technique t = spot_mapping(s);
  const double d = depth_of_distance(t, c.near, c.far, params, c.distance);
  // Nearer the light by `depth` in window depth: smaller D for standard, larger for reversed.
  const double moved = s.reversed ? std::min(1.0, d + depth) : std::max(0.0, d - depth);
  return c.distance - distance_of_depth<double>(t, c.near, c.far, params, moved);
}

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
  if (!(camera_near > 0) || !std::isfinite(camera_near))
    throw InputError(fmt::format(
        "--camera-near {}: the camera's near plane, where the first cascade starts: metres, more "
        "than 0",
        camera_near));
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
  if (s.cascades.empty())
    throw InputError(s.light == LightType::spot ? "shadow: no receiver distance (give --distances)"
                                                : "shadow: no cascade (give --splits or --extent)");
  if (s.light == LightType::spot) {
    if (!(s.spot_angle > 0 && s.spot_angle < 170))
      throw InputError(fmt::format(
          "--spot-angle {}: the spot light's full cone in degrees, above 0 and below 170",
          s.spot_angle));
    for (size_t i = 0; i < s.cascades.size(); ++i) {
      const ShadowCascade& c = s.cascades[i];
      if (!(c.near > 0) || !(c.far > c.near) || !std::isfinite(c.far))
        throw InputError(fmt::format(
            "spot light: --light-near {} and --light-far {}: metres from the light, 0 < near < "
            "far, finite",
            c.near, c.far));
      if (!(c.distance > c.near && c.distance < c.far))
        throw InputError(fmt::format(
            "--distances: receiver distance {} m lies outside the spot light's near {} and far "
            "{} m",
            c.distance, c.near, c.far));
    }
  }
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

namespace {

// A spot light at `distance` behind the receivers' centre along its axis: rows x, y scaled by the
// cone, w the distance along the axis, z the mapping's A w + C (D = z / w = A + C / w).
void spot_rows_of(const ShadowSetup& s, const ShadowCascade& c, LightMatrix& L) {
  const auto& [right, up, forward] = L.basis;
  for (int j = 0; j < 3; ++j) L.position[j] = L.centre[j] - c.distance * forward[j];
  L.tan_half = std::tan(radians(s.spot_angle) / 2);
  const double n = c.near, f = c.far;
  const double A = s.reversed ? -n / (f - n) : f / (f - n);
  const double C = s.reversed ? f * n / (f - n) : -f * n / (f - n);
  const std::array<double, 3>* axes[2] = {&right, &up};
  for (int r = 0; r < 2; ++r) {
    for (int j = 0; j < 3; ++j) L.m[r][j] = static_cast<float>((*axes[r])[j] / L.tan_half);
    L.m[r][3] = static_cast<float>(-dot(*axes[r], L.position) / L.tan_half);
  }
  for (int j = 0; j < 3; ++j) {
    L.m[2][j] = static_cast<float>(A * forward[j]);
    L.m[3][j] = static_cast<float>(forward[j]);
  }
  L.m[2][3] = static_cast<float>(-A * dot(forward, L.position) + C);
  L.m[3][3] = static_cast<float>(-dot(forward, L.position));
}

}  // namespace

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
  L.position = s.world_position;
  if (s.light == LightType::spot) {
    spot_rows_of(s, c, L);
    return L;
  }
  L.m[3] = {0.0f, 0.0f, 0.0f, 1.0f};
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
