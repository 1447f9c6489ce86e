#include "host/mts/bound_plane.h"

#include <algorithm>
#include <cmath>

namespace depthprec::bound {

namespace {

namespace b32 = binary32_error;
constexpr double kU = 0x1.0p-24;

struct Clip4 {
  double x = 0, y = 0, z = 0, w = 0;
};

// Half an ulp of the fixed-function stages (binary32) and of the shaders (the model's precision).
double hu(const RowModel& m, double magnitude) {
  return m.rounding.half_ulp(magnitude);
}
double hs(const RowModel& m, double magnitude) {
  return m.shader_rounding.half_ulp(magnitude);
}

// (1) The vertex stage. A vertex is M v, v = (x, y, 0, 1) with |x|, |y| <= 0.5, M = T R~ S the
// application's model-view: columns R~ side (|M_r0|, |M_r1| <= side for rows 0, 1 and
// side sqrt(2) sin r for row 2), translation (0, 0, -D) at the world origin. The exact geometry is
// the planes built from the same R~ at D_A and D_B (parallel, B = A scaled about the eye), so what
// this bounds is how far each computed eye coordinate lies from that geometry's:
// - the columns' entries, R~ side rounded once each (a binary32 product, or binary64 rounded):
//   half_ulp(column) each, times |x|, |y| <= 0.5;
// - the translation: exact at the origin (D is the binary32 distance, geometry_distance); away
//   from it rounded once (absolute: world + centre; camera_relative: a binary64 difference first,
//   within 2^-52 of its operands);
// - the row itself, ((m0 x + m1 y) + m2 0) + m3, in any association, fused or not (row_rounding);
// - under the absolute transform away from the origin, the view's translation, rounded once (the
//   same value for both planes, counted for each all the same), and its sum with the model's
//   product, which rounds at the eye coordinate's magnitude (the world's cancels).
// relative_to_eye forms the eye offset in emulated double-single arithmetic from binary64 world
// positions: within 4 u of the offset and 2^-46 of the world coordinate, doubled here; and each
// coordinate's low part, x less a multiple of 65536 (Cesium's split, interface/relative_to_eye.h),
// is stored as a binary32, below min(65536, |x|): the vertex's and the eye's each round once
// there, and the shader's difference of the two at most that magnitude (2^-8 spacing from 32768
// on: far from the origin this is most of the vertex's error). Premultiplied matrices have no eye
// stage: only binary32 M~'s entries carry over.
std::array<double, 3> eye_error(const RowModel& m, const PlaneGeometry& g) {
  const Scene& s = *m.scene;
  const Pipeline& p = s.pipeline;
  const auto& W = s.world_position;
  std::array<double, 3> out{};
  for (int r = 0; r < 3; ++r) {
    const double e_max = r < 2 ? g.lateral : g.wv_hi;
    if (m.path == VertexPath::relative_to_eye) {
      const double low = std::min(std::nextafter(65536.0, 0.0), std::fabs(W[r]) + e_max);
      out[r] =
          8 * hs(m, e_max) + 0x1.0p-45 * (std::fabs(W[r]) + e_max) + 2 * hu(m, low) + hs(m, low);
      continue;
    }
    const double column = r < 2 ? g.side : g.side * std::sqrt(2.0) * m.sin_tilt;
    double entries = 2 * 0.5 * hs(m, column);
    double t = r == 2 ? g.D : 0.0;
    if (!s.at_world_origin()) {
      if (m.path == VertexPath::model_view) {
        entries += 0x1.0p-52 * 2 * (std::fabs(W[r]) + g.D) + hs(m, t);
      } else {
        t = std::fabs(W[r]) + t;
        entries += hs(m, t);
      }
    }
    if (m.premultiplied) {
      out[r] = p.matrix_precision == MatrixPrecision::single ? entries * b32::kMargin : 0.0;
      continue;
    }
    double sum =
        entries + b32::row_rounding(m.shader_rounding,
                                    {{0.5 * column, false}, {0.5 * column, false}, {t, true}});
    if (m.path == VertexPath::model_then_view && !s.at_world_origin())
      sum += hs(m, std::fabs(W[r])) + hs(m, e_max);
    out[r] = sum * b32::kMargin;
  }
  return out;
}

// (2) The clip coordinates (the vertex shader, in the model's shader precision): each computed
// from the computed eye position (or, premultiplied, the
// object position) by a row of binary32 P (P * MV), against the exact product of that row with
// the same input:
// - separate: x = P00 e_x, y = P11 e_y (one product each, sums with zeros exact), z = a e_z + b
//   (a product unless a is a power of two, and one sum), w = -e_z exactly;
// - premultiplied: P * MV's entries rounded (binary32: a e_z's product and sum for the
//   translation, one product elsewhere, -M's entries exact in the w row; binary64: each rounded
//   once), then each row of three terms (row_rounding); w then carries rounding of its own;
// - llvmpipe's clip stage (in the model whatever the row's pipeline says; the planes cross the
//   x and y planes of the clip volume): a vertex made on a clip plane is out + t (in - out) per
//   coordinate with one t, so t's own error keeps it on the computed edge, in the computed
//   triangle's plane; the difference, the product and the sum round once each, at most
//   |in - out| twice and |c| once, for each of the (at most two) planes a corner vertex crosses;
//   the ends' errors carry through the convex combination at most as the larger.
Clip4 clip_rounding(const RowModel& m, const PlaneGeometry& g) {
  const b32::Rounding& R = m.shader_rounding;
  const double aa = std::fabs(m.a), ab = std::fabs(m.b);
  const double zc_max = std::max(std::fabs(-m.a * g.wv_lo + m.b), std::fabs(-m.a * g.wv_hi + m.b));
  const double xc_max = m.P00 * g.lateral, yc_max = m.P11 * g.lateral;
  Clip4 c;
  if (!m.premultiplied) {
    c.x = b32::row_rounding(R, {{xc_max, b32::exact_factor(m.P00)}});
    c.y = b32::row_rounding(R, {{yc_max, b32::exact_factor(m.P11)}});
    c.z = b32::row_rounding(R, {{aa * g.wv_hi, b32::exact_factor(m.a)}, {ab, true}});
  } else {
    const bool single = m.scene->pipeline.matrix_precision == MatrixPrecision::single;
    const double zcol = g.side * std::sqrt(2.0) * m.sin_tilt;
    // x_clip's row (P00 side R00, P00 side R01) times the object position in [-0.5, 0.5]^2: each
    // term up to P00 side / 2 (|R0j| <= 1), their sum up to xc_max; y's likewise.
    c.x = hs(m, m.P00 * g.side) +
          b32::row_rounding(R, {{0.5 * m.P00 * g.side, false}, {0.5 * m.P00 * g.side, false}});
    c.y = hs(m, m.P11 * g.side) +
          b32::row_rounding(R, {{0.5 * m.P11 * g.side, false}, {0.5 * m.P11 * g.side, false}});
    c.z = hs(m, aa * zcol) + (single ? hs(m, aa * g.D) : 0.0) + hs(m, aa * g.D + ab) +
          b32::row_rounding(
              R, {{0.5 * aa * zcol, false}, {0.5 * aa * zcol, false}, {aa * g.D + ab, true}});
    // orthographic's P M has the w row (0, 0, 0, 1): w is 1 exactly
    c.w = m.ortho
              ? 0.0
              : (single ? 0.0 : hs(m, zcol) + hs(m, g.D)) +
                    b32::row_rounding(R, {{0.5 * zcol, false}, {0.5 * zcol, false}, {g.D, true}});
  }
  if (m.model->clip_stage) {  // fixed function: binary32
    // |in - out|: both ends lie in one grid triangle (the clip stage's polygons stay inside the
    // triangle they clip), where a coordinate differs most between two of its vertices: across
    // the quad's diagonal, (dx, dy) of length sqrt(2)/N in the plane's unit square. e_x's row of
    // R has length 1, e_z's at most sqrt(2) sin r, so x_clip differs by at most
    // P00 side sqrt(2)/N = 2 xc_max/N and w (and z_clip / a) by 2 side sin r/N = dw/N.
    const double n = std::max(1, m.scene->plane_subdivisions);
    const double dw = (g.wv_hi - g.wv_lo) / n;
    c.x += 2 * (2 * hu(m, 2 * xc_max / n) + hu(m, xc_max));
    c.y += 2 * (2 * hu(m, 2 * yc_max / n) + hu(m, yc_max));
    c.z += 2 * (2 * hu(m, aa * dw) + hu(m, zc_max));
    // orthographic w is 1 at every vertex, so out + t (in - out) is 1 exactly
    if (!m.ortho) c.w += 2 * (2 * hu(m, dw) + hu(m, g.wv_hi));
    // Vertex-stage log depth rewrites z as (2 F - 1) w or F w, of magnitude at most w, which
    // changes across a grid triangle by at most (factor F' w + 1) dw: the clip stage interpolates
    // that z (window_error reads c.z so for log_vertex), not P's.
    if (m.vertex_log) {
      const double factor = m.pc.depth_gl ? 2 : 1;
      const double dz = (factor * depth_slope(m, g.wv_lo, g.wv_hi) * g.wv_hi + 1) * dw;
      c.z = 2 * (2 * hu(m, dz) + hu(m, g.wv_hi));
    }
  } else if (m.vertex_log) {
    c.z = 0;  // the rewrite replaces P's z row, whose rounding the rewrite's own terms count
  }
  c.x *= b32::kMargin;
  c.y *= b32::kMargin;
  c.z *= b32::kMargin;
  c.w *= b32::kMargin;
  return c;
}

// (3) A shader's own arithmetic from an exact w in [lo, hi] to the depth it writes (the input's
// error enters through the slope, depth_slope): every step a binary32 operation within half an ulp
// of its result, the log within the model's log_half_ulps (OpenCL's 3 ulp, llvmpipe's 3.84
// and 3.60); a quotient by a constant as a division or as a product with its reciprocal (two
// roundings).
double shader_own(const RowModel& m, double lo, double hi) {
  const ProbeConstants& pc = m.pc;
  const double f_max = std::max(std::fabs(exact_depth(m, lo)), std::fabs(exact_depth(m, hi)));
  // A quotient by a constant, or the product with its reciprocal (the model's reciprocal).
  const auto over = [&](double c) {
    return b32::quotient_by_constant_error(m.shader_rounding, f_max, c,
                                           m.model->reciprocal_half_ulps);
  };
  switch (m.ti.fragment) {
    // The numerator's error divided by c, or times fl(1 / c): 1 + 2^-22 covers the reciprocal's
    // own relative error (2^-23 within 1 ulp), which kMargin does not.
    case FragmentDepth::linear:
      return hs(m, hi - pc.near) / pc.range * (1 + 0x1.0p-22) + over(pc.range);
    case FragmentDepth::w_buffer:
      return over(pc.far);
    case FragmentDepth::threejs_log:
      break;  // as three.js's vertex-stage log, below
    case FragmentDepth::cesium_log: {
      // fl(log2(fl(fl(w - n) + 1)) C)
      const double x_hi = (hi - pc.near) + 1, l2 = std::log2(x_hi);
      return pc.cesium_inv_log2 *
                 ((hs(m, hi - pc.near) + hs(m, x_hi)) / (((lo - pc.near) + 1) * M_LN2) +
                  m.model->log_half_ulps * hs(m, l2)) +
             hs(m, f_max);
    }
    case FragmentDepth::log:
    case FragmentDepth::none:
      break;
  }
  if (m.ti.fragment == FragmentDepth::threejs_log ||
      (m.vertex_log && m.pc.vertex_log == MTS_VERTEX_LOG_THREEJS)) {
    // fl(fl(log2(fl(1 + w)) FC) 0.5): the product by one half is exact
    const double x_hi = 1 + hi, l2 = std::log2(x_hi);
    return 0.5 * pc.threejs_fc *
               (hs(m, x_hi) / ((1 + lo) * M_LN2) + m.model->log_half_ulps * hs(m, l2)) +
           0.5 * hs(m, 2 * f_max);
  }
  // Gilg's fl(ln(fl(fl(k w) + 1)) / L): the argument's roundings through the log's slope 1 / x,
  // the log's own error, then the quotient's (or the reciprocal's and product's) roundings.
  const double k = pc.log_k, x_hi = k * hi + 1;
  const double arg = (b32::exact_factor(k) ? 0.0 : hs(m, k * hi)) + hs(m, x_hi);
  return (arg / (k * lo + 1) + m.model->log_half_ulps * hs(m, std::log(x_hi))) / pc.log_L *
             (1 + 0x1.0p-22) +
         over(pc.log_L);
}

// (3') A mediump fragment shader's uniforms, each rounded to binary16
// (interface/mediump_fragment.h): the map it computes is F with the rounded constants, within, to
// first order in their relative errors (at most 2^-11; 1.01 covers the rest), of F over w in [lo,
// hi]: a quotient by a constant c moves d by d |dc| / c, k moves ln(k w + 1) by at most w |dk| / (k
// w + 1) (ln(1 + x) <= x), a near plane subtracted moves d by the map's slope times its rounding.
double uniform_error(const RowModel& m, double lo, double hi) {
  const ProbeConstants& pc = m.pc;
  const double f_max = std::max(std::fabs(exact_depth(m, lo)), std::fabs(exact_depth(m, hi)));
  const auto rel = [&m](double c) { return hs(m, c) / std::fabs(c); };
  double e = 0;
  switch (m.ti.fragment) {
    case FragmentDepth::linear:
      e = hs(m, pc.near) / pc.range + f_max * rel(pc.range);
      break;
    case FragmentDepth::w_buffer:
      e = f_max * rel(pc.far);
      break;
    case FragmentDepth::threejs_log:
      e = f_max * rel(pc.threejs_fc);
      break;
    case FragmentDepth::cesium_log:
      e = pc.cesium_inv_log2 * hs(m, pc.near) / ((std::max(lo - pc.near, 0.0) + 1) * M_LN2) +
          f_max * rel(pc.cesium_inv_log2);
      break;
    case FragmentDepth::log:
      e = hi * hs(m, pc.log_k) / (pc.log_k * lo + 1) / pc.log_L + f_max * rel(pc.log_L);
      break;
    case FragmentDepth::none:
      break;
  }
  return 1.01 * e;
}

// (4) The divide and the viewport transform of one vertex whose clip coordinates carry errors c,
// as the value the plane interpolates (window depth, or q = 1/w for fragment-stage depth), and
// window x and y:
// - q = fl(1 / w), or a correctly rounded divide in its place (one rounding fewer; the same
//   bound): reciprocal_error;
// - ndc = fl(clip q): product_error, rounding at the largest |ndc| of the vertices (from the
//   exact map, not from |clip| / w_min, which would cross a binade the values never reach);
// - window depth fl(fl(0.5 z) + 0.5) (gl; the product by one half exact, or one fma) or z
//   (zero_to_one); window x fl(fl(x (W/2)) + W/2), or one fma; snapped to 2^-bits where the
//   pipeline snaps;
// - vertex-stage log depth (log_vertex): the shader's depth F(w) from the clip w, its z rewritten
//   (2 F - 1) w (gl) or F w, which the divide turns back: F's error twice, the rewrite's -1 and
//   product, the divide's, the viewport's.
// x and y without snapping, whose half step `snap` is each one's further error.
struct WindowError {
  double value = 0, x = 0, y = 0, snap = 0;
};
// reciprocal_half_ulps: the model's, or 1 for the correctly rounded reciprocal the model's
// kReciprocal term is measured from.
WindowError window_error(const RowModel& m, const PlaneGeometry& g, const Clip4& c,
                         double reciprocal_half_ulps) {
  const b32::Rounding& R = m.rounding;
  const Scene& s = *m.scene;
  WindowError out;
  // Orthographic: w is 1 for every vertex (its row (0, 0, 0, 1) rounds nothing).
  const double w_lo = m.ortho ? 1.0 : g.wv_lo;
  // reciprocal_error holds for an error below half of w; beyond it nothing is bounded.
  if (!(c.w < 0.5 * w_lo)) {
    out.value = out.x = out.y = INFINITY;
    return out;
  }
  const double eq = b32::reciprocal_error(R, w_lo, c.w, reciprocal_half_ulps);
  const double q_max = 1 / (w_lo - c.w);
  if (m.fragment) {
    out.value = eq;
  } else if (m.vertex_log) {
    const double eF = shader_own(m, g.wv_lo, g.wv_hi) + depth_slope(m, g.wv_lo, g.wv_hi) * c.w;
    const double factor = m.pc.depth_gl ? 2 : 1;
    // c.z: the clip stage's interpolation of the rewritten z (clip_rounding)
    const double zc = (factor * eF + hu(m, 1.0)) * g.wv_hi + hu(m, g.wv_hi) + c.z;
    const double zn = b32::product_error(R, g.wv_hi, zc, q_max, eq, 1.0);
    out.value = m.pc.depth_gl ? 0.5 * zn + hu(m, 1.0) : zn;
  } else {
    const double zc_max =
        std::max(std::fabs(-m.a * g.wv_lo + m.b), std::fabs(-m.a * g.wv_hi + m.b));
    const double zn_max =
        m.ortho ? zc_max
                : std::max(std::fabs(-m.a + m.b / g.wv_lo), std::fabs(-m.a + m.b / g.wv_hi));
    const double zn = b32::product_error(R, zc_max, c.z, q_max, eq, zn_max);
    const double d_max =
        std::max(std::fabs(exact_depth(m, g.wv_lo)), std::fabs(exact_depth(m, g.wv_hi)));
    out.value = m.pc.depth_gl ? 0.5 * zn + hu(m, d_max + 0.5 * zn) : zn;
  }
  const int snap_bits = m.model->snap_bits > 0 ? m.model->snap_bits : s.pipeline.snap_bits;
  out.snap = snap_bits > 0 ? std::ldexp(1.0, -snap_bits - 1) : 0.0;
  const auto window = [&](double P, double clip_err, int size) {
    const double c_max = P * g.lateral, n_max = c_max * q_max, h = 0.5 * size;
    const double en = b32::product_error(R, c_max, clip_err, q_max, eq, n_max);
    return h * en + (b32::exact_factor(h) ? 0.0 : hu(m, h * n_max)) + hu(m, h * n_max + h);
  };
  out.x = window(m.P00, c.x, s.viewport_w);
  out.y = window(m.P11, c.y, s.viewport_h);
  out.value *= b32::kMargin;
  return out;
}

// The value's gradient in window space, per pixel in x and y. A plane's window depth (or q) is
// affine in screen space: d = F(w) with w = D / (1 - rx u - ry v), u = x_ndc / P00, so
// dd/dpx = F'(w) (w^2 / D) rx (2 / (W P00)) = -scale b rx 2 / (W P00 D) for a projection, and
// rx 2 / (W P00 D) for q: constants over the plane, at most tan_tilt in place of rx.
// Orthographic: w = D + rx u + ry v and d = scale (-a w + b) + ..., so scale |a| rx 2 / (W P00).
// log_vertex's per-vertex log is interpolated, not affine: its plane's gradient is bounded by the
// largest slope of F along w, with half again for the triangle's shape.
std::array<double, 2> gradient(const RowModel& m, const PlaneGeometry& g) {
  double k = 0;
  if (m.fragment)
    k = 1 / g.D;
  else if (m.vertex_log)
    k = 1.5 * depth_slope(m, g.wv_lo, g.wv_hi) * g.wv_hi * g.wv_hi / g.D;
  else
    k = m.ortho ? m.scale * std::fabs(m.a) : m.scale * std::fabs(m.b) / g.D;
  const Scene& s = *m.scene;
  return {k * m.tan_tilt * 2 / (s.viewport_w * m.P00), k * m.tan_tilt * 2 / (s.viewport_h * m.P11)};
}

// How far an eye-space error of at most e in z moves the value at a vertex: its secant slope over
// w's range widened by e (q = 1/w and the projections' b/w move by e / (w (w - e)) at most, not by
// the tangent's e / w^2: an error near w itself, as far from the world origin, is not small).
double value_slope(const RowModel& m, const PlaneGeometry& g, double e) {
  if (m.fragment) return 1 / (g.wv_lo * (g.wv_lo - e));
  if (m.vertex_log) return depth_slope(m, g.wv_lo - e, g.wv_hi + e);
  if (m.ortho) return m.scale * std::fabs(m.a);
  return m.scale * std::fabs(m.b) / (g.wv_lo * (g.wv_lo - e));
}

// The largest |value| at a kernel pixel.
double pixel_value_max(const RowModel& m, const PlaneGeometry& g) {
  return m.fragment ? 1 / g.wp_lo : pixel_depths(m, g).magnitude();
}

}  // namespace

const char* term_name(int t) {
  static const char* const names[kTermCount] = {
      "vertex",     "clip",          "divide",
      "reciprocal", "position",      "snap",
      "setup",      "interpolation", "interpolation_tolerance",
      "shader",     "storage"};
  return names[t];
}

double DepthError::total() const {
  double out = 0;
  for (const double t : term) out += t;
  return out * b32::kMargin;
}

std::array<double, 2> window_gradient(const RowModel& m, const PlaneGeometry& g) {
  return gradient(m, g);
}

PixelDepths pixel_depths(const RowModel& m, const PlaneGeometry& g) {
  const double a = exact_depth(m, g.wp_lo), b = exact_depth(m, g.wp_hi);
  return {std::min(a, b), std::max(a, b)};
}

// The fan triangles llvmpipe's clip stage makes are assumed to keep a smallest angle of 1 degree
// (the grid's own triangles are near right isosceles): the set-up's determinant then loses at
// most 1 / sin(1 deg) to cancellation (docs/mts.md lists it among the model's assumptions).
constexpr double kKappa = 57.3;

DepthError depth_error(const RowModel& m, const PlaneGeometry& g) {
  const Scene& s = *m.scene;
  const std::array<double, 3> ee = eye_error(m, g);
  const Clip4 c = clip_rounding(m, g);
  const double recip = m.model->reciprocal_half_ulps;
  const WindowError own = window_error(m, g, Clip4{}, recip);
  const WindowError all = window_error(m, g, c, recip);
  // the correctly rounded reciprocal's, where the model allows more (kReciprocal is the rest)
  const WindowError own_cr = recip > 1 ? window_error(m, g, Clip4{}, 1) : own;
  const std::array<double, 2> G = gradient(m, g);
  const double q_max = m.ortho ? 1.0 : 1 / g.wv_lo;
  const double xn_max = m.P00 * g.lateral * q_max, yn_max = m.P11 * g.lateral * q_max;
  // An eye-space error moves the vertex's window position by (W/2) d(x_ndc) with
  // x_ndc = P00 e_x / w: P00 / w per unit of e_x, |x_ndc| / w per unit of e_z (orthographic:
  // x_ndc = P00 e_x, e_z leaves it alone).
  // With the vertex's w moved by up to e_w, x_ndc moves by (P00 |dx| + |x_ndc| |dw|) / (w - e_w).
  // Where e_w reaches half of w nothing is bounded.
  DepthError out;
  auto& v = out.term;
  const double e_w = m.ortho ? 0.0 : ee[2];
  if (!(e_w < 0.5 * g.wv_lo)) {
    for (double& t : v) t = INFINITY;
    return out;
  }
  const double q_vertex = m.ortho ? 1.0 : 1 / (g.wv_lo - e_w);
  const double zx = m.ortho ? 0.0 : xn_max, zy = m.ortho ? 0.0 : yn_max;
  const double geo_x = 0.5 * s.viewport_w * (m.P00 * ee[0] + zx * ee[2]) * q_vertex * b32::kMargin;
  const double geo_y = 0.5 * s.viewport_h * (m.P11 * ee[1] + zy * ee[2]) * q_vertex * b32::kMargin;
  // (5) The plane at a covered pixel p. With lambda~ the computed triangle's barycentrics at p and
  // grad v the exact plane's gradient, the plane through the computed vertices is exactly
  // sum lambda~_i [(v~_i - v_i) - grad v . (x~_i - x_i)] away from the exact plane at p (write
  // v(p) = sum lambda~_i v(x~_i); v is affine). A covered pixel centre lies inside the computed
  // triangle up to its edge tests' rounding, lambda~_i >= -0.01, sum |lambda~_i| <= 1.02: each
  // vertex's error, value and position through the gradient, counts at most 1.02 times.
  v[kVertex] = value_slope(m, g, e_w) * ee[2] + G[0] * geo_x + G[1] * geo_y;
  v[kClip] = std::max(0.0, all.value - own.value) + G[0] * (all.x - own.x) + G[1] * (all.y - own.y);
  v[kDivide] = own_cr.value;
  v[kPosition] = G[0] * own_cr.x + G[1] * own_cr.y;
  if (recip > 1)
    v[kReciprocal] =
        (own.value - own_cr.value) + G[0] * (own.x - own_cr.x) + G[1] * (own.y - own_cr.y);
  v[kSnap] = (G[0] + G[1]) * own.snap;
  for (double& t : v) t *= 1.02;
  // Set-up: the gradients from differences, products, the determinant and a quotient, each
  // rounded: within (6 kappa + 4) u of both gradients' magnitudes, kappa bounding the triangle's
  // |e1| |e2| / |det| at its anchor vertex, over a pixel no farther from the anchor vertex than
  // the grid quad's extent (a fan triangle of the clip stage lies inside its grid triangle). The
  // origin forms anchor the plane at the framebuffer's origin with a0 = d0 - (gx x0 + gy y0)
  // from the same rounded gradients, so the gradients' error still multiplies p - (x0, y0); a0's
  // own roundings are the evaluation's.
  const double quad_x = 0.5 * s.viewport_w * m.P00 * g.side / s.plane_subdivisions * q_max;
  const double quad_y = 0.5 * s.viewport_h * m.P11 * g.side / s.plane_subdivisions * q_max;
  v[kSetup] = (6 * kKappa + 4) * kU * (G[0] + G[1]) * (quad_x + quad_y);
  // Evaluation: c0 + gx (px - x0) + gy (py - y0) (two sums at the value's magnitude, two products
  // and two coordinate differences), llvmpipe's a0 = c0 - (gx x0 + gy y0) then two fma (three and
  // three), or softpipe's a0, (a0 + gx qx) + gy qy and a step in x and in y (five sums at the
  // value's magnitude plus the slopes' reach, five products and sums at the reach): five and
  // five, and the coordinates' differences (tests/base/binary32_error_proof.cpp); a pixel lies at
  // most X = W (1 + |x_ndc|) from the anchor (a vertex, or the framebuffer's origin).
  const double X = s.viewport_w * (1 + xn_max), Y = s.viewport_h * (1 + yn_max);
  const double reach = G[0] * X + G[1] * Y;
  const BoundModel& bm = *m.model;
  v[kInterpolation] = bm.value_roundings * hu(m, pixel_value_max(m, g) + reach) +
                      bm.reach_roundings * hu(m, reach) + G[0] * hu(m, X) + G[1] * hu(m, Y);
  v[kInterpolationTolerance] =
      m.scene->interpolation_tolerance_or(bm.interpolation_relative) * pixel_value_max(m, g);
  if (!m.fragment) return out;
  // (6) Fragment-stage depth: w = fl(1 / q~) with q~ within Eq of q >= 1 / wp_hi, then the
  // shader's depth F(w): the interpolation's error through 1 / q and F's slope, w's rounding and
  // the shader's own arithmetic.
  // A mediump shader's varying q arrives rounded to binary16 (interface/mediump_fragment.h).
  const double q_varying = m.fragment_mediump ? hs(m, 1 / g.wp_lo) : 0.0;
  const double Eq = out.total() + q_varying;
  const double q_min = 1 / g.wp_hi;
  if (!(Eq < 0.5 * q_min)) {
    for (double& t : v) t = INFINITY;
    return out;
  }
  const double to_w = 1 / (q_min * (q_min - Eq));
  // w = fl(1 / q~): within the model's reciprocal_half_ulps of the correctly rounded one
  const double w_rounding = m.model->reciprocal_half_ulps * hu(m, g.wp_hi + Eq * to_w);
  const double ew = Eq * to_w + w_rounding;
  const double Fp = depth_slope(m, std::max(g.wp_lo - ew, 0.5 * g.wp_lo), g.wp_hi + ew);
  for (int t = 0; t < kShader; ++t) v[t] *= to_w * Fp;
  if (!m.fragment_mediump) {
    v[kShader] = Fp * w_rounding + shader_own(m, g.wp_lo - ew, g.wp_hi + ew);
    return out;
  }
  // In mediump: the varying's rounding through 1/q, w's rounding in binary16, the shader's own
  // roundings (shader_own at the shader's precision), its uniforms'.
  v[kShader] = Fp * (q_varying * to_w + hs(m, g.wp_hi + Eq * to_w)) +
               shader_own(m, g.wp_lo - ew, g.wp_hi + ew) +
               uniform_error(m, g.wp_lo - ew, g.wp_hi + ew);
  return out;
}

}  // namespace depthprec::bound
