#include "host/model/frame_setup.h"

#include <fmt/format.h>

#include <cmath>
#include <cstring>
#include <glm/glm.hpp>
#include <glm/gtc/constants.hpp>

#include "host/base/errors.h"
#include "host/model/bound_model.h"
#include "host/model/tilted_plane.h"
#include "interface/relative_to_eye.h"

namespace depthprec {

namespace {

template <class T>
using Mat = glm::mat<4, 4, T, glm::defaultp>;

// glm is column-major: m[c][r].
template <class T>
Mat4f to_row_major(const Mat<T>& m) {
  Mat4f out{};
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) out[r * 4 + c] = static_cast<float>(m[c][r]);
  return out;
}

// The same in binary64, never rounded (a binary32 matrix exactly).
template <class T>
Mat4d row_major_f64(const Mat<T>& m) {
  Mat4d out{};
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) out[r * 4 + c] = m[c][r];
  return out;
}

// z: the planes' distance, which an orthographic camera's view takes its size from: the
// perspective view's at z (half-height z tan(fov / 2)), so a plane covers the same pixels.
template <class T>
Mat<T> projection(const Scene& s, const EvalPair& pair, T n, T f, double z) {
  const T half_fov = static_cast<T>(s.fov_y_deg * glm::pi<double>() / 360.0);
  const bool ortho = pair.technique == Technique::orthographic;
  const T sy = ortho ? T(1) / (static_cast<T>(z) * std::tan(half_fov)) : T(1) / std::tan(half_fov);
  const T aspect = static_cast<T>(s.viewport_w) / static_cast<T>(s.viewport_h);
  const T sx = sy / aspect;
  const Row3<T> row = projection_row3<T>(pair.technique, pair.depth_range, n, f);
  Mat<T> P(T(0));
  P[0][0] = sx;
  P[1][1] = sy;
  P[2][2] = row.a;
  P[3][2] = row.b;
  if (ortho)
    P[3][3] = T(1);
  else
    P[2][3] = T(-1);
  return P;
}

// The distance a plane is built from in precision T: with tilt 0, all that D enters as.
template <class T>
T model_distance(double D) {
  return static_cast<T>(D);
}

// The translation of a plane's model matrix at distance D under transform t (binary64; docs/spec.md
// 2, "World position"): its centre in the world (absolute, relative_to_eye), or that minus the
// camera's position, formed in binary64 as camera-relative rendering forms it (camera_relative).
// At the world origin every transform gives (0, 0, -D).
std::array<double, 3> plane_translation(const Scene& s, double D, Transform t) {
  const auto& wp = s.world_position;
  const std::array<double, 3> centre = {wp[0], wp[1], wp[2] - D};
  if (t != Transform::camera_relative) return centre;
  return {centre[0] - wp[0], centre[1] - wp[1], centre[2] - wp[2]};
}

