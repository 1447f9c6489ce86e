// The vertex stage, described once (docs/spec.md 2 "World position", docs/audit.md "Vertex stage"):
// which matrices the application hands the GPU for one draw, how it forms them, and in what order
// the GPU applies them on the way to the clip position. The MTS's planes (plane_vertex_stage,
// host/model/frame_setup.h) and the scene audit's draws (draw_vertex_stage,
// host/audit/audit_setup.h) get theirs from vertex_stage and compute clip positions with
// vertex_clip; the audit's error bound walks the same description (vertex_clip_error,
// host/audit/depth_tolerance.h); `render` uploads it. The kernels' vertex stage
// (kernels/mts/setup/vertex.cl) reads what append_plane_words packs of it.
#pragma once

#include <array>
#include <cmath>

#include "host/model/matrix.h"
#include "host/model/scene.h"

namespace depthprec {

// Row r of m times a computed vector v in binary32, in the kernels' order (kernels/mts/common.cl
// mat_vec): ((m0 x + m1 y) + m2 z) + m3 w, or under VertexForm::fma the chain a shader compiler
// fuses it into, fma(m3, w, fma(m2, z, fma(m1, y, m0 x))).
inline float mat_row_dot(const Mat4f& m, int r, const float v[4],
                         VertexForm form = VertexForm::separate) {
  const float* row = &m[r * 4];
  if (form == VertexForm::fma)
    return std::fma(row[3], v[3], std::fma(row[2], v[2], std::fma(row[1], v[1], row[0] * v[0])));
  return ((row[0] * v[0] + row[1] * v[1]) + row[2] * v[2]) + row[3] * v[3];
}

// Row r of m times v at a reduced shader precision (pipeline.shader_precision: mediump's binary16
// or the GLSL ES 1.00 highp minimum, interface/binary16.h dp_shader_round): the matrix entries
// held at it, every product and sum rounded to it, in mat_row_dot's
// order (separate) or fused one step at a time; an object row is not folded here. The same
// arithmetic as kernels/mts/setup/vertex.cl mediump_row.
float mediump_row_dot(const Mat4f& m, int r, const float v[4], VertexForm form,
                      ShaderPrecision precision);

// Row r of m times an object position (x, y, z, 1) (kernels/mts/common.cl obj_row16 for the
// planes' z = 0): as mat_row_dot, except that under VertexForm::fma the compiler, which sees the
// constant w, folds it away and fuses what is left as fma(m2, z, fma(m1, y, fma(m0, x, m3))). For
// a plane's z = 0 the outer fma adds an exact zero: fma(m1, y, fma(m0, x, m3)), what the compiler
// makes of the planes' positions, whose z it folds too.
inline float object_row_dot(const Mat4f& m, int r, const float obj[4], VertexForm form) {
  const float* row = &m[r * 4];
  if (form == VertexForm::fma)
    return std::fma(row[2], obj[2], std::fma(row[1], obj[1], std::fma(row[0], obj[0], row[3])));
  return mat_row_dot(m, r, obj);
}

// Which matrices the GPU gets, and in what order it applies them to an object position v.
enum class VertexPath {
  // transform absolute, compose separate: the model matrix M and the view matrix V, each as the
  // application holds it, rounded to binary32 once: P (V (M v)), V left out where it is the
  // identity (the MTS's camera at the world origin).
  model_then_view,
  // camera_relative, compose separate: the model-view V M formed on the host: P (MV v).
  model_view,
  // compose premultiplied (absolute or camera_relative): P V M formed on the host: (P V M) v.
  premultiplied,
  // relative_to_eye (compose does not apply): the world matrix W in binary64, from which the
  // application forms each vertex's world position on the CPU, split into binary32 high and low
  // parts, as the eye's position is (interface/relative_to_eye.h); the GPU differences them, then
  // applies the view's rotation (none for the MTS's camera), then P.
  relative_to_eye,
};
// The decision, from the pipeline's transform and compose; every vertex stage takes it here.
VertexPath vertex_path(const Pipeline& pipeline);

// A view matrix (world to eye) as the application holds it: the identity, a translation alone (no
// rotation: the MTS's camera away from the world origin), or a general rigid view.
struct ViewMatrix {
  enum class Form { identity, translation, general };
  Form form = Form::identity;
  Mat4d m = mat_identity();  // row-major, in the matrix precision (ApplicationDraw)
};

// What the application holds for one draw, asked for by vertex_stage as the path needs it. A
// matrix "in the matrix precision" is row-major binary64 whose entries are binary32 values under
// matrix_precision float (built in binary32, or rounded from binary64: held_in) and binary64
// under double.
class ApplicationDraw {
 public:
  virtual ~ApplicationDraw() = default;
  // The model matrix and the view under transform t (absolute or camera_relative), in the matrix
  // precision: an application rendering camera-relative may hold both relative to the camera.
  virtual Mat4d model(Transform t) const = 0;
  virtual ViewMatrix view(Transform t) const = 0;
  // relative_to_eye: the model (world) matrix in binary64, and the eye's world position.
  virtual Mat4d world() const = 0;
  virtual Vec3 eye() const = 0;
};

// m as the application holds it in precision p: each entry rounded to binary32 under float.
Mat4d held_in(MatrixPrecision p, const Mat4d& m);

// What the GPU gets for one draw, and how it applies it.
struct VertexStage {
  VertexPath path = VertexPath::model_then_view;
  Mat4f matrix{};  // M (model_then_view), MV (model_view), P V M (premultiplied)
  // What follows M (model_then_view), or the difference from the eye (relative_to_eye): nothing;
  // a view without rotation, applied as its translation t added per coordinate, eye[r] + t[r], as
  // the kernels do (MTS_F_VIEW_TRANSLATE); or a view's rows 0-2 times (eye, 1) (relative to eye
  // its rotation alone). view_matrix holds the view either way: t is its last column.
  enum class View { none, translation, matrix };
  View view = View::none;
  Mat4f view_matrix{};
  // relative_to_eye: the world matrix, and the eye's high and low parts.
  Mat4d world{};
  std::array<float, 3> eye_high{}, eye_low{};
  // The vertex shader's precision (pipeline.shader_precision): below binary32 (mediump's binary16,
  // or the GLSL ES 1.00 highp minimum) its uniforms, products and sums are rounded to it;
  // relative_to_eye is refused with it.
  ShaderPrecision precision = ShaderPrecision::highp;
};

// The one decision: what the GPU gets for the draw under the pipeline's transform, compose and
// matrix_precision. P: the projection in the matrix precision (ProbeConstants::P_full).
VertexStage vertex_stage(const Pipeline& pipeline, const Mat4d& P, const ApplicationDraw& draw);

// Row r of the binary64 world matrix W times the object position obj (x, y, z, 1), as the
// application computes it on the CPU, every operation rounded: ((W0 x + W1 y) + W2 z) + W3.
inline double world_row(const Mat4d& W, int r, const float obj[4]) {
  const double* m = &W[r * 4];
  return ((m[0] * obj[0] + m[1] * obj[1]) + m[2] * obj[2]) + m[3];
}

// The vertex stage of the object position obj (x, y, z, 1) up to its clip position, in binary32
// with rows in `form` (P: ProbeConstants::P).
void vertex_clip(const VertexStage& stage, const Mat4f& P, const float obj[4], VertexForm form,
                 float clip[4]);

}  // namespace depthprec
