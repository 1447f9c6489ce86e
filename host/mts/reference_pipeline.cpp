#include "host/mts/reference_pipeline.h"

#include <array>
#include <cmath>
#include <vector>

#include "host/model/frame_setup.h"
#include "host/model/shader_log.h"
#include "host/runtime/kernel_variant.h"
#include "interface/bias_formula.h"
#include "interface/snap.h"

namespace depthprec {

namespace {

DP_SNAP_WINDOW_DEFINE(snap_window, std::fabs, std::rint)

struct Vertex {
  float x, y, d, q;
  std::array<float, 4> c;  // clip coordinates (the clip stage's input)
  int id;                  // edges are evaluated from their lower-id vertex
};

// llvmpipe's clip stage (docs/spec.md 2, pipeline.clip; kernels/mts/setup.cl clip_fan has the
// account): a vertex's clip mask, bit k outside plane k of x <= w, x >= -w, y <= w, y >= -w.
unsigned clip_mask(const std::array<float, 4>& c) {
  return (c[0] > c[3] ? 1u : 0u) | (0.0f > c[0] + c[3] ? 2u : 0u) | (c[1] > c[3] ? 4u : 0u) |
         (0.0f > c[1] + c[3] ? 8u : 0u);
}

float clip_dist(const std::array<float, 4>& c, int k) {
  static const float planes[4][4] = {{-1, 0, 0, 1}, {1, 0, 0, 1}, {0, -1, 0, 1}, {0, 1, 0, 1}};
  const float* p = planes[k];
  return ((c[0] * p[0] + c[1] * p[1]) + c[2] * p[2]) + c[3] * p[3];
}

// The polygon a triangle (with the union of its vertices' clip masks) becomes; empty when a
// distance is not finite. New vertices get ids from next_id on, and window x, y snapped to
// 2^-snap_bits pixel.
std::vector<Vertex> clip_polygon(std::vector<Vertex> poly, unsigned mask, float hw, float hh,
                                 bool gl, int snap_bits, int next_id) {
  for (int k = 0; k < 4 && poly.size() >= 3; ++k) {
    if (!((mask >> k) & 1u)) continue;
    std::vector<Vertex> out;
    poly.push_back(poly[0]);
    Vertex prev = poly[0];
    float dp_prev = clip_dist(prev.c, k);
    if (!std::isfinite(dp_prev)) return {};
    for (size_t i = 1; i < poly.size(); ++i) {
      const Vertex cur = poly[i];
      const float dp = clip_dist(cur.c, k);
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
        const Vertex &o = leaving ? cur : prev, &in = leaving ? prev : cur;
        const float t = leaving ? dp / (dp - dp_prev) : dp_prev / (dp_prev - dp);
        Vertex n{};
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

struct Edge {
  float ax, ay, dx, dy;
  bool negate, owns;
};

struct Triangle {
  Edge e[3];
  bool valid;
  float x0, y0, d0, dzdx, dzdy, q0, dqdx, dqdy, ymin, ymax;
  float bias;  // the depth bias added to its fragments (plane B of the bias measurement)
};

// What a plane's triangles add to their fragments' depth: nothing (the MTS planes), or a depth
// bias (interface/bias_formula.h depth_bias's arguments).
struct BiasTerms {
  float units_term = 0, factor = 0, clamp = 0;
  int float_rule = 0, slope_form = BIAS_SLOPE_MAX;
};

enum Status { ok = 0, clipped = 1, non_finite = 2, uncovered = 3 };

struct Plane {
  std::vector<Triangle> tris;
  bool non_finite = false;
};

// flip: each quad split along its other diagonal (b to d), as kernels/mts/setup.cl's
// triangle_vertices16 does for the bias measurement's overlay; bias: its offsets, or none.
// words: what the set-up kernel reads of the plane (append_plane_words): its model-view (or
// P * MV), or relative to eye its binary64 world matrix.
Plane setup_plane(const Scene& s, const EvalPair& pair, const ProbeConstants& pc,
                  const std::vector<float>& words, bool flip = false,
                  const BiasTerms* bias = nullptr) {
  const TechniqueInfo& ti = info(depth_path(s, pair.technique));
  const bool gl = pair.depth_range == DepthRange::gl;
  const int g = s.plane_subdivisions;
  const float hw = 0.5f * static_cast<float>(s.viewport_w);
  const float hh = 0.5f * static_cast<float>(s.viewport_h);
  Plane plane;
  std::vector<Vertex> v((g + 1) * (g + 1));
  for (int j = 0; j <= g; ++j) {
    for (int i = 0; i <= g; ++i) {
      const float obj[4] = {grid_coordinate(g, i), grid_coordinate(g, j), 0.0f, 1.0f};
      float clip[4];
      plane_vertex_clip(s, pc, words, obj, s.pipeline.vertex, clip);
      if (ti.from == DepthFrom::vertex_log)
        clip[2] = vertex_log_clip_z(pc, s.pipeline.log, gl, clip[3]);
      const float inv_w = 1.0f / clip[3];
      float ndc[3];
      for (int r = 0; r < 3; ++r)
        ndc[r] = s.pipeline.divide == Divide::exact ? clip[r] / clip[3] : clip[r] * inv_w;
      Vertex& vx = v[j * (g + 1) + i];
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
      vx.id = j * (g + 1) + i;
      if (!std::isfinite(vx.x) || !std::isfinite(vx.y) || !std::isfinite(vx.q))
        plane.non_finite = true;
      if (ti.from != DepthFrom::fragment && !std::isfinite(vx.d)) plane.non_finite = true;
    }
  }
  // One triangle from its vertices (in the order the set-up takes them).
  const auto emit = [&](const Vertex* tv[3]) {
    Triangle tri{};
    for (int e = 0; e < 3; ++e) {
      const Vertex &va = *tv[e], &vb = *tv[(e + 1) % 3];
      const Vertex& lo = va.id < vb.id ? va : vb;
      const Vertex& hi = va.id < vb.id ? vb : va;
      tri.e[e] = {lo.x, lo.y, hi.x - lo.x, hi.y - lo.y, va.id > vb.id, false};
    }
    const Vertex& p2 = *tv[2];
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
    const Vertex &v0 = *tv[0], &v1 = *tv[1], &v2 = *tv[2];
    const float e1x = v1.x - v0.x, e1y = v1.y - v0.y, e2x = v2.x - v0.x, e2y = v2.y - v0.y;
    const float det = e1x * e2y - e2x * e1y;
    if (s.pipeline.plane == PlaneForm::origin_fma) {
      // llvmpipe's set-up: (v1, v0, v2) for a negative area, gradients times 1/area, the value at
      // the framebuffer origin, evaluated at integer pixel coordinates (x0 = y0 = 0.5).
      const Vertex &u0 = det < 0.0f ? v1 : v0, &u1 = det < 0.0f ? v0 : v1, &u2 = v2;
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
    } else if (s.pipeline.plane == PlaneForm::origin_quads) {
      // softpipe's set-up: sorted by y as setup_sort_vertices does, ebot = vmid - vmin, emaj =
      // vmax - vmin, gradients times 1/area, the value at the origin from vmin (x0 = y0 = 0.5).
      const float y0 = v0.y, y1 = v1.y, y2 = v2.y;
      const Vertex* lo = &v0;
      const Vertex* mid = &v1;
      const Vertex* hi = &v2;
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
      const auto plane = [&](float lov, float midv, float hiv, float& a0, float& dadx,
                             float& dady) {
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
    tri.bias = 0;
    if (bias) {
      tri.bias =
          depth_bias(bias->units_term, bias->float_rule, bias->factor, bias->clamp,
                     depth_bias_slope(tri.dzdx, tri.dzdy, bias->slope_form), v0.d, v1.d, v2.d);
      if (!std::isfinite(tri.bias)) plane.non_finite = true;
    }
    plane.tris.push_back(tri);
  };
  for (int t = 0; t < 2 * g * g; ++t) {
    const int quad = t / 2, qi = quad % g, qj = quad / g;
    const int a = qj * (g + 1) + qi, b = a + 1, c = a + g + 2, d = a + g + 1;
    int vi[3] = {a, (t & 1) ? c : b, (t & 1) ? d : c};
    if (flip) {
      const int fb[3] = {a, b, d}, fo[3] = {b, c, d};
      for (int k = 0; k < 3; ++k) vi[k] = (t & 1) ? fo[k] : fb[k];
    }
    const Vertex* tv[3] = {&v[vi[0]], &v[vi[1]], &v[vi[2]]};
    if (s.pipeline.clip == ClipForm::none) {
      emit(tv);
      continue;
    }
    const unsigned m0 = clip_mask(tv[0]->c), m1 = clip_mask(tv[1]->c), m2 = clip_mask(tv[2]->c);
    if (!(m0 | m1 | m2)) {
      emit(tv);
    } else if (!(m0 & m1 & m2)) {  // all outside one plane: culled
      const std::vector<Vertex> poly =
          clip_polygon({*tv[0], *tv[1], *tv[2]}, m0 | m1 | m2, hw, hh, gl, s.pipeline.snap_bits,
                       (g + 1) * (g + 1) + 8 * t);
      for (size_t i = 2; i < poly.size(); ++i) {
        const Vertex* f[3] = {&poly[i - 1], &poly[i], &poly[0]};
        emit(f);
      }
    }
  }
  return plane;
}

bool inside(const Triangle& t, float px, float py) {
  for (const Edge& e : t.e) {
    float E = e.dx * (py - e.ay) - e.dy * (px - e.ax);
    if (e.negate) E = -E;
    if (!(E > 0.0f || (E == 0.0f && e.owns))) return false;
  }
  return true;
}

class PlaneRow {
 public:
  PlaneRow(const Plane& p, float py) : plane_(p) {
    for (size_t t = 0; t < p.tris.size(); ++t)
      if (p.tris[t].valid && p.tris[t].ymin <= py && py <= p.tris[t].ymax)
        cand_.push_back(static_cast<int>(t));
  }
  // The lowest-index triangle whose edge tests pass (candidates are in index order).
  int find(float px, float py) const {
    for (int c : cand_)
      if (inside(plane_.tris[c], px, py)) return c;
    return -1;
  }

 private:
  const Plane& plane_;
  std::vector<int> cand_;
};

Status fragment(const Scene& s, const EvalPair& pair, const StorageFormat& fmt,
                const ProbeConstants& pc, const Triangle& t, float px, float py, uint32_t& code,
                bool biased = false) {
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
    const float w = 1.0f / q;
    if (!std::isfinite(w)) return non_finite;
    // Cesium's varying, and its discard in place of the clip volume's near and far (writeLogDepth)
    const float from_near_plus_one = (w - pc.near) + 1.0f;
    if (ti.fragment == FragmentDepth::cesium_log) {
      if (from_near_plus_one <= 0.9999999f || from_near_plus_one > pc.cesium_far1) return clipped;
    } else if (w < pc.near || w > pc.far) {
      return clipped;
    }
    switch (ti.fragment) {
      case FragmentDepth::linear:
        d = (w - pc.near) / pc.range;
        break;
      case FragmentDepth::w_buffer:
        d = w / pc.far;
        break;
      case FragmentDepth::threejs_log:  // log2(vFragDepth) * logDepthBufFC * 0.5
        d = (shader_log2(s.pipeline.log, 1.0f + w) * pc.threejs_fc) * 0.5f;
        break;
      case FragmentDepth::cesium_log:  // log2(depth) * czm_oneOverLog2FarDepthFromNearPlusOne
        d = shader_log2(s.pipeline.log, from_near_plus_one) * pc.cesium_inv_log2;
        break;
      default:
        d = shader_log(s.pipeline.log, pc.log_k * w + 1.0f) / pc.log_L;
        break;
    }
    if (std::isnan(d)) return non_finite;
    d = std::fmin(std::fmax(d, 0.0f), 1.0f);
  } else {
    d = at(t.d0, t.dzdx, t.dzdy);
    if (!std::isfinite(d)) return non_finite;
    if (!(d >= 0.0f && d <= 1.0f)) return clipped;
    if (biased) d = std::fmin(std::fmax(d + t.bias, 0.0f), 1.0f);  // the offset, then the clamp
  }
  code = fmt.encode(d);
  return ok;
}

}  // namespace

FrameCodes reference_frame(const Scene& s, const EvalPair& pair, const Probe& probe, int frame) {
  const StorageFormat fmt = s.storage_format(pair);
  const ProbeConstants pc = probe_constants(s, pair, probe.z);
  std::vector<float> wa, wb;
  append_plane_words(wa, s, pc, probe.z, frame);
  append_plane_words(wb, s, pc, probe.z + probe.s, frame);
  const Plane a = setup_plane(s, pair, pc, wa);
  const Plane b = setup_plane(s, pair, pc, wb);
  const float ox = static_cast<float>((s.viewport_w - s.kernel_w) / 2);
  const float oy = static_cast<float>((s.viewport_h - s.kernel_h) / 2);
  FrameCodes fc;
  fc.width = s.kernel_w;
  fc.height = s.kernel_h;
  for (int y = 0; y < s.kernel_h; ++y) {
    const float py = oy + static_cast<float>(y) + 0.5f;
    PlaneRow ra(a, py), rb(b, py);
    for (int x = 0; x < s.kernel_w; ++x) {
      const float px = ox + static_cast<float>(x) + 0.5f;
      uint32_t ca = 0, cb = 0;
      const int ta = ra.find(px, py), tb = rb.find(px, py);
      Status sa = ta < 0 ? uncovered : fragment(s, pair, fmt, pc, a.tris[ta], px, py, ca);
      Status sb = tb < 0 ? uncovered : fragment(s, pair, fmt, pc, b.tris[tb], px, py, cb);
      if (a.non_finite) sa = non_finite;
      if (b.non_finite) sb = non_finite;
      fc.code_a.push_back(ca);
      fc.code_b.push_back(cb);
      fc.status_a.push_back(static_cast<uint8_t>(sa));
      fc.status_b.push_back(static_cast<uint8_t>(sb));
    }
  }
  return fc;
}

BiasFrame reference_biased_frame(const Scene& s, const EvalPair& pair, const ReferenceBias& bias,
                                 double z, int frame) {
  const StorageFormat fmt = s.storage_format(pair);
  const ProbeConstants pc = probe_constants(s, pair, z);
  std::vector<float> m;
  append_plane_words(m, s, pc, z, frame, bias.tilt);
  BiasTerms terms;
  terms.units_term = bias.units_term;
  terms.float_rule = bias.float_rule;
  terms.factor = bias.factor;
  terms.clamp = bias.clamp;
  terms.slope_form = bias.slope_form;
  const Plane a = setup_plane(s, pair, pc, m);
  const Plane b = setup_plane(s, pair, pc, m, true, &terms);
  const bool greater = info(depth_path(s, pair.technique)).greater;
  const float ox = static_cast<float>((s.viewport_w - s.kernel_w) / 2);
  const float oy = static_cast<float>((s.viewport_h - s.kernel_h) / 2);
  BiasFrame out;
  if (a.non_finite || b.non_finite) {
    out.non_finite = true;
    return out;
  }
  for (int y = 0; y < s.kernel_h; ++y) {
    const float py = oy + static_cast<float>(y) + 0.5f;
    PlaneRow ra(a, py), rb(b, py);
    for (int x = 0; x < s.kernel_w; ++x) {
      const float px = ox + static_cast<float>(x) + 0.5f;
      const int ta = ra.find(px, py), tb = rb.find(px, py);
      if (ta < 0 || tb < 0) {
        out.uncovered = true;
        continue;
      }
      uint32_t ca = 0, cb = 0;
      const Status sa = fragment(s, pair, fmt, pc, a.tris[ta], px, py, ca);
      const Status sb = fragment(s, pair, fmt, pc, b.tris[tb], px, py, cb, true);
      if (sa == non_finite || sb == non_finite) {
        out.non_finite = true;
        continue;
      }
      if (sa == clipped || sb == clipped) {
        out.clipped = true;
        continue;
      }
      if (!bias.or_equal && ca == fmt.encode(greater ? 0.0f : 1.0f)) {
        out.uncovered = true;  // A fails its own test against the cleared buffer: not drawn
        continue;
      }
      const bool passes =
          greater ? (bias.or_equal ? cb >= ca : cb > ca) : (bias.or_equal ? cb <= ca : cb < ca);
      if (!passes) out.fight = true;
    }
  }
  return out;
}

}  // namespace depthprec
