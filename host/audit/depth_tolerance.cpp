#include "host/audit/depth_tolerance.h"

#include <algorithm>
#include <cmath>

#include "host/runtime/kernel_variant.h"
#include "interface/audit_layout.h"

namespace depthprec {

namespace {

// Unit roundoff of binary32 and Higham's gamma(n) = n u / (1 - n u): n correctly rounded
// operations in sequence, each within u of its result, stay within gamma(n) of the exact value
// relative to the sum of the magnitudes they combine. Every bound below is evaluated in binary64,
// whose own rounding (2^-53 relative) the 1.01 factors cover many times over.
constexpr double kU = 0x1.0p-24;
constexpr double gamma(int n) {
  return n * kU / (1 - n * kU);
}

// A vertex's window-space values and their error bounds.
struct WindowError {
  double x, y, v;     // window x, y and the interpolated value (depth, or q = 1/w)
  double ex, ey, ev;  // bounds on their errors
  double w, ew;       // clip w and its error
};

// Sub-pixel snapping the model allows: D3D 11 (section 15.16) and most hardware snap window x and
// y to 8 fractional bits and set up depth from the snapped positions; llvmpipe and softpipe set it
// up from the float positions. Either way a position moves by at most half a step.
constexpr double kSnap = 0x1.0p-9;

// Whether m * x is exact for every binary32 x (short of overflow and underflow): m is zero or a
// power of two, as the identity's and most projections' entries are.
bool exact_factor(double m) {
  int e = 0;
  return m == 0 || std::fabs(std::frexp(m, &e)) == 0.5;
}

// One row of a binary32 matrix times a vector with values x and error bounds ex: the product's
// value and its error bound. With k nonzero terms p_j = m_j x_j, in any order, fused or not: each
// inexact product rounds once (within u |p_j|; a fused multiply-add only removes that rounding)
// and the k - 1 sums within gamma(k - 1) (1 + u) sum |p_j| (Higham, Theorem 3.1 and its proof:
// each partial sum is at most the sum of magnitudes); sums with a zero and products by a power of
// two round nothing. The inputs' own errors carry through the row: sum |m_j| ex_j.
void row_times(const Mat4f& m, int rows, const double x[4], const double ex[4], double y[4],
               double ey[4]) {
  for (int r = 0; r < rows; ++r) {
    double v = 0, mag = 0, products = 0, carried = 0;
    int k = 0;
    for (int j = 0; j < 4; ++j) {
      const double mj = m[r * 4 + j];
      const double t = mj * x[j];
      v += t;
      carried += std::fabs(mj) * ex[j];
      if (mj == 0 || (x[j] == 0 && ex[j] == 0)) continue;
      ++k;
      mag += std::fabs(t);
      if (!exact_factor(mj)) products += kU * std::fabs(t);
    }
    y[r] = v;
    ey[r] = 1.01 * (products + (k > 1 ? gamma(k - 1) * mag : 0.0)) + carried;
  }
}

// Window x, y, depth and q = 1/w of clip coordinates c with errors ec.
WindowError window_error(const Scene& s, const ProbeConstants& pc, bool depth_from_plane,
                         const std::array<float, 4>& c, const ClipError& ec) {
  WindowError out{};
  const double w = c[3];
  out.w = w;
  const double aw = std::fabs(w);
  if (!(ec[3] < 0.5 * aw)) {
    out.ex = out.ey = out.ev = INFINITY;
    return out;
  }
  // q = fl(1 / w): the exact 1/w of a w off by ew is off by at most |q| ew / (|w| - ew) <=
  // 2 |q| ew / |w| (ew < |w| / 2); the reciprocal rounds once more (or a divide x / w once in its
  // place, which the product's rounding below covers).
  // The eye displacement E (ec[4..6]) through the projection: c_i / w moves by at most
  // sum_j E_j |N_ij| / (|w| - dw)^2 along the segment, N_ij = P_ij w - c_i P_3j (linear in the
  // eye point: anywhere on the segment within |P_ij| dw + dc_i |P_3j| of its value here), dw and
  // dc_i the most w and c_i move (mean value theorem, every factor bounded over the segment); the
  // computed c lies within the roundings ec[0..3] of the segment's end, which widen dw and dc_i.
  double dc[4] = {0, 0, 0, 0};
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 3; ++j) dc[i] += std::fabs(pc.P[i * 4 + j]) * ec[kEyeError + j];
  const double dw = dc[3];
  if (!(ec[3] + dw < 0.5 * aw)) {
    out.ex = out.ey = out.ev = INFINITY;
    return out;
  }
  const auto moved = [&](int i) {  // the most c_i / w moves under the displacement
    const double dwi = dw + ec[3], dci = dc[i] + ec[i];
    double sum = 0;
    for (int j = 0; j < 3; ++j) {
      const double N = pc.P[i * 4 + j] * w - c[i] * pc.P[3 * 4 + j];
      sum += ec[kEyeError + j] *
             (std::fabs(N) + std::fabs(pc.P[i * 4 + j]) * dwi + dci * std::fabs(pc.P[3 * 4 + j]));
    }
    return 1.01 * sum / ((aw - dwi) * (aw - dwi));
  };
  out.ew = ec[3] + dw;
  const double q = 1.0 / w, aq = std::fabs(q);
  const double eq = 2 * aq * ec[3] / aw + gamma(1) * aq;
  // x_ndc = fl(x q), then window x = fl(fl(hw x_ndc) + hw) (or one fma): the product carries x's
  // and q's errors and rounds once, the viewport transform rounds twice.
  const double hw = 0.5 * s.viewport_w, hh = 0.5 * s.viewport_h;
  const auto ndc = [&](double v, double ev) {
    return aq * ev + std::fabs(v) * eq + gamma(1) * std::fabs(v * q) * 1.01;
  };
  const double xn = c[0] * q, yn = c[1] * q, zn = c[2] * q;
  out.x = hw * xn + hw;
  out.y = hh * yn + hh;
  out.ex = hw * (ndc(c[0], ec[0]) + moved(0)) + gamma(2) * (std::fabs(hw * xn) + hw) * 1.01 + kSnap;
  out.ey = hh * (ndc(c[1], ec[1]) + moved(1)) + gamma(2) * (std::fabs(hh * yn) + hh) * 1.01 + kSnap;
  if (depth_from_plane) {
    // depth = fl(fl(scale z_ndc) + offset): 0.5 z_ndc + 0.5 under OpenGL's range (the product by
    // one half is exact, the sum rounds once, or the fma once), z_ndc itself under zero_to_one.
    const double scale = pc.depth_gl ? 0.5 : 1.0, offset = pc.depth_gl ? 0.5 : 0.0;
    out.v = scale * zn + offset;
    out.ev = scale * (ndc(c[2], ec[2]) + moved(2)) +
             (pc.depth_gl ? gamma(1) * 1.01 * std::fabs(out.v) : 0.0);
  } else {
    out.v = q;
    out.ev = eq + 1.01 * dw / (aw * (aw - dw));  // 1/w moved by the displacement's dw
  }
  return out;
}

// The technique's depth d = D(w) where a shader computes it from w (log depth in the vertex
// stage, or in the fragment stage from the interpolated 1/w): D(w) and a bound on a shader's
// error given w off by ew. The shader's own arithmetic (bounds.cl frag_err, every form the kernels
// emulate): at most 9 u |d| of roundings and the log's ulps (llvmpipe's log, the least accurate
// measured, 3.84 ulp), plus 12 u |D'(w)| max(w, 1) for the roundings of its argument (k w + 1,
// w + 1, (w - n) + 1: each within a few u of max(w, 1)); the input's error through the slope.
struct ShaderDepth {
  double d, err;
};
ShaderDepth shader_depth(const Scene& s, const EvalPair& pair, double w, double ew) {
  const auto D = [&](double x) {
    return depth_of_distance(pair.technique, s.near, s.far, s.params, x);
  };
  const double h = 1e-7 * std::max(std::fabs(w), 1e-30);
  const double d = D(w);
  const double slope =
      std::fabs(D(w + h) - D(std::max(w - h, 0.5 * w))) / (w + h - std::max(w - h, 0.5 * w));
  // The slope is taken from a secant: the 1.5 covers its difference from the tangent where D
  // bends (a log's curvature over 10^-7 of w changes the slope by far less).
  const double err = 1.5 * slope * ew + 9 * kU * std::fabs(d) +
                     12 * kU * 1.5 * slope * std::max(std::fabs(w), 1.0);
  return {d, err};
}

// The plane through three window vertices (x_i, y_i, v_i) with errors, over the pixels the
// triangle covers, in any set-up form the model allows; anchored at (ax, ay).
RecordTolerance plane_tolerance(const WindowError* const v[3], double ax, double ay) {
  RecordTolerance out;
  const double dx01 = v[0]->x - v[1]->x, dy01 = v[0]->y - v[1]->y;
  const double dx20 = v[2]->x - v[0]->x, dy20 = v[2]->y - v[0]->y;
  const double dv01 = v[0]->v - v[1]->v, dv20 = v[2]->v - v[0]->v;
  const double area = dx01 * dy20 - dy01 * dx20;
  if (!(std::fabs(area) > 0)) {
    out.constant = INFINITY;
    return out;
  }
  const double s = (dv01 * dy20 - dv20 * dy01) / area;
  const double t = (dv20 * dx01 - dv01 * dx20) / area;
  // (1) The vertices' own errors. At a covered pixel the exact plane is sum lambda_i v_i with
  // barycentric lambda_i in [0, 1]; moving vertex i by (ex, ey, ev) moves it by at most
  // lambda_i E_i, E_i = ev + |s| ex + |t| ey, to first order: at the pixel, the plane through the
  // points (x_i, y_i, E_i), which is affine in the pixel, so it is kept as a plane (the kernel
  // evaluates it per pixel): a clipped vertex's large error weighs only near that vertex.
  double E[3], x_max = 0, y_max = 0, v_max = 0;
  for (int i = 0; i < 3; ++i) {
    E[i] = v[i]->ev + std::fabs(s) * v[i]->ex + std::fabs(t) * v[i]->ey;
    x_max = std::max(x_max, std::fabs(v[i]->x));
    y_max = std::max(y_max, std::fabs(v[i]->y));
    v_max = std::max(v_max, std::fabs(v[i]->v));
  }
  if (!std::isfinite(E[0] + E[1] + E[2])) {
    out.constant = INFINITY;
    return out;
  }
  const double dE01 = E[0] - E[1], dE20 = E[2] - E[0];
  out.ex = (dE01 * dy20 - dE20 * dy01) / area;
  out.ey = (dE20 * dx01 - dE01 * dx20) / area;
  out.e0 = E[0] + out.ex * (ax - v[0]->x) + out.ey * (ay - v[0]->y);
  // (2) The gradients' rounding. s = fl(fl(dv01 dy20 - dv20 dy01) / area) with each difference
  // rounded once, each product once, the sum once: the numerator within gamma(3) of the sum of
  // its terms' magnitudes, the area likewise, the division (or reciprocal and product) gamma(2).
  // Over the triangle, |px - anchor| <= 2 x_max whether the plane is anchored at a vertex or at
  // the framebuffer origin (then |px| <= x_max and the anchor term |s x0| <= |s| x_max).
  const double area_mag = std::fabs(dx01 * dy20) + std::fabs(dy01 * dx20);
  const double es = (gamma(3) * (std::fabs(dv01 * dy20) + std::fabs(dv20 * dy01)) +
                     std::fabs(s) * gamma(3) * area_mag) /
                        std::fabs(area) +
                    gamma(2) * std::fabs(s);
  const double et = (gamma(3) * (std::fabs(dv20 * dx01) + std::fabs(dv01 * dx20)) +
                     std::fabs(t) * gamma(3) * area_mag) /
                        std::fabs(area) +
                    gamma(2) * std::fabs(t);
  const double gradients = es * 2 * (x_max + 1) + et * 2 * (y_max + 1);
  // (3) Evaluation: d = c0 + s (px - x0) + t (py - y0) in binary32, six roundings at most (the
  // origin form's anchor a0 = c0 - (s x0 + t y0) three more, softpipe's quad step one more): within
  // gamma(10) of the sum of the terms' magnitudes, |c0| + 2 |s| x_max + 2 |t| y_max each side. A
  // plane of constant value (s = t = 0, as a surface facing the eye has under the reversed and
  // standard maps' exact slopes) adds zeros only, which round nothing.
  const double evaluation =
      s == 0 && t == 0
          ? 0.0
          : gamma(10) * (v_max + 2 * std::fabs(s) * (x_max + 1) + 2 * std::fabs(t) * (y_max + 1));
  out.constant = gradients + evaluation;
  return out;
}

}  // namespace

