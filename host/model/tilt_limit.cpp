#include "host/model/tilt_limit.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "host/base/errors.h"
#include "host/model/frame_setup.h"
#include "host/model/tilted_plane.h"

namespace depthprec {

namespace {

constexpr double kRadPerDeg = M_PI / 180.0;
// The tilt refused short of the geometric limit, so the far side of the plane stays a bounded
// size (about 57 times the plane's distance at one degree from the limit).
constexpr double kTiltSpareDeg = 1.0;

// Whether the planes tilted tilt_deg have a footprint in every frame of the scene.
bool covers_every_frame(const Scene& s, double tilt_deg) {
  std::vector<std::array<double, 3>> angles;
  for (int k = 0; k < s.frames; ++k) angles.push_back(frame_angles(s, k));
  // Worst-case sampling takes orientations anywhere in the rotation cube: its corners are the
  // steepest (docs/mts.md, "The worst case").
  if (s.sampling == Sampling::worst_case) {
    const double r = std::abs(s.rotation_range_deg) * kRadPerDeg;
    for (int c = 0; c < 8; ++c) angles.push_back({c & 1 ? r : -r, c & 2 ? r : -r, c & 4 ? r : -r});
  }
  for (std::array<double, 3> a : angles) {
    a[0] += tilt_deg * kRadPerDeg;
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
  // The tilted planes are fitted to the perspective view's rays (host/model/tilted_plane.h).
  for (const EvalPair& pair : s.evaluate)
    if (pair.technique == Technique::orthographic)
      throw InputError(fmt::format(
          "--tilt {}: tilted planes are fitted to a perspective view; orthographic takes no tilt "
          "yet",
          tilt_deg));
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
