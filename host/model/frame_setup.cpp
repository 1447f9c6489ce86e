#include "host/model/frame_setup.h"

#include <fmt/format.h>

#include <cmath>
#include <cstring>
#include <glm/glm.hpp>
#include <glm/gtc/constants.hpp>

#include "host/base/errors.h"
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

// The same in binary64, never rounded.
std::array<double, 16> row_major_f64(const Mat<double>& m) {
  std::array<double, 16> out{};
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) out[r * 4 + c] = m[c][r];
  return out;
}

template <class T>
Mat<T> projection(const Scene& s, const EvalPair& pair, T n, T f) {
  const T half_fov = static_cast<T>(s.fov_y_deg * glm::pi<double>() / 360.0);
  const T sy = T(1) / std::tan(half_fov);
  const T aspect = static_cast<T>(s.viewport_w) / static_cast<T>(s.viewport_h);
  const T sx = sy / aspect;
  const Row3<T> row = projection_row3<T>(pair.technique, pair.depth_range, n, f);
  Mat<T> P(T(0));
  P[0][0] = sx;
  P[1][1] = sy;
  P[2][2] = row.a;
  P[3][2] = row.b;
  P[2][3] = T(-1);
  return P;
}

// The distance a plane is built from in precision T: with tilt 0, all that D enters as.
template <class T>
T model_distance(double D) {
  return static_cast<T>(D);
}

// The translation of a plane's model matrix at distance D (binary64; docs/spec.md 2, "World
// position"): its centre in the world (absolute, relative_to_eye), or that minus the camera's
// position, formed in binary64 as camera-relative rendering forms it (camera_relative). At the
// world origin every transform gives (0, 0, -D).
std::array<double, 3> plane_translation(const Scene& s, double D) {
  const auto& wp = s.world_position;
  const std::array<double, 3> centre = {wp[0], wp[1], wp[2] - D};
  if (s.pipeline.transform != Transform::camera_relative) return centre;
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

template <class T>
ProbeConstants constants(const Scene& s, const EvalPair& pair, double n64, double f64) {
  ProbeConstants pc;
  const T n = static_cast<T>(n64), f = static_cast<T>(f64);
  const Mat<T> P = projection<T>(s, pair, n, f);
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
  pc.forms = (pipe.divide == Divide::exact ? MTS_F_DIVIDE_EXACT : 0u) |
             (pipe.compose == Compose::premultiplied ? MTS_F_COMPOSE_PREMULT : 0u) |
             (pipe.viewport == ViewportForm::fma ? MTS_F_VIEWPORT_FMA : 0u) |
             (pipe.vertex == VertexForm::fma ? MTS_F_VERTEX_FMA : 0u);
  pc.snap_bits = pipe.snap_bits;
  // The view matrix's translation, -world_position, applied on the GPU after the model matrix
  // (absolute, compose separate); premultiplied, the host folds it into P * V * M.
  const auto& wp = s.world_position;
  if (view_translated_on_gpu(s)) {
    pc.forms |= MTS_F_VIEW_TRANSLATE;
    for (int i = 0; i < 3; ++i) pc.view[i] = static_cast<float>(static_cast<T>(-wp[i]));
  }
  if (pipe.transform == Transform::relative_to_eye)
    for (int i = 0; i < 3; ++i) dp_rte_encode(wp[i], &pc.eye_high[i], &pc.eye_low[i]);
  pc.layer_near = n64;
  pc.layer_far = f64;
  return pc;
}

}  // namespace

std::array<float, MTS_PROBE_STRIDE> ProbeConstants::packed() const {
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
  return s.pipeline.transform == Transform::absolute && s.pipeline.compose == Compose::separate &&
         !s.at_world_origin();
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
                          ? constants<float>(s, geometry, n, f)
                          : constants<double>(s, geometry, n, f);
  pc.z = z;
  const auto it = orientations.at.find(z);
  if (it != orientations.at.end()) pc.orientations = it->second;
  return pc;
}

namespace {

// P * MV, or P * V * MV under the absolute transform away from the world origin (V: the camera's
// translation), in precision T as glm evaluates it, left to right.
template <class T>
Mat<T> premultiplied(const Scene& s, const Mat<T>& P, const Mat<T>& M) {
  if (s.pipeline.transform != Transform::absolute || s.at_world_origin()) return P * M;
  Mat<T> V(T(1));
  for (int i = 0; i < 3; ++i) V[3][i] = static_cast<T>(-s.world_position[i]);
  return P * V * M;
}

}  // namespace