ClipError vertex_clip_error(const ProbeConstants& pc, const VertexStage& st,
                            const std::array<float, 3>& p) {
  const float obj[4] = {p[0], p[1], p[2], 1.0f};
  const double x[4] = {p[0], p[1], p[2], 1.0}, ex[4] = {0, 0, 0, 0};
  double eye[4] = {0, 0, 0, 1}, eeye[4] = {0, 0, 0, 0};
  if (st.path == VertexPath::premultiplied) {  // P V M applied at once: its rounding alone
    ClipError out{};
    double clip[4], rounding[4];
    row_times(st.matrix, 4, x, ex, clip, rounding);
    for (int k = 0; k < 4; ++k) out[k] = rounding[k];
    return out;
  }
  if (st.path == VertexPath::relative_to_eye) {
    // World position in binary64, differenced against the eye's two binary32 parts in emulated
    // double-single arithmetic (interface/relative_to_eye.h): within a few u of the difference
    // and 2^-46 of the world coordinate (the split's low part).
    for (int r = 0; r < 3; ++r) {
      const double world = world_row(st.world, r, obj);
      eye[r] = world - st.eye_high[r] - st.eye_low[r];
      eeye[r] = gamma(4) * std::fabs(eye[r]) + 0x1.0p-46 * std::fabs(world);
    }
  } else {
    row_times(st.matrix, 3, x, ex, eye, eeye);
  }
  if (st.view != VertexStage::View::none) {
    // The view's rows times (eye, 1); a translation alone is the rows of the identity and t, whose
    // products by 1 and 0 are exact: what is left is the sum's one rounding, x + t.
    const double v[4] = {eye[0], eye[1], eye[2], 1.0}, ev[4] = {eeye[0], eeye[1], eeye[2], 0.0};
    row_times(st.view_matrix, 3, v, ev, eye, eeye);
  }
  eye[3] = 1;
  ClipError out{};
  // P's rows round on their own; the eye displacement is carried apart (window_error)
  const double none[4] = {0, 0, 0, 0};
  double clip[4], rounding[4];
  row_times(pc.P, 4, eye, none, clip, rounding);
  for (int k = 0; k < 4; ++k) out[k] = rounding[k];
  for (int k = 0; k < 3; ++k) out[kEyeError + k] = eeye[k];
  return out;
}

