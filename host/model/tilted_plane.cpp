#include "host/model/tilted_plane.h"

#include <algorithm>
#include <cmath>

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

}  // namespace depthprec
