#include "host/model/tilted_plane.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "host/base/errors.h"
#include "host/model/frame_setup.h"

namespace depthprec {

namespace {

// The columns of R = Rx(x) Ry(y) Rz(z) (the rotation frame_setup.cpp's model() builds, in
// binary64): where the plane's x axis, y axis and normal point.
std::array<Vec3, 3> rotated_axes(const std::array<double, 3>& a) {
  const double cx = std::cos(a[0]), sx = std::sin(a[0]);
  const double cy = std::cos(a[1]), sy = std::sin(a[1]);
  const double cz = std::cos(a[2]), sz = std::sin(a[2]);
  // Rz e_x = (cz, sz, 0), Rz e_y = (-sz, cz, 0), Rz e_z = (0, 0, 1); then Ry, then Rx.
  const auto ry_rx = [&](const Vec3& v) {
    const Vec3 y = {cy * v[0] + sy * v[2], v[1], -sy * v[0] + cy * v[2]};
    return Vec3{y[0], cx * y[1] - sx * y[2], sx * y[1] + cx * y[2]};
  };
  return {ry_rx({cz, sz, 0}), ry_rx({-sz, cz, 0}), ry_rx({0, 0, 1})};
}

constexpr double kDeg = M_PI / 180.0;
// The tilt refused short of the geometric limit, so the far side of the plane stays a bounded
// size (about 57 times the plane's distance at one degree from the limit).
constexpr double kTiltSpareDeg = 1.0;

}  // namespace

std::optional<PlaneRect> view_footprint(const Scene& s, double D,
                                        const std::array<double, 3>& angles) {
  const double ty = std::tan(s.fov_y_deg * kDeg / 2);
  const double tx = ty * static_cast<double>(s.viewport_w) / static_cast<double>(s.viewport_h);
  // The view the plane must cover: the viewport, or the kernel where it reaches past it, widened
  // by plane_margin as the untilted planes are.
  const double half_x =
      s.plane_margin * tx * std::max(1.0, static_cast<double>(s.kernel_w) / s.viewport_w);
  const double half_y =
      s.plane_margin * ty * std::max(1.0, static_cast<double>(s.kernel_h) / s.viewport_h);
  const auto [u, v, n] = rotated_axes(angles);
  const Vec3 centre = {0, 0, -D};
  const double n_centre = dot(n, centre);
  double x0 = INFINITY, x1 = -INFINITY, y0 = INFINITY, y1 = -INFINITY;
  for (const double sx : {-1.0, 1.0})
    for (const double sy : {-1.0, 1.0}) {
      const Vec3 ray = {sx * half_x, sy * half_y, -1};
      const double lambda = n_centre / dot(n, ray);  // the camera sits at the origin
      if (!(lambda > 0) || !std::isfinite(lambda)) return std::nullopt;
      const Vec3 off = {lambda * ray[0] - centre[0], lambda * ray[1] - centre[1],
                        lambda * ray[2] - centre[2]};
      const double a = dot(u, off), b = dot(v, off);
      x0 = std::min(x0, a);
      x1 = std::max(x1, a);
      y0 = std::min(y0, b);
      y1 = std::max(y1, b);
    }
  return PlaneRect{(x0 + x1) / 2, (y0 + y1) / 2, x1 - x0, y1 - y0};
}

namespace {

bool covers_every_frame(const Scene& s, double tilt_deg) {
  std::vector<std::array<double, 3>> angles;
  for (int k = 0; k < s.frames; ++k) angles.push_back(frame_angles(s, k));
  // Worst-case sampling takes orientations anywhere in the rotation cube: its corners are the
  // steepest (docs/mts.md, "The worst case").
  if (s.sampling == Sampling::worst_case) {
    const double r = std::abs(s.rotation_range_deg) * kDeg;
    for (int c = 0; c < 8; ++c) angles.push_back({c & 1 ? r : -r, c & 2 ? r : -r, c & 4 ? r : -r});
  }
  for (std::array<double, 3> a : angles) {
    a[0] += tilt_deg * kDeg;
    // The footprint's existence does not depend on D (it scales with it): any distance decides.
    if (!view_footprint(s, 1.0, a)) return false;
  }
  return true;
}

}  // namespace

double max_tilt_deg(const Scene& s) {
  // Covering fails once the view's far edge runs parallel to the plane; below that it holds,
  // so the limit is found by bisection between 0 (always covered: the view looks at the plane)
  // and 90 degrees (never: edge-on).
  double lo = 0, hi = 90;
  if (!covers_every_frame(s, lo)) return 0;
  while (hi - lo > 1e-3) {
    const double mid = (lo + hi) / 2;
    (covers_every_frame(s, mid) ? lo : hi) = mid;
  }
  return std::max(0.0, std::floor((lo - kTiltSpareDeg) * 10) / 10);
}

void check_tilt(const Scene& s, double tilt_deg) {
  if (tilt_deg == 0) return;
  const double limit = max_tilt_deg(s);
  if (tilt_deg > limit)
    throw InputError(fmt::format(
        "--tilt {}: this scene's planes can be tilted at most {} degrees: steeper, the lower edge "
        "of the view (fov_y_deg {}, widened by plane_margin {}, with rotations of up to {} "
        "degrees) runs nearly parallel to the plane, which would have to reach to infinity to "
        "cover the kernel",
        tilt_deg, limit, s.fov_y_deg, s.plane_margin, s.rotation_range_deg));
}

}  // namespace depthprec