ClipError clipped_vertex_error(const std::array<float, 4>& largest, const ClipError& carried,
                               int planes, const std::array<float, 4>& c) {
  // Each plane the clip stage crosses makes a vertex c = out + t (in - out), t in [0, 1]: the
  // difference rounds within u |in - out|, the product within u |t (in - out)|, the sum within
  // u |c|; with |t (in - out)| = |c - out| <= |c| + |out| and |in - out| t <= |c| + |out| that is
  // within 2 u |out| + 3 u |c|, |out| at most the triangle's largest coordinate (every vertex the
  // stage makes is a convex combination of the triangle's). The ends' errors carry through the
  // combination at most as the larger of the two; a later plane interpolates between made vertices,
  // so each plane crossed adds its rounding once more.
  ClipError out = carried;  // the eye displacement: the vertex is a combination of the ends'
  for (int k = 0; k < 4; ++k)
    out[k] =
        carried[k] + planes * 1.01 * (2 * kU * std::fabs(largest[k]) + 3 * kU * std::fabs(c[k]));
  return out;
}

RecordTolerance record_tolerance(const Scene& s, const EvalPair& pair, const ProbeConstants& pc,
                                 const SetupVertex* const v[3], const ClipError* const e[3],
                                 float ax, float ay) {
  const TechniqueInfo& ti = info(depth_path(s, pair.technique));
  const bool plane_depth = ti.from != DepthFrom::fragment;
  WindowError we[3];
  const WindowError* wp[3];
  for (int i = 0; i < 3; ++i) {
    we[i] = window_error(s, pc, plane_depth, v[i]->c, *e[i]);
    if (ti.from == DepthFrom::vertex_log) {
      // The vertex stage rewrites z_clip = (2 D(w) - 1) w (or D(w) w), which the divide turns back
      // into D(w): the shader's depth error, and four more roundings of values within [-w, w].
      const ShaderDepth sd = shader_depth(s, pair, we[i].w, we[i].ew);
      we[i].v = sd.d;
      we[i].ev = sd.err + gamma(4) * 1.01 * 2;
    }
    wp[i] = &we[i];
  }
  RecordTolerance out = plane_tolerance(wp, ax, ay);
  if (plane_depth || !std::isfinite(out.constant)) return out;
  // Fragment-stage depth: q = 1/w interpolated (the kernel maps the q interval through the
  // shader's own D(1/q), so the interpolation's error needs no slope here), then the shader's own
  // arithmetic, largest at one end of the triangle's range of w (q between its vertices').
  double q_lo = INFINITY, q_hi = -INFINITY;
  for (const WindowError& x : we) {
    q_lo = std::min(q_lo, x.v);
    q_hi = std::max(q_hi, x.v);
  }
  for (const double q : {q_lo, q_hi}) {
    if (!(q > 0)) {
      out.constant = INFINITY;
      return out;
    }
    out.shader = std::max(out.shader, shader_depth(s, pair, 1.0 / q, 0.0).err);
  }
  return out;
}

int conversion_codes(const StorageFormat& f) {
  return AUDIT_CONVERSION_CODES(f.is_unorm(), f.bits(), f.name() == "float32");
}

}  // namespace depthprec
