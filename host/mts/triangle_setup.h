// One triangle through the emulated pipeline on the host, after its vertex stage: the clip stage,
// the set-up (edges, ownership, the depth and 1/w planes in the pipeline's form) and each pixel's
// coverage and stored code, in the arithmetic forms the kernels use (kernels/mts.cl's header lists
// them). The MTS reference (host/mts/reference_pipeline.cpp) runs its plane grids through these,
// the scene audit (host/audit/audit_setup.h) a user's triangles.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "host/model/frame_setup.h"
#include "host/model/scene.h"

namespace depthprec {

// A vertex after the vertex stage: window x, y (snapped), depth and 1/w, its clip coordinates (the
// clip stage's input), and an id: an edge is evaluated from its lower-id vertex, so two triangles
// sharing it compute the same value.
struct SetupVertex {
  float x = 0, y = 0, d = 0, q = 0;
  std::array<float, 4> c{};
  int id = 0;
};

struct SetupEdge {
  float ax = 0, ay = 0, dx = 0, dy = 0;
  bool negate = false, owns = false;
};

// A set-up triangle: edges, whether it rasterises at all (non-zero finite area), its depth and 1/w
// planes (anchored at x0, y0 in the pipeline's form), its y-range, and the depth bias its
// fragments get (zero unless the caller sets one).
struct SetupTriangle {
  SetupEdge e[3];
  bool valid = false;
  float x0 = 0, y0 = 0, d0 = 0, dzdx = 0, dzdy = 0, q0 = 0, dqdx = 0, dqdy = 0, ymin = 0, ymax = 0;
  float bias = 0;
  // The direction an envelope's adversary moves its stored codes (MTS_T_ADVERSARY): +1 up, -1
  // down, 0 none.
  float adversary = 0;
};

// A fragment's fate (interface/mts_layout.h MTS_S_*).
enum FragmentStatus { fragment_ok = 0, fragment_clipped = 1, fragment_non_finite = 2 };

// The clip planes in the order llvmpipe's clip stage takes them (Mesa 22.3 draw_cliptest_tmp.h):
// x <= w, x >= -w, y <= w, y >= -w, then the depth range's near and far sides (z >= -w under
// OpenGL's range, z >= 0 under zero_to_one; z <= w).
constexpr unsigned kClipPlanesXY = 0xfu, kClipPlanesZ = 0x30u;
// Bit k set when c is outside clip plane k (planes: those asked, kClipPlanes*).
unsigned clip_mask(const std::array<float, 4>& c, bool depth_gl, unsigned planes);

// The polygon a triangle (with the union of its vertices' clip masks) becomes, clipped by
// Sutherland-Hodgman plane by plane in order; empty when a distance is not finite. New vertices get
// ids from next_id on, window x, y snapped to 2^-snap_bits pixel (hw, hh: half the viewport).
std::vector<SetupVertex> clip_polygon(std::vector<SetupVertex> poly, unsigned mask, float hw,
                                      float hh, bool depth_gl, int snap_bits, int next_id);

// The vertex stage after the clip position: the divide, the window transform (depth by the depth
// range) and snapping, as the scene's pipeline says.
// reciprocal: an envelope's faithful rounding of 1/w (interface/adversary.h), +1 the one above,
// -1 the one below, 0 the correctly rounded one.
SetupVertex window_vertex(const Scene& scene, bool depth_gl, const float clip[4], int id,
                          int reciprocal = 0);

// The one rule for a vertex the set-up cannot use (kernels/mts/setup/vertex.cl's nonfinite): its
// window x, y or 1/w is not finite, or its depth where the set-up interpolates depth (every depth
// path but the fragment stage's, which interpolates 1/w alone).
bool vertex_non_finite(const SetupVertex& v, bool depth_interpolated);

// The set-up of the triangle tv[0..2] in the order the set-up takes them.
SetupTriangle setup_triangle(const Pipeline& pipeline, const SetupVertex* const tv[3]);

// Whether pixel centre (px, py) is covered: every edge test passes, ties to the owning edge.
bool covers(const SetupTriangle& t, float px, float py);

// The fragment of t at pixel centre (px, py): its status, and when fragment_ok its stored code
// (biased: with t.bias added before the clamp), and where asked the interpolated value (depth, or
// q = 1/w) and the depth converted.
FragmentStatus fragment_code(const Scene& scene, const EvalPair& pair, const StorageFormat& fmt,
                             const ProbeConstants& pc, const SetupTriangle& t, float px, float py,
                             uint32_t& code, bool biased = false, float* value = nullptr,
                             float* depth = nullptr);

// The depth of interpolated value v, clamped into [0, 1] (a NaN to 0) as the kernels'
// depth_of_value16 gives it: v itself, or the fragment shader's depth at w = 1/v.
float depth_of_value(const Scene& scene, const EvalPair& pair, const ProbeConstants& pc, float v);

}  // namespace depthprec
