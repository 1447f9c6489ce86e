#include "host/shadow/shadow_bound.h"

#include <cmath>

#include "host/base/binary32_error.h"
#include "host/model/bound_model.h"

namespace depthprec {

namespace {

using binary32_error::half_ulp;
using binary32_error::kMargin;
using binary32_error::row_rounding;
using binary32_error::RowTerm;

// |computed - exact| of one row of the light matrix times a point whose coordinates are at most
// p[j] in magnitude, in the given arithmetic (any order, fused or not).
double row_error(const binary32_error::Rounding& r, const std::array<float, 4>& m,
                 const std::array<double, 3>& p) {
  return row_rounding(r, {{std::fabs(m[0]) * p[0], false},
                          {std::fabs(m[1]) * p[1], false},
                          {std::fabs(m[2]) * p[2], false},
                          {std::fabs(m[3]), true}});
}

}  // namespace

double shadow_r(const ShadowSetup& s, size_t cascade) {
  const BiasRule rule = bias_rule(s.raster, s.format);
  if (!rule.float_rule) return rule.r_fixed;
  if (s.light == LightType::directional) return 0x1.0p-24;
  const ShadowCascade& c = s.cascades[cascade];
  const double d = depth_of_distance(s.reversed ? Technique::reversed : Technique::standard, c.near,
                                     c.far, TechniqueParams{}, c.distance);
  return rule.r_at(static_cast<float>(d));
}

namespace {

// Spot: the largest sine of a receiver normal's angle to the light's axis, sin(theta + beta).
double spot_normal_sine(const ShadowSetup& s, double theta) {
  const double beta = std::atan(std::sqrt(2.0) * std::tan(radians(s.spot_angle) / 2));
  return std::sin(std::min(theta + beta, M_PI / 2));
}

// The receiver's window-depth gradient per texel at slope theta (radians) along its steepest
// direction: texel / range tan(theta) for a directional light; a spot light's, the largest over
// its cone at the row's distance.
double depth_per_texel(const ShadowSetup& s, size_t cascade, double theta) {
  const ShadowCascade& c = s.cascades[cascade];
  if (s.light == LightType::directional)
    return s.texel(cascade) / c.depth_range() * std::tan(theta);
  // A plane's window depth D = A + C / w is affine in the map: |dD/ds| = |C| |n_xy| / h per unit
  // of tan (s), h the plane's distance from the light along its normal, at least w cos(theta) for
  // a plane through a point at axial distance w whose normal lies within theta of that point's
  // ray; |n_xy| (the normal's part across the axis) at most sin(theta + beta), beta the ray's
  // largest angle to the axis, atan(sqrt(2) tan(half cone)). A texel is 2 tan(half cone) / res.
  const double C = c.far * c.near / c.depth_range();
  const double step = 2 * std::tan(radians(s.spot_angle) / 2) / s.resolution;
  return C * spot_normal_sine(s, theta) * step / (c.distance * std::cos(theta));
}

}  // namespace

double gap_of(const ShadowSetup& s, double metres) {
  return metres * std::cos(radians(s.light_elevation));
}

ShadowBound shadow_bound(const ShadowSetup& s, size_t cascade, const BoundModel& model) {
  const ShadowCascade& c = s.cascades[cascade];
  const LightMatrix L = light_matrix(s, cascade);
  const double theta = radians(s.slope_max);
  ShadowBound b;
  b.texel = s.texel(cascade);
  b.range = c.depth_range();
  ShadowTerms& t = b.terms;
  t.reach = s.filter.reach;

  // Every point the pipeline transforms (caster vertices, receivers, receivers moved along their
  // normal by at most the normal offset) lies in the cascade's box, or within the normal offset
  // of it: per world axis at most |centre| plus the box's half-diagonal plus that offset.
  // A spot light's: within its cone, at most twice the row's distance along its axis (the model's
  // assumption, below).
  const bool spot = s.light == LightType::spot;
  const double half_diagonal =
      spot ? 2 * c.distance * std::sqrt(1 + 2 * L.tan_half * L.tan_half)
           : std::sqrt(0.5 * c.extent * c.extent + std::max(c.near * c.near, c.far * c.far));
  const double offset_reach = 2 * s.filter.reach * b.texel;  // beyond any normal offset used
  std::array<double, 3> p{};
  for (int j = 0; j < 3; ++j)
    p[j] = std::fabs(spot ? L.position[j] : L.centre[j]) + half_diagonal + offset_reach;
  // Spot: x, y and z are divided by w, the distance along the axis, within a factor 2 of the
  // row's for every caster vertex and receiver (the model's assumption; the emulation's lie within
  // a few per cent): a quotient of a value within e of its own by a w within e_w of its own is
  // within (e + |quotient| e_w) / w_lo, plus its own rounding; every quotient here is at most 1 in
  // magnitude (the points lie inside the map, their depths in [0, 1]).
  const double w_lo = c.distance / 2;
  auto divided = [&](double e, double e_w) { return (e + e_w) / w_lo + half_ulp(1.0); };

  binary32_error::Rounding shader;  // the vertex and fragment stages' arithmetic
  shader.bits = model.shader_bits;
  const binary32_error::Rounding fixed;  // the rasteriser's binary32
  const double half_res = s.resolution / 2.0;

  // Caster, vertex stage: x_ndc = row 0 . (p, 1), then x_w = x_ndc * res/2 + res/2 (a product
  // and a sum, each within half an ulp of res), and snapping to 2^-snap_bits of a texel (half a
  // step). Inside a triangle the snapped plane is the exact one displaced by a convex combination
  // of the vertices' displacements: at most this far along each axis.
  const int snap = model.snap_bits > 0 ? model.snap_bits : 8;
  const double xy_rows = std::max(row_error(shader, L.m[0], p), row_error(shader, L.m[1], p));
  const double xy_transform =
      (spot ? divided(xy_rows, row_error(shader, L.m[3], p)) : xy_rows) * half_res +
      2 * half_ulp(s.resolution);
  t.caster_xy = (xy_transform + std::ldexp(1.0, -snap - 1)) * kMargin;

  // Caster depth: each vertex's D = row 2 . (p, 1) within row_error; inside the triangle the
  // interpolation weights are non-negative and sum to 1, so the vertices' errors reach the texel
  // at most as large. The interpolation itself (weights from exact fixed-point edge functions,
  // one division, the weighted sum) rounds at the depth's magnitude, at most 1: the model's value
  // and reach roundings plus its reciprocal's, and its own relative tolerance where it has one.
  t.caster_vertex = spot ? divided(row_error(shader, L.m[2], p), row_error(shader, L.m[3], p))
                         : row_error(shader, L.m[2], p);
  t.interpolation = ((model.value_roundings + model.reach_roundings + model.reciprocal_half_ulps) *
                         half_ulp(1.0) +
                     model.interpolation_relative) *
                    kMargin;

  // Storage: a unorm code up to the conversion's width below d (2^n - 1) codes, then the code
  // read back as binary32 for the comparison (exact up to 24 bits, half an ulp of 1 above); a
  // float32 buffer stores the binary32 depth itself.
  if (s.format.is_unorm()) {
    const unsigned bits = s.format.bits();
    const double width = model.unorm_width[unorm_entry(bits)];
    t.storage =
        width / (std::ldexp(1.0, static_cast<int>(bits)) - 1) + (bits > 24 ? half_ulp(1.0) : 0.0);
  }

  // Receiver: its world position is a varying interpolated by the camera's rasteriser (the same
  // roundings as the caster's depth, at each coordinate's magnitude), moved along its normal
  // (o n_j, then the sum: two roundings at most |p_j| + o), then transformed by the same rows.
  std::array<double, 3> dp{};
  for (int j = 0; j < 3; ++j)
    dp[j] = (model.value_roundings + model.reach_roundings + model.reciprocal_half_ulps) *
                shader.half_ulp(p[j]) +
            model.interpolation_relative * p[j] + 2 * shader.half_ulp(p[j]);
  auto moved = [&](int row) {
    double e = 0;
    for (int j = 0; j < 3; ++j) e += std::fabs(L.m[row][j]) * dp[j];
    return (e + row_error(shader, L.m[row], p)) * kMargin;
  };
  t.receiver = spot ? divided(moved(2), moved(3)) * kMargin : moved(2);
  const double receiver_rows =
      spot ? divided(std::max(moved(0), moved(1)), moved(3)) : std::max(moved(0), moved(1));
  t.receiver_xy = (receiver_rows * half_res + 2 * half_ulp(s.resolution)) * kMargin;

  // The recipes. A receiver at slope theta whose steepest direction makes angle phi with the
  // map's axes reads texels up to reach' texels away per axis: their depths lie below its own by
  // up to g reach' (|cos phi| + |sin phi|), g = depth_per_texel; at phi = 45 degrees,
  // sqrt(2) g reach'.
  const double rho = t.lateral_reach();
  const double g = depth_per_texel(s, cascade, theta);
  const double sin_n = spot_normal_sine(s, theta);
  const double E = t.depth_errors();
  const double r = shadow_r(s, cascade);
  const double grow = (1 + kBiasArithmetic) * kMargin;
  b.constant = (std::sqrt(2.0) * rho * g + E) * grow;
  b.constant_units = b.constant / r;
  b.constant_metres = metres_of_depth(s, cascade, b.constant);
  b.error_constant = E * grow;
  b.error_units = b.error_constant / r;
  b.error_metres = metres_of_depth(s, cascade, b.error_constant);
  // Slope: factor m covers g reach' (|cos| + |sin|) where m = g max(|cos|, |sin|) (or g for the
  // sqrt form): the ratio is at most 2 (sqrt(2)), at phi = 45 degrees, for every theta.
  const double ratio = s.raster.slope == SlopeForm::sqrt ? std::sqrt(2.0) : 2.0;
  b.slope_factor = ratio * rho * grow / (1 - kSlopeRelativeError);
  // Normal offset o: the moved point lies o / cos(theta) above the plane along the light, which
  // must cover sqrt(2) reach' texel tan(theta): o = sqrt(2) reach' texel sin(theta).
  b.normal_metres = std::sqrt(2.0) * rho * b.texel * std::sin(theta) * grow;
  if (spot) {
    // The moved point P' lies nearer the light than the plane's point Q on its ray: in 1/w by
    // o / ((h - o) w_Q), against the texels' drop sqrt(2) reach' |n_xy| step / h (h the plane's
    // distance from the light along its normal, |n_xy| <= sin_n): o w_Q-proportional, with
    // w_Q <= w / (1 - o / (w cos theta)). So o (1 - o / c) >= K, c = w cos(theta), met by
    // o = K / (1 - 2K / c) while c >= 4K.
    const double K =
        std::sqrt(2.0) * rho * c.distance * sin_n * 2 * L.tan_half / s.resolution * grow;
    const double cc = c.distance * std::cos(theta);
    b.normal_metres = cc >= 4 * K ? K / (1 - 2 * K / cc) : NAN;
  }
  b.normal_texels = b.normal_metres / b.texel;

  // Gaps: a wall facing the light makes the elevation's angle with it, so its slope bias is
  // factor * texel / range * tan(elevation) at the worst azimuth; the normal offset moves the
  // ground's lookup up along the wall, still behind it, and costs no gap.
  const double elevation = radians(s.light_elevation);
  b.gap_constant = gap_of(s, b.constant_metres);
  const double wall_slope_depth =
      s.light_elevation < 90 ? b.slope_factor * b.texel * std::tan(elevation) : 0.0;
  b.gap_slope = s.light_elevation < 90 ? gap_of(s, wall_slope_depth + b.error_metres) : 0.0;
  b.gap_normal = gap_of(s, b.error_metres);
  return b;
}

}  // namespace depthprec
