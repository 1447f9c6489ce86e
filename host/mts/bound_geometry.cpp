#include "host/mts/bound_geometry.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "host/base/errors.h"
#include "host/runtime/kernel_variant.h"
#include "interface/binary16.h"

namespace depthprec::bound {

namespace {

// The cube's rotations as the application's matrices give them: R~ = Rx Ry Rz formed in the
// matrix precision from binary32 (or binary64) cos and sin is within about 10 u of R per entry,
// the same for both planes, so it is a slightly different orientation, not an error between the
// planes; widening the cube by 2^-16 rad (far more than 10 u) keeps every such R~ inside it.
constexpr double kTiltMargin = 0x1.0p-16;

}  // namespace

std::vector<double> fragment_uniforms(const RowModel& m) {
  const ProbeConstants& pc = m.pc;
  switch (m.ti.fragment) {
    case FragmentDepth::linear:
      return {pc.near, pc.range};
    case FragmentDepth::w_buffer:
      return {pc.far};
    case FragmentDepth::threejs_log:
      return {pc.threejs_fc};
    case FragmentDepth::cesium_log:
      return {pc.near, pc.cesium_inv_log2};
    case FragmentDepth::log:
      return {pc.log_k, pc.log_L};
    case FragmentDepth::none:
      break;
  }
  return {};
}

RowModel row_model(const Scene& s, const EvalPair& pair, double z) {
  RowModel m;
  m.scene = &s;
  m.pair = pair;
  m.pc = probe_constants(s, pair, z);
  m.ti = info(depth_path(s, pair.technique));
  m.format = s.storage_format(pair);
  m.model = &bound_model(s.bound_model);
  m.shader_rounding = {true, false, m.model->shader_bits};
  if (const char* formats = m.model->api_formats) {
    const std::string listed = std::string(", ") + formats + ", ";
    if (listed.find(", " + m.format.name() + ", ") == std::string::npos)
      throw InputError(fmt::format("{} has no {} depth format (its: {})", m.model->name,
                                   m.format.name(), formats));
  }
  const Pipeline& p = s.pipeline;
  // Binary32 arithmetic rounds to nearest in every profile; flushing subnormal results is allowed
  // (it only matters below 2^-126, where no depth of a resolved row lies).
  m.rounding = {true, false};
  m.path = vertex_path(p);
  m.premultiplied = m.path == VertexPath::premultiplied;
  if (m.premultiplied && !s.at_world_origin())
    throw InputError("no bound model for compose premultiplied away from the world origin");
  // Under premultiplied binary64 matrices the GPU gets P * MV rounded once from binary64: the
  // depths follow the binary64 P; otherwise the binary32 P the GPU multiplies by.
  const bool full = m.premultiplied && p.matrix_precision == MatrixPrecision::binary64;
  const auto P = [&](int r, int c) {
    return full ? m.pc.P_full[r * 4 + c] : static_cast<double>(m.pc.P[r * 4 + c]);
  };
  m.a = P(2, 2);
  m.b = P(2, 3);
  m.P00 = P(0, 0);
  m.P11 = P(1, 1);
  m.ortho = pair.technique == Technique::orthographic;
  if (m.ortho ? (P(3, 2) != 0 || P(3, 3) != 1)
              : (P(3, 2) != -1 || P(3, 3) != 0) || P(2, 0) != 0 || P(2, 1) != 0)
    throw InputError(
        "no bound model for a projection whose w row is not (0, 0, -1, 0), or orthographic's "
        "(0, 0, 0, 1)");
  // A vertex shader below binary32 (pipeline.shader_precision: mediump's binary16, the GLSL ES
  // 1.00 highp minimum) computes at that precision whatever the model allows, within its range,
  // and holds the projection's entries at it: the map its depths follow.
  m.shader_range = m.model->shader_range;
  if (const BoundModel* reduced = shader_precision_model(static_cast<int>(p.shader_precision))) {
    m.shader_rounding.bits = std::min(m.shader_rounding.bits, reduced->shader_bits);
    m.shader_range = std::min(m.shader_range, reduced->shader_range);
    for (double* e : {&m.a, &m.b, &m.P00, &m.P11})
      *e = dp_shader_round(static_cast<float>(*e), static_cast<int>(p.shader_precision));
  }
  m.scale = m.pc.depth_gl ? 0.5 : 1.0;
  const double r = s.rotation_range_deg * M_PI / 180 + kTiltMargin;
  m.sin_tilt = std::sin(r);
  // The plane's normal is Rx Ry e_z = (sin ty, -sin tx cos ty, cos tx cos ty): |n_x / n_z| and
  // |n_y / n_z| are at most tan r / cos r.
  m.tan_tilt = std::tan(r) / std::cos(r);
  m.xn_max = static_cast<double>(s.kernel_w) / s.viewport_w;
  m.yn_max = static_cast<double>(s.kernel_h) / s.viewport_h;
  m.sign = m.ti.greater ? -1.0 : 1.0;
  m.fragment = m.ti.from == DepthFrom::fragment;
  m.fragment_mediump = m.fragment && p.shader_precision != ShaderPrecision::highp;
  if (m.fragment_mediump)
    for (const double u : fragment_uniforms(m))
      m.fragment_uniform_max = std::max(m.fragment_uniform_max, std::fabs(u));
  m.vertex_log = m.ti.from == DepthFrom::vertex_log;
  return m;
}

double geometry_distance(const RowModel& m, double D) {
  // At the origin the model-view the GPU gets holds the translation -D rounded to binary32,
  // whichever precision formed it (vertex_stage.cpp: rounded(M)): the planes lie at fl32(D).
  // Premultiplied binary64 matrices are the exception: P M is formed from D itself, each entry
  // rounded once (its z row's translation fl32(-a D + b), not -a fl32(D) + b), which the clip
  // term counts against D (clip_rounding).
  if (!m.scene->at_world_origin()) return D;
  if (m.premultiplied && m.scene->pipeline.matrix_precision == MatrixPrecision::binary64) return D;
  return static_cast<double>(static_cast<float>(D));
}

PlaneGeometry plane_geometry(const RowModel& m, double D) {
  const Scene& s = *m.scene;
  PlaneGeometry g;
  g.D = D;
  // The binary32 side differs from this by a few u: a scaling within the plane, which moves no
  // depth; the margin keeps the ranges bounds.
  g.side = plane_side(s, D) * (1 + 0x1.0p-18);
  // A vertex (x, y) in [-0.5, 0.5]^2 sits at e_z = -D + side (R20 x + R21 y): the third row of
  // R = Rx Ry Rz has |(R20, R21)| <= sqrt(2) sin r, so |R20 x + R21 y| <= sin r.
  g.wv_lo = D - g.side * m.sin_tilt;
  g.wv_hi = D + g.side * m.sin_tilt;
  // The ray through NDC (xn, yn) is w (xn / P00, yn / P11, -1); it meets the plane n.e = -D n_z at
  // w = D / (1 - (n_x/n_z) xn / P00 - (n_y/n_z) yn / P11). Orthographic rays are parallel, at
  // (xn / P00, yn / P11) across the view: w = D - (n_x/n_z) xn / P00 - (n_y/n_z) yn / P11.
  const double U = m.xn_max / m.P00 + m.yn_max / m.P11;
  g.wp_lo = m.ortho ? D - m.tan_tilt * U : D / (1 + m.tan_tilt * U);
  g.wp_hi = m.ortho ? D + m.tan_tilt * U : D / (1 - m.tan_tilt * U);
  g.lateral = g.side * std::sqrt(0.5);
  return g;
}

double exact_depth(const RowModel& m, double w) {
  const ProbeConstants& pc = m.pc;
  switch (m.ti.fragment) {
    case FragmentDepth::linear:
      return (w - pc.near) / pc.range;
    case FragmentDepth::w_buffer:
      return w / pc.far;
    case FragmentDepth::log:
      return std::log1p(pc.log_k * w) / pc.log_L;
    case FragmentDepth::threejs_log:
      return std::log2(1 + w) * pc.threejs_fc * 0.5;
    case FragmentDepth::cesium_log:
      return std::log2((w - pc.near) + 1) * pc.cesium_inv_log2;
    case FragmentDepth::none:
      break;
  }
  if (m.vertex_log)
    return m.pc.vertex_log == MTS_VERTEX_LOG_THREEJS ? std::log2(1 + w) * pc.threejs_fc * 0.5
                                                     : std::log1p(pc.log_k * w) / pc.log_L;
  if (m.ortho) return m.scale * (-m.a * w + m.b) + (1 - m.scale);
  return m.scale * (-m.a + m.b / w) + (1 - m.scale);
}

double depth_slope(const RowModel& m, double lo, double hi) {
  // Every map here is monotone with a monotone slope (1/w^2, 1/(k w + 1), constants), so the
  // larger slope of the two ends, from secants a hair inside them, bounds it; 1 % covers the
  // secant's difference from the tangent.
  double out = 0;
  for (const double w : {lo, hi}) {
    const double h = 1e-6 * w;
    const double x = std::max(w - h, 0.5 * w), y = w + h;
    out = std::max(out, std::fabs(exact_depth(m, y) - exact_depth(m, x)) / (y - x));
  }
  return 1.01 * out;
}

double exact_gap(const RowModel& m, double lm1, double w) {
  const ProbeConstants& pc = m.pc;
  const double lw = (1 + lm1) * w;
  double gap = 0;
  switch (m.ti.fragment) {
    case FragmentDepth::linear:
      gap = lm1 * w / pc.range;
      break;
    case FragmentDepth::w_buffer:
      gap = lm1 * w / pc.far;
      break;
    case FragmentDepth::log:
      gap = std::log1p(pc.log_k * lm1 * w / (pc.log_k * w + 1)) / pc.log_L;
      break;
    case FragmentDepth::threejs_log:
      gap = std::log1p(lm1 * w / (1 + w)) / M_LN2 * pc.threejs_fc * 0.5;
      break;
    case FragmentDepth::cesium_log:
      gap = std::log1p(lm1 * w / ((w - pc.near) + 1)) / M_LN2 * pc.cesium_inv_log2;
      break;
    case FragmentDepth::none:
      if (m.ortho) {
        // scale (-a lambda w + a w) = scale (-a) (lambda - 1) w
        gap = m.scale * -m.a * lm1 * w;
      } else if (!m.vertex_log) {
        // scale (b / (lambda w) - b / w) = scale b (1 - lambda) / (lambda w)
        gap = m.scale * m.b * (-lm1) / lw;
      } else if (m.pc.vertex_log == MTS_VERTEX_LOG_THREEJS) {
        gap = std::log1p(lm1 * w / (1 + w)) / M_LN2 * pc.threejs_fc * 0.5;
      } else {
        gap = std::log1p(pc.log_k * lm1 * w / (pc.log_k * w + 1)) / pc.log_L;
      }
      break;
  }
  return m.sign * gap;
}

}  // namespace depthprec::bound