Mat4f plane_matrix(const Scene& s, const ProbeConstants& pc, double D, int frame, double tilt) {
  if (s.pipeline.transform == Transform::relative_to_eye)
    throw Error(ExitCode::internal,
                "plane_matrix: relative_to_eye hands the GPU world positions "
                "(plane_world_matrix), not a model-view");
  const bool premult = s.pipeline.compose == Compose::premultiplied;
  if (s.pipeline.matrix_precision == MatrixPrecision::single) {
    const Mat<float> M =
        model<float>(s, D, frame_orientation(s, pc, frame), plane_translation(s, D), tilt);
    if (!premult) return to_row_major(M);
    Mat<float> P;
    for (int r = 0; r < 4; ++r)
      for (int c = 0; c < 4; ++c) P[c][r] = pc.P[r * 4 + c];
    return to_row_major(premultiplied(s, P, M));
  }
  const Mat<double> M =
      model<double>(s, D, frame_orientation(s, pc, frame), plane_translation(s, D), tilt);
  if (!premult) return to_row_major(M);
  Mat<double> P;  // the binary64 P, so P * MV is rounded once, at the end
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) P[c][r] = pc.P_full[r * 4 + c];
  return to_row_major(premultiplied(s, P, M));
}

Mat4d plane_world_matrix(const Scene& s, const ProbeConstants& pc, double D, int frame,
                         double tilt) {
  return row_major_f64(
      model<double>(s, D, frame_orientation(s, pc, frame), plane_translation(s, D), tilt));
}

void append_plane_words(std::vector<float>& words, const Scene& s, const ProbeConstants& pc,
                        double D, int frame, double tilt) {
  if (s.pipeline.transform == Transform::relative_to_eye) {
    const std::array<double, 16> m = plane_world_matrix(s, pc, D, frame, tilt);
    const size_t at = words.size();
    words.resize(at + MTS_WORLD_MAT_STRIDE);
    std::memcpy(words.data() + at, m.data(), sizeof m);
    return;
  }
  const Mat4f m = plane_matrix(s, pc, D, frame, tilt);
  words.insert(words.end(), m.begin(), m.end());
}

void plane_vertex_clip(const Scene& s, const ProbeConstants& pc, const std::vector<float>& words,
                       const float obj[4], VertexForm form, float clip[4]) {
  float eye[4] = {0, 0, 0, 1.0f};
  if (s.pipeline.transform == Transform::relative_to_eye) {
    std::array<double, 16> W{};
    std::memcpy(W.data(), words.data(), sizeof W);
    for (int r = 0; r < 3; ++r)
      eye[r] =
          dp_rte_eye(dp_rte_world_row(W.data(), r, obj[0], obj[1]), pc.eye_high[r], pc.eye_low[r]);
  } else {
    Mat4f M{};
    std::copy(words.begin(), words.begin() + MTS_MAT_STRIDE, M.begin());
    if (s.pipeline.compose == Compose::premultiplied) {  // P * MV already
      for (int r = 0; r < 4; ++r) clip[r] = object_row_dot(M, r, obj, form);
      return;
    }
    for (int r = 0; r < 4; ++r) eye[r] = object_row_dot(M, r, obj, form);
    if (pc.forms & MTS_F_VIEW_TRANSLATE)  // the view matrix: the camera's translation alone
      for (int r = 0; r < 3; ++r) eye[r] = eye[r] + pc.view[r];
  }
  for (int r = 0; r < 4; ++r) clip[r] = mat_row_dot(pc.P, r, eye, form);
}

size_t plane_words(const Scene& s) {
  return s.pipeline.transform == Transform::relative_to_eye ? MTS_WORLD_MAT_STRIDE : MTS_MAT_STRIDE;
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

double vertex_bound(double z) {
  // z itself is rarely a binary32 (1.005 is not): B moves off A's vertex once z + s passes the
  // midpoint between fl32(z) and the next binary32 above it.
  const float zf = static_cast<float>(z);
  const double mid =
      0.5 * (static_cast<double>(zf) + static_cast<double>(std::nextafter(zf, INFINITY)));
  return mid - z;
}

}  // namespace depthprec
