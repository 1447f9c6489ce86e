#include "host/mts/triangle_setup.h"

#include <cmath>

#include "host/model/bound_model.h"
#include "host/model/shader_log.h"
#include "host/runtime/kernel_variant.h"
#include "interface/adversary.h"
#include "interface/mediump_fragment.h"
#include "interface/snap.h"

namespace depthprec {

namespace {

DP_SNAP_WINDOW_DEFINE(snap_window, std::fabs, std::rint)
DP_ADV_RECIPROCAL_DEFINE(adv_reciprocal, std::fma, std::nextafter)

// Clip plane k's distance, dot4(c, plane), in draw's order of additions
// (kernels/mts/setup/clip.cl).
float clip_dist(const std::array<float, 4>& c, int k, bool depth_gl) {
  static const float planes[6][4] = {{-1, 0, 0, 1}, {1, 0, 0, 1}, {0, -1, 0, 1},
                                     {0, 1, 0, 1},  {0, 0, 1, 1}, {0, 0, -1, 1}};
  static const float near_half_z[4] = {0, 0, 1, 0};
  const float* p = k == 4 && !depth_gl ? near_half_z : planes[k];
  return ((c[0] * p[0] + c[1] * p[1]) + c[2] * p[2]) + c[3] * p[3];
}

}  // namespace

unsigned clip_mask(const std::array<float, 4>& c, bool depth_gl, unsigned planes) {
  unsigned m = (c[0] > c[3] ? 1u : 0u) | (0.0f > c[0] + c[3] ? 2u : 0u) | (c[1] > c[3] ? 4u : 0u) |
               (0.0f > c[1] + c[3] ? 8u : 0u);
  m |= (depth_gl ? 0.0f > c[2] + c[3] : 0.0f > c[2]) ? 16u : 0u;
  m |= c[2] > c[3] ? 32u : 0u;
  return m & planes;
}

std::vector<SetupVertex> clip_polygon(std::vector<SetupVertex> poly, unsigned mask, float hw,
                                      float hh, bool gl, int snap_bits, int next_id) {
  for (int k = 0; k < 6 && poly.size() >= 3; ++k) {
    if (!((mask >> k) & 1u)) continue;
    std::vector<SetupVertex> out;
    poly.push_back(poly[0]);
    SetupVertex prev = poly[0];
    float dp_prev = clip_dist(prev.c, k, gl);
    if (!std::isfinite(dp_prev)) return {};
    for (size_t i = 1; i < poly.size(); ++i) {
      const SetupVertex cur = poly[i];
      const float dp = clip_dist(cur.c, k, gl);
      if (!std::isfinite(dp)) return {};
      bool cross;
      if (dp_prev >= 0.0f) {
        out.push_back(prev);
        cross = dp < 0.0f;
      } else {
        cross = !(dp < 0.0f);
      }
      if (cross) {
        const bool leaving = dp < 0.0f;
        const SetupVertex &o = leaving ? cur : prev, &in = leaving ? prev : cur;
        const float t = leaving ? dp / (dp - dp_prev) : dp_prev / (dp_prev - dp);
        SetupVertex n{};
        for (int r = 0; r < 4; ++r) n.c[r] = o.c[r] + t * (in.c[r] - o.c[r]);
        const float oow = 1.0f / n.c[3];
        n.x = snap_window(n.c[0] * oow * hw + hw, snap_bits);
        n.y = snap_window(n.c[1] * oow * hh + hh, snap_bits);
        n.d = gl ? n.c[2] * oow * 0.5f + 0.5f : n.c[2] * oow * 1.0f + 0.0f;
        n.q = oow;
        n.id = next_id++;
        out.push_back(n);
      }
      prev = cur;
      dp_prev = dp;
    }
    poly = out;
  }
  return poly;
}

bool vertex_non_finite(const SetupVertex& v, bool depth_interpolated) {
  return !std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.q) ||
         (depth_interpolated && !std::isfinite(v.d));
}

