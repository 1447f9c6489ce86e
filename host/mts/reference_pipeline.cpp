#include "host/mts/reference_pipeline.h"

#include <array>
#include <cmath>
#include <vector>

#include "host/model/frame_setup.h"
#include "host/model/shader_log.h"
#include "host/mts/triangle_setup.h"
#include "host/runtime/kernel_variant.h"
#include "interface/adversary.h"
#include "interface/bias_formula.h"

namespace depthprec {

namespace {

// What a plane's triangles add to their fragments' depth: nothing (the MTS planes), or a depth
// bias (interface/bias_formula.h depth_bias's arguments).
struct BiasTerms {
  float units_term = 0, factor = 0, clamp = 0;
  int float_rule = 0, slope_form = BIAS_SLOPE_MAX;
};

enum Status { ok = 0, clipped = 1, non_finite = 2, uncovered = 3 };
using Vertex = SetupVertex;

struct Plane {
  std::vector<SetupTriangle> tris;
  bool non_finite = false;
};

// flip: each quad split along its other diagonal (b to d), as kernels/mts/setup.cl's
// triangle_vertices16 does for the bias measurement's overlay; bias: its offsets, or none.
// words: what the set-up kernel reads of the plane (append_plane_words): its model-view (or
// P * MV), or relative to eye its binary64 world matrix; read as the kernel reads them
// (read_plane_words) into the vertex stage's description, whose clip positions vertex_clip gives.
// adversary: the plane's side under an envelope (ProbeConstants::packed's plane: +1 plane A, -1
// plane B, 0 none), as the set-up kernel reads it from MTS_C_ADV_DEPTH.
Plane setup_plane(const Scene& s, const EvalPair& pair, const ProbeConstants& pc,
                  const std::vector<float>& words, bool flip = false,
                  const BiasTerms* bias = nullptr, int adversary = 0) {
  const float adv_depth = pc.adv_far * static_cast<float>(adversary);
  const TechniqueInfo& ti = info(depth_path(s, pair.technique));
  const bool gl = pair.depth_range == DepthRange::gl;
  const int g = s.plane_subdivisions;
  const float hw = 0.5f * static_cast<float>(s.viewport_w);
  const float hh = 0.5f * static_cast<float>(s.viewport_h);
  Plane plane;
  const VertexStage stage = read_plane_words(s, pc, words.data());
  std::vector<Vertex> v((g + 1) * (g + 1));
  for (int j = 0; j <= g; ++j) {
    for (int i = 0; i <= g; ++i) {
      const float obj[4] = {grid_coordinate(g, i), grid_coordinate(g, j), 0.0f, 1.0f};
      float clip[4];
      vertex_clip(stage, pc.P, obj, s.pipeline.vertex, clip);
      if (ti.from == DepthFrom::vertex_log)
        clip[2] = vertex_log_clip_z(pc, s.pipeline.log, gl, clip[3]);
      // the reciprocal's rounding that moves the depth the adversary's way (vertex.cl, the same)
      int reciprocal = 0;
      if (adv_depth != 0 && pc.adv_reciprocal != 0)
        reciprocal =
            dp_adv_reciprocal_up(ti.from == DepthFrom::fragment, clip[2], adv_depth) ? 1 : -1;
      Vertex& vx = v[j * (g + 1) + i];
      vx = window_vertex(s, gl, clip, j * (g + 1) + i, reciprocal);
      if (vertex_non_finite(vx, ti.from != DepthFrom::fragment)) plane.non_finite = true;
    }
  }
  // One triangle from its vertices (in the order the set-up takes them).
  const auto emit = [&](const Vertex* tv[3]) {
    SetupTriangle tri = setup_triangle(s.pipeline, tv);
    const Vertex &v0 = *tv[0], &v1 = *tv[1], &v2 = *tv[2];
    // the interpolation error the adversary takes (triangles.cl adversary_planes16, the same)
    tri.adversary = adv_depth;
    if (adv_depth != 0 && pc.adv_interpolation > 0) {
      const bool fragment = ti.from == DepthFrom::fragment;
      const int sign = dp_adv_value_sign(fragment, adv_depth);
      if (fragment)
        tri.q0 = dp_adv_shift_plane(tri.q0, v0.q, v1.q, v2.q, pc.adv_interpolation, sign);
      else
        tri.d0 = dp_adv_shift_plane(tri.d0, v0.d, v1.d, v2.d, pc.adv_interpolation, sign);
    }
    tri.bias = 0;
    // A triangle that covers no pixel (a degenerate fan triangle of the clip stage: gradients
    // 0/0) has no bias to apply, as kernels/bias.cl skips it.
    if (bias && tri.valid) {
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
    const unsigned m0 = clip_mask(tv[0]->c, gl, kClipPlanesXY),
                   m1 = clip_mask(tv[1]->c, gl, kClipPlanesXY),
                   m2 = clip_mask(tv[2]->c, gl, kClipPlanesXY);
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
      if (covers(plane_.tris[c], px, py)) return c;
    return -1;
  }

 private:
  const Plane& plane_;
  std::vector<int> cand_;
};

Status fragment(const Scene& s, const EvalPair& pair, const StorageFormat& fmt,
                const ProbeConstants& pc, const SetupTriangle& t, float px, float py,
                uint32_t& code, bool biased = false) {
  return static_cast<Status>(fragment_code(s, pair, fmt, pc, t, px, py, code, biased));
}

}  // namespace

FrameCodes reference_frame(const Scene& s, const EvalPair& pair, const Probe& probe, int frame) {
  const StorageFormat fmt = s.storage_format(pair);
  const ProbeConstants pc = probe_constants(s, pair, probe.z);
  std::vector<float> wa, wb;
  append_plane_words(wa, s, pc, probe.z, frame);
  append_plane_words(wb, s, pc, probe.z + probe.s, frame);
  const Plane a = setup_plane(s, pair, pc, wa, false, nullptr, +1);
  const Plane b = setup_plane(s, pair, pc, wb, false, nullptr, -1);
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
