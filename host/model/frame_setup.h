// What the host hands the GPU for one probe (z, s) of one pair: the projection and technique
// constants, and per frame the model-view (or P*MV) matrix of each plane, built as an
// application would (docs/spec.md 2.1, 5.1): in binary32, or in binary64 rounded once at the end.
#pragma once

#include <array>
#include <cmath>
#include <map>
#include <vector>

#include "host/model/matrix.h"
#include "host/model/scene.h"
#include "host/model/vertex_stage.h"
#include "interface/mts_layout.h"

namespace depthprec {

// The object coordinate of grid line i of a plane of g x g quads over [-0.5, 0.5]^2, in binary32
// as the kernels' vertex stage computes it (kernels/mts/setup/vertex.cl).
inline float grid_coordinate(int g, int i) {
  return static_cast<float>(i) / static_cast<float>(g) - 0.5f;
}

// Orientations sampled at run time (worst-case sampling's rounds, host/mts/worst_case.h; no scene
// file says them): per distance of plane A, the frames' angle triples. A distance not listed
// takes the paper's path (frame_angles).
struct Orientations {
  std::map<double, std::vector<Angles>> at;
  // A round's chunk (host/mts/refinement.h): each distance is probed once, at its answer, and
  // again only after one of the orientations fought there, so caches an evaluator keeps per
  // distance for later probes do not pay for themselves.
  bool chunk = false;
};

// Per-probe constants, packed as the kernels read them (interface/mts_layout.h: MTS_PROBE_STRIDE
// floats, P then the C_* offsets).
struct ProbeConstants {
  Mat4f P{};
  Mat4d P_full{};  // P in the matrix precision before rounding to binary32
  float near = 0, far = 0, range = 0, log_k = 0, log_L = 0;
  // The engines' log depth constants (MTS_C_THREEJS_FC, MTS_C_CESIUM_FAR1, MTS_C_CESIUM_INV_LOG2)
  // and the vertex stage's log form (MTS_C_VERTEX_LOG: MTS_VERTEX_LOG_*).
  float threejs_fc = 0, cesium_far1 = 0, cesium_inv_log2 = 0;
  int vertex_log = MTS_VERTEX_LOG_GILG;
  bool depth_gl = false;        // the pair's depth range is OpenGL's (MTS_C_DEPTH_GL)
  unsigned forms = 0;           // the pipeline's vertex-stage forms, F_* bits (MTS_C_FORMS)
  int snap_bits = 0;            // the pipeline's sub-pixel snapping (MTS_C_SNAP_BITS)
  std::array<float, 3> view{};  // the view's translation under MTS_F_VIEW_TRANSLATE (MTS_C_VIEW_X)
  // The eye's relative-to-eye parts (interface/relative_to_eye.h; MTS_C_EYE_HIGH_X, _LOW_X)
  std::array<float, 3> eye_high{}, eye_low{};
  double layer_near = 0, layer_far = 0;  // the sub-frustum used (layered), else near/far
  double z = 0;  // plane A's distance: the frames' orientations are per distance (Orientations)
  // The frames' angle triples at z where they are sampled (Orientations), else empty: the path
  std::vector<Angles> orientations;
  // An envelope's adversary (pipeline.envelope, interface/adversary.h): the direction of the
  // window depth towards the far side of the pair's depth test (+1, -1 under GEQUAL; 0: no
  // envelope), whether the reciprocal of w takes its faithful rounding that way, the relative
  // interpolation error it takes.
  float adv_far = 0, adv_reciprocal = 0, adv_interpolation = 0;
  // For the set-up of plane A (towards the far side: +1), plane B (the near side: -1), or of a
  // plane no adversary moves (0: depth bias, the audit).
  std::array<float, MTS_PROBE_STRIDE> packed(int plane) const;
};

// orientations: the frames' sampled ones, where z has them; the paper's path elsewhere.
ProbeConstants probe_constants(const Scene& scene, const EvalPair& pair, double z,
                               const Orientations& orientations = {});

// Whether the GPU adds the view's translation after the model matrix (vertex_path model_then_view,
// the camera away from the world origin): MTS_F_VIEW_TRANSLATE in the probe constants.
bool view_translated_on_gpu(const Scene& scene);

// The rotation angles of frame k of the paper's path in radians (binary64; the animation input,
// not GPU arithmetic).
Angles frame_angles(const Scene& scene, int frame);
// The rotation angles of frame k at plane A's distance pc.z: the sampled orientations the probe
// constants carry (worst-case sampling), else the path's.
Angles frame_orientation(const Scene& scene, const ProbeConstants& pc, int frame);

// What the GPU gets for a plane at requested distance D (binary64: z for plane A, z + s for
// plane B) in frame k (host/model/vertex_stage.h): its model matrix with the world translation,
// built in the matrix precision from the frame's angles, and the camera's view (a translation,
// none at the world origin); camera-relative the model with its translation formed in binary64
// and no view; relative to eye its world matrix in binary64 and the camera's position. tilt
// (radians, `bias --tilt`) turns the plane about the view's x axis on top of the frame's
// rotation, and sizes it in each frame to cover the view still (host/model/tilted_plane.h).
VertexStage plane_vertex_stage(const Scene& scene, const ProbeConstants& pc, double D, int frame,
                               double tilt = 0);

// plane_vertex_stage's matrix: the model-view, or P * MV under compose = premultiplied (not
// relative to eye, where the GPU gets world positions).
Mat4f plane_matrix(const Scene& scene, const ProbeConstants& pc, double D, int frame,
                   double tilt = 0);

// Appends what the set-up kernels read of one plane (plane_words(scene) floats): plane_matrix, or
// under relative_to_eye the world matrix's 16 doubles in 32 floats' place.
void append_plane_words(std::vector<float>& words, const Scene& scene, const ProbeConstants& pc,
                        double D, int frame, double tilt = 0);
size_t plane_words(const Scene& scene);  // MTS_MAT_STRIDE, or MTS_WORLD_MAT_STRIDE

// The vertex stage as the set-up kernels read it (kernels/mts/setup/vertex.cl): one plane's words
// (append_plane_words, plane_words(scene) floats from `words`) with the probe constants' view
// translation (MTS_F_VIEW_TRANSLATE) and eye. vertex_clip of it is the kernels' clip position.
VertexStage read_plane_words(const Scene& scene, const ProbeConstants& pc, const float* words);

// The distance plane_matrix builds a plane from when tilt is 0: D rounded to binary32 under
// matrix_precision float, D itself under double. Two distances with the same value give the same
// matrix in every frame.
double plane_matrix_distance(const Scene& scene, double D);

// The model-view of a plane at distance D in frame k of plane A's distance pc.z in binary64, never
// rounded, in eye space whatever world_position says (the plane D in front of the camera): the
// exact geometry of the storage-limited pipeline. Row-major.
Mat4d model_matrix_f64(const Scene& scene, const ProbeConstants& pc, double D, int frame);

// The side of the measurement's square plane at eye distance D: plane_margin times the view's
// height there, 2 D tan(fov_y / 2).
double plane_side(const Scene& scene, double D);
// The nearest eye distance a vertex of that plane reaches over the rotation cube: a vertex (x, y)
// in [-0.5, 0.5]^2 sits at w = D - side (R20 x + R21 y), and the third row of R = Rx Ry Rz has
// |R20 x + R21 y| <= sin r (r = rotation_range_deg). Wide views reach nearer: about D / 1.0034 at
// the default 10 degrees, D / 1.023 at 60.
double nearest_vertex_distance(const Scene& scene, double D);
// The farthest, D + side sin r.
double farthest_vertex_distance(const Scene& scene, double D);

// Away from the world origin with world positions in the vertex stage (transform absolute,
// compose separate; or relative_to_eye, whose low parts are binary32 below 65536): how far
// rounding a vertex's world coordinates to binary32 can move the depth of the two planes at a
// pixel, together. Per plane, half the spacing at each coordinate's largest magnitude
// (|world_position| + z + side, at most 65536 relative to eye): along the view (z) directly, across
// it (x, y) through the plane's slope, at most tan r / cos r over the rotation cube. An MTS below
// it was decided by where the planes' vertices fell between grid points (docs/mts.md, "Below the
// world grid"). 0 elsewhere (at the origin vertex_bound says it).
double world_grid_reach(const Scene& scene, double z);

// fl32(z + s) - fl32(z): the separation the pipeline really sees, exact in binary64.
double seen_separation(double z, double s);
// The vertex-precision bound (docs/spec.md 5.3): the distance from z to the midpoint between
// fl32(z) and the next binary32 above; for a smaller s, fl32(z + s) == fl32(z) and the planes
// coincide. For a z that is a binary32 this is half its spacing.
double vertex_bound(double z);

}  // namespace depthprec