// The plane at distance D in frame orientation ang, translated to `at` (binary64, rounded to T
// here). tilt (radians) turns the plane about x on top of the frame's rotation; the plane is then
// no longer the centred square but, frame by frame, the rectangle that covers the view widened by
// plane_margin (host/model/tilted_plane.h): longer and wider on its far side than on its near one.
// Untilted planes are the square of docs/spec.md 5.1, built as they always were.
template <class T>
Mat<T> model(const Scene& s, double D, const Angles& ang, const std::array<double, 3>& at,
             double tilt = 0) {
  const T dist = model_distance<T>(D);
  const T half_fov = static_cast<T>(s.fov_y_deg * glm::pi<double>() / 360.0);
  const T side = static_cast<T>(s.plane_margin) * T(2) * dist * std::tan(half_fov);
  const double ax = tilt == 0 ? ang[0] : ang[0] + tilt;
  T side_x = side, side_y = side;
  Mat<T> offset(T(1));  // the rectangle's centre in the plane's own coordinates
  if (tilt != 0) {
    const auto rect = view_footprint(s, D, {ax, ang[1], ang[2]});
    if (!rect)
      throw Error(ExitCode::internal,
                  fmt::format("a plane at {} tilted {} degrees cannot cover the view turned "
                              "({}, {}, {}) radians (check_tilt lets no such tilt through)",
                              D, tilt * 180 / glm::pi<double>(), ang[0], ang[1], ang[2]));
    side_x = static_cast<T>(rect->width);
    side_y = static_cast<T>(rect->height);
    offset[3][0] = static_cast<T>(rect->cx);
    offset[3][1] = static_cast<T>(rect->cy);
  }
  const T cx = std::cos(static_cast<T>(ax)), sx = std::sin(static_cast<T>(ax));
  const T cy = std::cos(static_cast<T>(ang[1])), sy = std::sin(static_cast<T>(ang[1]));
  const T cz = std::cos(static_cast<T>(ang[2])), sz = std::sin(static_cast<T>(ang[2]));
  Mat<T> Rx(T(1)), Ry(T(1)), Rz(T(1)), S(T(1)), Tr(T(1));
  Rx[1][1] = cx;
  Rx[2][1] = -sx;
  Rx[1][2] = sx;
  Rx[2][2] = cx;
  Ry[0][0] = cy;
  Ry[2][0] = sy;
  Ry[0][2] = -sy;
  Ry[2][2] = cy;
  Rz[0][0] = cz;
  Rz[1][0] = -sz;
  Rz[0][1] = sz;
  Rz[1][1] = cz;
  S[0][0] = side_x;
  S[1][1] = side_y;
  for (int i = 0; i < 3; ++i) Tr[3][i] = static_cast<T>(at[i]);
  if (tilt != 0) return Tr * (Rx * Ry * Rz) * offset * S;
  return Tr * (Rx * Ry * Rz) * S;
}

// The MTS camera's view under transform t, in the matrix precision: it looks down -z without
// rotation, so its view is the translation -world_position under the absolute transform away
// from the world origin, and the identity elsewhere (camera-relative, the model's translation is
// relative to it already; relative to eye, the difference from its position is the GPU's).
ViewMatrix camera_view(const Scene& s, Transform t) {
  ViewMatrix v;
  if (t != Transform::absolute || s.at_world_origin()) return v;
  v.form = ViewMatrix::Form::translation;
  for (int i = 0; i < 3; ++i) v.m[i * 4 + 3] = -s.world_position[i];
  v.m = held_in(s.pipeline.matrix_precision, v.m);
  return v;
}