SetupVertex window_vertex(const Scene& s, bool gl, const float clip[4], int id, int reciprocal) {
  const float hw = 0.5f * static_cast<float>(s.viewport_w);
  const float hh = 0.5f * static_cast<float>(s.viewport_h);
  float inv_w = 1.0f / clip[3];
  if (reciprocal != 0) inv_w = adv_reciprocal(clip[3], inv_w, reciprocal > 0);
  float ndc[3];
  for (int r = 0; r < 3; ++r)
    ndc[r] = s.pipeline.divide == Divide::exact ? clip[r] / clip[3] : clip[r] * inv_w;
  SetupVertex vx;
  if (s.pipeline.viewport == ViewportForm::fma) {
    vx.x = std::fma(ndc[0], hw, hw);
    vx.y = std::fma(ndc[1], hh, hh);
    vx.d = gl ? std::fma(ndc[2], 0.5f, 0.5f) : ndc[2];
  } else {
    vx.x = ndc[0] * hw + hw;
    vx.y = ndc[1] * hh + hh;
    vx.d = gl ? ndc[2] * 0.5f + 0.5f : ndc[2];
  }
  vx.x = snap_window(vx.x, s.pipeline.snap_bits);
  vx.y = snap_window(vx.y, s.pipeline.snap_bits);
  vx.q = inv_w;
  for (int r = 0; r < 4; ++r) vx.c[r] = clip[r];
  vx.id = id;
  return vx;
}

SetupTriangle setup_triangle(const Pipeline& pipeline, const SetupVertex* const tv[3]) {
  SetupTriangle tri{};
  for (int e = 0; e < 3; ++e) {
    const SetupVertex &va = *tv[e], &vb = *tv[(e + 1) % 3];
    const SetupVertex& lo = va.id < vb.id ? va : vb;
    const SetupVertex& hi = va.id < vb.id ? vb : va;
    tri.e[e] = {lo.x, lo.y, hi.x - lo.x, hi.y - lo.y, va.id > vb.id, false};
  }
  const SetupVertex& p2 = *tv[2];
  float orient = tri.e[0].dx * (p2.y - tri.e[0].ay) - tri.e[0].dy * (p2.x - tri.e[0].ax);
  if (tri.e[0].negate) orient = -orient;
  if (orient < 0.0f)
    for (auto& e : tri.e) e.negate = !e.negate;
  tri.valid = orient != 0.0f && std::isfinite(orient);
  for (auto& e : tri.e) {
    const float sg = e.negate ? -1.0f : 1.0f;
    const float dx = sg * e.dx, dy = sg * e.dy;
    e.owns = dy < 0.0f || (dy == 0.0f && dx < 0.0f);
  }
  const SetupVertex &v0 = *tv[0], &v1 = *tv[1], &v2 = *tv[2];
  const float e1x = v1.x - v0.x, e1y = v1.y - v0.y, e2x = v2.x - v0.x, e2y = v2.y - v0.y;
  const float det = e1x * e2y - e2x * e1y;
  if (pipeline.plane == PlaneForm::origin_fma) {
    // llvmpipe's set-up: (v1, v0, v2) for a negative area, gradients times 1/area, the value at
    // the framebuffer origin, evaluated at integer pixel coordinates (x0 = y0 = 0.5).
    const SetupVertex &u0 = det < 0.0f ? v1 : v0, &u1 = det < 0.0f ? v0 : v1, &u2 = v2;
    const float x0c = u0.x - 0.5f, y0c = u0.y - 0.5f;
    const float dx01 = u0.x - u1.x, dy01 = u0.y - u1.y, dx20 = u2.x - u0.x, dy20 = u2.y - u0.y;
    const float ooa = 1.0f / (dx01 * dy20 - dx20 * dy01);
    const float dy20o = dy20 * ooa, dy01o = dy01 * ooa, dx20o = dx20 * ooa, dx01o = dx01 * ooa;
    const auto plane = [&](float a0v, float a1v, float a2v, float& a0, float& dadx, float& dady) {
      const float da01 = a0v - a1v, da20 = a2v - a0v;
      dadx = da01 * dy20o - da20 * dy01o;
      dady = da20 * dx01o - da01 * dx20o;
      a0 = a0v - (dadx * x0c + dady * y0c);
    };
    tri.x0 = 0.5f;
    tri.y0 = 0.5f;
    plane(u0.d, u1.d, u2.d, tri.d0, tri.dzdx, tri.dzdy);
    plane(u0.q, u1.q, u2.q, tri.q0, tri.dqdx, tri.dqdy);
  } else if (pipeline.plane == PlaneForm::origin_quads) {
    // softpipe's set-up: sorted by y as setup_sort_vertices does, ebot = vmid - vmin, emaj =
    // vmax - vmin, gradients times 1/area, the value at the origin from vmin (x0 = y0 = 0.5).
    const float y0 = v0.y, y1 = v1.y, y2 = v2.y;
    const SetupVertex* lo = &v0;
    const SetupVertex* mid = &v1;
    const SetupVertex* hi = &v2;
    if (y0 <= y1) {
      if (y1 <= y2) {
      } else if (y2 <= y0) {
        lo = &v2, mid = &v0, hi = &v1;
      } else {
        mid = &v2, hi = &v1;
      }
    } else if (y0 <= y2) {
      lo = &v1, mid = &v0;
    } else if (y2 <= y1) {
      lo = &v2, hi = &v0;
    } else {
      lo = &v1, mid = &v2, hi = &v0;
    }
    const float bot_dx = mid->x - lo->x, bot_dy = mid->y - lo->y;
    const float maj_dx = hi->x - lo->x, maj_dy = hi->y - lo->y;
    const float ooa = 1.0f / (maj_dx * bot_dy - bot_dx * maj_dy);
    const float xc = lo->x - 0.5f, yc = lo->y - 0.5f;
    const auto plane = [&](float lov, float midv, float hiv, float& a0, float& dadx, float& dady) {
      const float bot = midv - lov, maj = hiv - lov;
      dadx = (bot_dy * maj - bot * maj_dy) * ooa;
      dady = (maj_dx * bot - maj * bot_dx) * ooa;
      a0 = lov - (dadx * xc + dady * yc);
    };
    tri.x0 = 0.5f;
    tri.y0 = 0.5f;
    plane(lo->d, mid->d, hi->d, tri.d0, tri.dzdx, tri.dzdy);
    plane(lo->q, mid->q, hi->q, tri.q0, tri.dqdx, tri.dqdy);
  } else {
    const float e1d = v1.d - v0.d, e2d = v2.d - v0.d, e1q = v1.q - v0.q, e2q = v2.q - v0.q;
    tri.x0 = v0.x;
    tri.y0 = v0.y;
    tri.d0 = v0.d;
    tri.dzdx = (e1d * e2y - e2d * e1y) / det;
    tri.dzdy = (e2d * e1x - e1d * e2x) / det;
    tri.q0 = v0.q;
    tri.dqdx = (e1q * e2y - e2q * e1y) / det;
    tri.dqdy = (e2q * e1x - e1q * e2x) / det;
  }
  tri.ymin = std::fmin(std::fmin(v0.y, v1.y), v2.y);
  tri.ymax = std::fmax(std::fmax(v0.y, v1.y), v2.y);
  return tri;
}