template <class T>
ProbeConstants constants(const Scene& s, const EvalPair& pair, double n64, double f64, double z) {
  ProbeConstants pc;
  const T n = static_cast<T>(n64), f = static_cast<T>(f64);
  const Mat<T> P = projection<T>(s, pair, n, f, z);
  pc.P = to_row_major(P);
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) pc.P_full[r * 4 + c] = static_cast<double>(P[c][r]);
  pc.near = static_cast<float>(n);
  pc.far = static_cast<float>(f);
  pc.range = static_cast<float>(f - n);
  const T k = static_cast<T>(s.params.log_k);
  pc.log_k = static_cast<float>(k);
  pc.log_L = static_cast<float>(std::log(k * f + T(1)));
  // The engines compute their constants in JavaScript, binary64 whatever the matrices' precision,
  // from the camera's near and far (n64, f64), and upload them as binary32: three.js
  // (WebGLRenderer.js) 2.0 / (Math.log(camera.far + 1.0) / Math.LN2); Cesium (UniformState.js)
  // far - near + 1.0 and 1.0 / CesiumMath.log2 of it, CesiumMath.log2 being Math.log2.
  pc.threejs_fc = static_cast<float>(2.0 / (std::log(f64 + 1.0) / M_LN2));
  const double cesium_far1 = f64 - n64 + 1.0;
  pc.cesium_far1 = static_cast<float>(cesium_far1);
  pc.cesium_inv_log2 = static_cast<float>(1.0 / std::log2(cesium_far1));
  static_assert(static_cast<int>(VertexLog::threejs) == MTS_VERTEX_LOG_THREEJS &&
                static_cast<int>(VertexLog::gilg) == MTS_VERTEX_LOG_GILG);
  pc.vertex_log = static_cast<int>(vertex_log(info(pair.technique)));
  pc.depth_gl = pair.depth_range == DepthRange::gl;
  const Pipeline& pipe = s.pipeline;
  const VertexPath path = vertex_path(pipe);
  pc.forms = (pipe.divide == Divide::exact ? MTS_F_DIVIDE_EXACT : 0u) |
             (path == VertexPath::premultiplied ? MTS_F_COMPOSE_PREMULT : 0u) |
             (pipe.viewport == ViewportForm::fma ? MTS_F_VIEWPORT_FMA : 0u) |
             (pipe.vertex == VertexForm::fma ? MTS_F_VERTEX_FMA : 0u) |
             (pipe.shader_precision == ShaderPrecision::mediump ? MTS_F_MEDIUMP : 0u) |
             (pipe.shader_precision == ShaderPrecision::es2_highp ? MTS_F_ES2_HIGHP : 0u);
  pc.snap_bits = pipe.snap_bits;
  if (!pipe.envelope.empty()) {
    const BoundModel& m = bound_model(pipe.envelope);
    // the depth test the kernel runs: a layered pair's is its layer mapping's
    const Technique run =
        pair.technique == Technique::layered ? s.params.layer_mapping : pair.technique;
    pc.adv_far = info(run).greater ? -1.0f : 1.0f;
    pc.adv_reciprocal = m.reciprocal_half_ulps > 1 ? 1.0f : 0.0f;
    // in binary32, rounded down: the adversary never takes more than the bound allows
    const double tolerance = s.interpolation_tolerance_or(m.interpolation_relative);
    pc.adv_interpolation = static_cast<float>(tolerance);
    if (pc.adv_interpolation > tolerance)
      pc.adv_interpolation = std::nextafter(pc.adv_interpolation, 0.0f);
  }
  // The view's translation, applied on the GPU after the model matrix (plane_vertex_stage's view:
  // model_then_view away from the origin); premultiplied, the host folds it into P * V * M.
  const auto& wp = s.world_position;
  if (view_translated_on_gpu(s)) {
    pc.forms |= MTS_F_VIEW_TRANSLATE;
    const ViewMatrix v = camera_view(s, pipe.transform);
    for (int i = 0; i < 3; ++i) pc.view[i] = static_cast<float>(v.m[i * 4 + 3]);
  }
  if (path == VertexPath::relative_to_eye)
    for (int i = 0; i < 3; ++i) dp_rte_encode(wp[i], &pc.eye_high[i], &pc.eye_low[i]);
  pc.layer_near = n64;
  pc.layer_far = f64;
  return pc;
}

}  // namespace

std::array<float, MTS_PROBE_STRIDE> ProbeConstants::packed(int plane) const {
  std::array<float, MTS_PROBE_STRIDE> out{};
  for (int i = 0; i < MTS_MAT_STRIDE; ++i) out[i] = P[i];
  out[MTS_C_NEAR] = near;
  out[MTS_C_FAR] = far;
  out[MTS_C_RANGE] = range;
  out[MTS_C_LOGK] = log_k;
  out[MTS_C_LOGL] = log_L;
  out[MTS_C_THREEJS_FC] = threejs_fc;
  out[MTS_C_CESIUM_FAR1] = cesium_far1;
  out[MTS_C_CESIUM_INV_LOG2] = cesium_inv_log2;
  out[MTS_C_VERTEX_LOG] = static_cast<float>(vertex_log);
  out[MTS_C_DEPTH_GL] = depth_gl ? 1.0f : 0.0f;
  out[MTS_C_FORMS] = static_cast<float>(forms);
  out[MTS_C_SNAP_BITS] = static_cast<float>(snap_bits);
  for (int i = 0; i < 3; ++i) {
    out[MTS_C_VIEW_X + i] = view[i];
    out[MTS_C_EYE_HIGH_X + i] = eye_high[i];
    out[MTS_C_EYE_LOW_X + i] = eye_low[i];
  }
  out[MTS_C_ADV_DEPTH] = adv_far * static_cast<float>(plane);
  out[MTS_C_ADV_RECIPROCAL] = adv_reciprocal;
  out[MTS_C_ADV_INTERPOLATION] = adv_interpolation;
  return out;
}

Angles frame_orientation(const Scene& s, const ProbeConstants& pc, int frame) {
  return pc.orientations.empty() ? frame_angles(s, frame)
                                 : pc.orientations.at(static_cast<size_t>(frame));
}

Angles frame_angles(const Scene& s, int frame) {
  const double a = frame * s.delta_a;
  std::array<double, 3> out{};
  for (int i = 0; i < 3; ++i)
    out[i] = s.rotation_range_deg * glm::pi<double>() / 180.0 *
             std::sin(s.rotation_step[i] * a + s.rotation_offset[i]);
  return out;
}

bool view_translated_on_gpu(const Scene& s) {
  return vertex_path(s.pipeline) == VertexPath::model_then_view &&
         camera_view(s, s.pipeline.transform).form == ViewMatrix::Form::translation;
}

ProbeConstants probe_constants(const Scene& s, const EvalPair& pair, double z,
                               const Orientations& orientations) {
  double n = s.near, f = s.far;
  EvalPair geometry = pair;
  if (pair.technique == Technique::layered) {
    const Layer l = layer_bounds(layer_of(z, s.near, s.far, s.params), s.near, s.far, s.params);
    n = l.near;
    f = l.far;
    geometry.technique = s.params.layer_mapping;
  }
  ProbeConstants pc = s.pipeline.matrix_precision == MatrixPrecision::single
                          ? constants<float>(s, geometry, n, f, z)
                          : constants<double>(s, geometry, n, f, z);
  pc.z = z;
  const auto it = orientations.at.find(z);
  if (it != orientations.at.end()) pc.orientations = it->second;
  return pc;
}

namespace {

// A plane as the application holds it (host/model/vertex_stage.h): its model matrix built from the
// frame's angles in the matrix precision (as glm builds it, in binary32 under float), the camera's
// view, and relative to eye its world matrix in binary64 and the camera's position.
class PlaneDraw final : public ApplicationDraw {
 public:
  PlaneDraw(const Scene& s, const ProbeConstants& pc, double D, int frame, double tilt)
      : s_(s), D_(D), tilt_(tilt), angles_(frame_orientation(s, pc, frame)) {}
  Mat4d model(Transform t) const override {
    const std::array<double, 3> at = plane_translation(s_, D_, t);
    if (s_.pipeline.matrix_precision == MatrixPrecision::single)
      return row_major_f64(depthprec::model<float>(s_, D_, angles_, at, tilt_));
    return row_major_f64(depthprec::model<double>(s_, D_, angles_, at, tilt_));
  }
  ViewMatrix view(Transform t) const override { return camera_view(s_, t); }
  Mat4d world() const override {
    return row_major_f64(depthprec::model<double>(
        s_, D_, angles_, plane_translation(s_, D_, Transform::absolute), tilt_));
  }
  Vec3 eye() const override { return s_.world_position; }

 private:
  const Scene& s_;
  double D_, tilt_;
  Angles angles_;
};

}  // namespace

VertexStage plane_vertex_stage(const Scene& s, const ProbeConstants& pc, double D, int frame,
                               double tilt) {
  return vertex_stage(s.pipeline, pc.P_full, PlaneDraw(s, pc, D, frame, tilt));
}

Mat4f plane_matrix(const Scene& s, const ProbeConstants& pc, double D, int frame, double tilt) {
  const VertexStage st = plane_vertex_stage(s, pc, D, frame, tilt);
  if (st.path == VertexPath::relative_to_eye)
    throw Error(ExitCode::internal,
                "plane_matrix: relative_to_eye hands the GPU world positions "
                "(plane_vertex_stage's world), not a model-view");
  return st.matrix;
}

void append_plane_words(std::vector<float>& words, const Scene& s, const ProbeConstants& pc,
                        double D, int frame, double tilt) {
  const VertexStage st = plane_vertex_stage(s, pc, D, frame, tilt);
  if (st.path == VertexPath::relative_to_eye) {
    const size_t at = words.size();
    words.resize(at + MTS_WORLD_MAT_STRIDE);
    std::memcpy(words.data() + at, st.world.data(), sizeof st.world);
    return;
  }
  words.insert(words.end(), st.matrix.begin(), st.matrix.end());
}