bool covers(const SetupTriangle& t, float px, float py) {
  for (const SetupEdge& e : t.e) {
    float E = MTS_EDGE_FUNCTION(e.ax, e.ay, e.dx, e.dy, px, py);
    if (e.negate) E = -E;
    if (!MTS_EDGE_PASSES(E, e.owns)) return false;
  }
  return true;
}

namespace {

float library_log(float x) {
  return shader_log(LogForm::library, x);
}
float library_log2(float x) {
  return shader_log2(LogForm::library, x);
}
float llvmpipe_log(float x) {
  return shader_log(LogForm::llvmpipe, x);
}
float llvmpipe_log2(float x) {
  return shader_log2(LogForm::llvmpipe, x);
}
DP_MEDIUMP_FRAGMENT_DEFINE(mediump_depth_library, library_log, library_log2)
DP_MEDIUMP_FRAGMENT_DEFINE(mediump_depth_llvmpipe, llvmpipe_log, llvmpipe_log2)

// The fragment shader's depth at eye distance w = 1/q (fragment-stage depth), before
// gl_FragDepth's clamp; from_near_plus_one is Cesium's varying. In mediump from q itself
// (interface/mediump_fragment.h).
float shader_depth(const Scene& s, const TechniqueInfo& ti, const ProbeConstants& pc, float q,
                   float w, float from_near_plus_one) {
  if (s.pipeline.shader_precision != ShaderPrecision::highp)
    return (s.pipeline.log == LogForm::llvmpipe ? mediump_depth_llvmpipe : mediump_depth_library)(
        static_cast<int>(ti.fragment), q, pc.near, pc.range, pc.far, pc.log_k, pc.log_L,
        pc.threejs_fc, pc.cesium_inv_log2, static_cast<int>(s.pipeline.shader_precision));
  switch (ti.fragment) {
    case FragmentDepth::linear:
      return (w - pc.near) / pc.range;
    case FragmentDepth::w_buffer:
      return w / pc.far;
    case FragmentDepth::threejs_log:  // log2(vFragDepth) * logDepthBufFC * 0.5
      return (shader_log2(s.pipeline.log, 1.0f + w) * pc.threejs_fc) * 0.5f;
    case FragmentDepth::cesium_log:  // log2(depth) * czm_oneOverLog2FarDepthFromNearPlusOne
      return shader_log2(s.pipeline.log, from_near_plus_one) * pc.cesium_inv_log2;
    default:
      return shader_log(s.pipeline.log, pc.log_k * w + 1.0f) / pc.log_L;
  }
}

}  // namespace

float depth_of_value(const Scene& s, const EvalPair& pair, const ProbeConstants& pc, float v) {
  const TechniqueInfo& ti = info(depth_path(s, pair.technique));
  if (ti.from != DepthFrom::fragment) return v;
  const float w = 1.0f / v;
  const float d = shader_depth(s, ti, pc, v, w, (w - pc.near) + 1.0f);
  return std::fmin(std::fmax(d, 0.0f), 1.0f);
}

FragmentStatus fragment_code(const Scene& s, const EvalPair& pair, const StorageFormat& fmt,
                             const ProbeConstants& pc, const SetupTriangle& t, float px, float py,
                             uint32_t& code, bool biased, float* value, float* depth) {
  const TechniqueInfo& ti = info(depth_path(s, pair.technique));
  const float tx = px - t.x0, ty = py - t.y0;
  // The plane at the pixel, in the set-up's form (docs/spec.md 2.4).
  const auto at = [&](float c0, float dx, float dy) {
    switch (s.pipeline.plane) {
      case PlaneForm::origin_fma:
        return std::fma(dy, ty, std::fma(dx, tx, c0));
      case PlaneForm::origin_quads: {  // from the 2x2 quad's even corner, then increments
        const bool odd_x = static_cast<int>(tx) & 1, odd_y = static_cast<int>(ty) & 1;
        const float z0 =
            (c0 + dx * (tx - (odd_x ? 1.0f : 0.0f))) + dy * (ty - (odd_y ? 1.0f : 0.0f));
        const float z1 = odd_x ? z0 + dx : z0;
        return odd_y ? z1 + dy : z1;
      }
      case PlaneForm::vertex:
        break;
    }
    return (c0 + dx * tx) + dy * ty;
  };
  float d;
  if (ti.from == DepthFrom::fragment) {
    const float q = at(t.q0, t.dqdx, t.dqdy);
    if (value) *value = q;
    const float w = 1.0f / q;
    if (!std::isfinite(w)) return fragment_non_finite;
    // Cesium's varying, and its discard in place of the clip volume's near and far (writeLogDepth)
    const float from_near_plus_one = (w - pc.near) + 1.0f;
    if (ti.fragment == FragmentDepth::cesium_log) {
      if (from_near_plus_one <= 0.9999999f || from_near_plus_one > pc.cesium_far1)
        return fragment_clipped;
    } else if (w < pc.near || w > pc.far) {
      return fragment_clipped;
    }
    d = shader_depth(s, ti, pc, q, w, from_near_plus_one);
    if (std::isnan(d)) return fragment_non_finite;
    d = std::fmin(std::fmax(d, 0.0f), 1.0f);
  } else {
    d = at(t.d0, t.dzdx, t.dzdy);
    if (value) *value = d;
    if (!std::isfinite(d)) return fragment_non_finite;
    if (!(d >= 0.0f && d <= 1.0f)) return fragment_clipped;
    if (biased) d = std::fmin(std::fmax(d + t.bias, 0.0f), 1.0f);  // the offset, then the clamp
  }
  if (depth) *depth = d;
  code = t.adversary != 0 && fmt.spec().kind == DF_KIND_UNORM
             ? dp_adv_unorm_code(d, fmt.spec(), t.adversary > 0,
                                 adversary_code_slack(bound_model(s.pipeline.envelope)))
             : fmt.encode(d);
  return fragment_ok;
}

}  // namespace depthprec