VertexStage read_plane_words(const Scene& s, const ProbeConstants& pc, const float* words) {
  VertexStage st;
  st.path = vertex_path(s.pipeline);
  if (st.path == VertexPath::relative_to_eye) {
    std::memcpy(st.world.data(), words, sizeof st.world);
    st.eye_high = pc.eye_high;
    st.eye_low = pc.eye_low;
    return st;
  }
  std::copy(words, words + MTS_MAT_STRIDE, st.matrix.begin());
  st.precision = (pc.forms & MTS_F_MEDIUMP)     ? ShaderPrecision::mediump
                 : (pc.forms & MTS_F_ES2_HIGHP) ? ShaderPrecision::es2_highp
                                                : ShaderPrecision::highp;
  if (pc.forms & MTS_F_VIEW_TRANSLATE) {  // the view: the camera's translation alone
    st.view = VertexStage::View::translation;
    st.view_matrix = rounded(mat_identity());
    for (int r = 0; r < 3; ++r) st.view_matrix[r * 4 + 3] = pc.view[r];
  }
  return st;
}

size_t plane_words(const Scene& s) {
  return vertex_path(s.pipeline) == VertexPath::relative_to_eye ? MTS_WORLD_MAT_STRIDE
                                                                : MTS_MAT_STRIDE;
}

double plane_matrix_distance(const Scene& s, double D) {
  // Away from the origin the translation is formed from D in binary64 (plane_translation), so
  // two distances that round alike may still give different matrices.
  if (!s.at_world_origin()) return D;
  return s.pipeline.matrix_precision == MatrixPrecision::single ? model_distance<float>(D)
                                                                : model_distance<double>(D);
}

Mat4d model_matrix_f64(const Scene& s, const ProbeConstants& pc, double D, int frame) {
  // The geometry as the eye sees it, wherever the world is: the plane D in front of the camera.
  return row_major_f64(model<double>(s, D, frame_orientation(s, pc, frame), {0, 0, -D}));
}

double seen_separation(double z, double s) {
  return static_cast<double>(static_cast<float>(z + s)) -
         static_cast<double>(static_cast<float>(z));
}

double plane_side(const Scene& s, double D) {
  return s.plane_margin * 2 * D * std::tan(s.fov_y_deg * M_PI / 360);
}

double nearest_vertex_distance(const Scene& s, double D) {
  return D - plane_side(s, D) * std::sin(s.rotation_range_deg * M_PI / 180);
}

double farthest_vertex_distance(const Scene& s, double D) {
  return D + plane_side(s, D) * std::sin(s.rotation_range_deg * M_PI / 180);
}

double world_grid_reach(const Scene& s, double z) {
  const VertexPath path = vertex_path(s.pipeline);
  if (s.at_world_origin() ||
      (path != VertexPath::model_then_view && path != VertexPath::relative_to_eye))
    return 0;
  const double side = plane_side(s, farthest_vertex_distance(s, z));
  const auto half_spacing = [&](int axis) {
    double m = std::fabs(s.world_position[axis]) + z + side;
    // relative to eye keeps a coordinate's low part, below 65536, in binary32
    // (interface/relative_to_eye.h)
    if (path == VertexPath::relative_to_eye) m = std::min(m, std::nextafter(65536.0, 0.0));
    int e = 0;
    std::frexp(m, &e);  // m in [2^(e-1), 2^e): spacing 2^(e-24)
    return std::ldexp(1.0, e - 25);
  };
  const double r = s.rotation_range_deg * M_PI / 180;
  const double slope = std::tan(r) / std::cos(r);
  return 2 * (half_spacing(2) + slope * (half_spacing(0) + half_spacing(1)));
}

double vertex_bound(double z) {
  // z itself is rarely a binary32 (1.005 is not): B moves off A's vertex once z + s passes the
  // midpoint between fl32(z) and the next binary32 above it.
  const float zf = static_cast<float>(z);
  const double mid =
      0.5 * (static_cast<double>(zf) + static_cast<double>(std::nextafter(zf, INFINITY)));
  return mid - z;
}

}  // namespace depthprec
