#include "host/model/vertex_stage.h"

#include <glm/glm.hpp>
#include <initializer_list>

#include "interface/binary16.h"

static_assert(static_cast<int>(depthprec::ShaderPrecision::mediump) == DP_SHADER_MEDIUMP &&
              static_cast<int>(depthprec::ShaderPrecision::es2_highp) == DP_SHADER_ES2_HIGHP);
#include "interface/relative_to_eye.h"

namespace depthprec {

namespace {

// The product of factors held in the matrix precision, as the application forms it: left to right
// from the identity, as glm code that starts from glm::mat4(1) evaluates it (each entry
// ((a0 b0 + a1 b1) + a2 b2) + a3 b3), in precision T, then rounded to binary32 once (exactly,
// under float). A factor alone is no product: it is handed on as held.
//
// Starting from the identity changes nothing where a product used to start from P (the MTS's
// P * V * M and P * M, formed in glm from P): an entry of I P is 1 p plus three products 0 q, all
// exact (P is finite), so it is p whenever p is not zero, and a sum of zeros that includes +0 is +0
// (round to nearest); P's zeros are +0 (glm's Mat(T(0)), and a = T(0) for reversed_infinite under
// zero_to_one), so I P = P bit for bit. The one exception is a near plane below binary32's least
// subnormal (about 1.4e-45), where b = -n, -2 n or -f n / (f - n) underflows to -0 and I P holds +0
// instead: only the sign of a zero in P V M's third row can differ then.
template <class T>
Mat4f product(std::initializer_list<const Mat4d*> factors) {
  if (factors.size() == 1) return rounded(**factors.begin());
  using M = glm::mat<4, 4, T, glm::defaultp>;  // column-major: m[c][r]
  M out(T(1));
  for (const Mat4d* f : factors) {
    M m(T(0));
    for (int r = 0; r < 4; ++r)
      for (int c = 0; c < 4; ++c) m[c][r] = static_cast<T>((*f)[r * 4 + c]);
    out = out * m;
  }
  Mat4f f{};
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) f[r * 4 + c] = static_cast<float>(out[c][r]);
  return f;
}

Mat4f product(MatrixPrecision p, std::initializer_list<const Mat4d*> factors) {
  return p == MatrixPrecision::single ? product<float>(factors) : product<double>(factors);
}

// The view as the GPU applies it after the model matrix (or the difference from the eye): nothing
// for the identity, eye[r] + t[r] for a translation, its rows for a general view. Relative to eye
// the view's translation is in the difference already, so only a general view's rotation is left.
void set_view(VertexStage& st, const ViewMatrix& v, bool rotation_only) {
  if (v.form == ViewMatrix::Form::identity) return;
  if (rotation_only && v.form == ViewMatrix::Form::translation) return;
  st.view = v.form == ViewMatrix::Form::translation ? VertexStage::View::translation
                                                    : VertexStage::View::matrix;
  st.view_matrix = rounded(v.m);
  if (rotation_only) st.view_matrix[3] = st.view_matrix[7] = st.view_matrix[11] = 0;
}

}  // namespace

VertexPath vertex_path(const Pipeline& p) {
  if (p.transform == Transform::relative_to_eye) return VertexPath::relative_to_eye;
  if (p.compose == Compose::premultiplied) return VertexPath::premultiplied;
  return p.transform == Transform::absolute ? VertexPath::model_then_view : VertexPath::model_view;
}

Mat4d held_in(MatrixPrecision p, const Mat4d& m) {
  if (p == MatrixPrecision::binary64) return m;
  Mat4d out{};
  for (int i = 0; i < 16; ++i) out[i] = static_cast<float>(m[i]);
  return out;
}

float mediump_row_dot(const Mat4f& m, int r, const float v[4], VertexForm form,
                      ShaderPrecision precision) {
  const int p = static_cast<int>(precision);
  const auto h = [p](float x) { return dp_shader_round(x, p); };
  const float* row = &m[r * 4];
  float s = h(h(row[0]) * v[0]);
  for (int c = 1; c < 4; ++c)
    s = form == VertexForm::fma ? h(std::fma(h(row[c]), v[c], s)) : h(s + h(h(row[c]) * v[c]));
  return s;
}

VertexStage vertex_stage(const Pipeline& pipe, const Mat4d& P, const ApplicationDraw& draw) {
  VertexStage st;
  st.path = vertex_path(pipe);
  st.precision = pipe.shader_precision;
  const Transform t = pipe.transform;
  if (st.path == VertexPath::relative_to_eye) {
    st.world = draw.world();
    const Vec3 eye = draw.eye();
    for (int i = 0; i < 3; ++i) dp_rte_encode(eye[i], &st.eye_high[i], &st.eye_low[i]);
    set_view(st, draw.view(t), true);
    return st;
  }
  const Mat4d M = draw.model(t);
  const ViewMatrix V = draw.view(t);
  const bool has_view = V.form != ViewMatrix::Form::identity;
  switch (st.path) {
    case VertexPath::premultiplied:
      st.matrix = has_view ? product(pipe.matrix_precision, {&P, &V.m, &M})
                           : product(pipe.matrix_precision, {&P, &M});
      break;
    case VertexPath::model_view:
      st.matrix = has_view ? product(pipe.matrix_precision, {&V.m, &M}) : rounded(M);
      break;
    default:  // model_then_view
      st.matrix = rounded(M);
      set_view(st, V, false);
  }
  return st;
}

void vertex_clip(const VertexStage& st, const Mat4f& P, const float obj[4], VertexForm form,
                 float clip[4]) {
  float eye[4] = {0, 0, 0, 1.0f};
  const ShaderPrecision sp = st.precision;
  if (sp != ShaderPrecision::highp) {  // kernels/mts/setup/vertex.cl mediump_vertex, the same steps
    if (st.path == VertexPath::premultiplied) {
      for (int r = 0; r < 4; ++r) clip[r] = mediump_row_dot(st.matrix, r, obj, form, sp);
      return;
    }
    for (int r = 0; r < 3; ++r) eye[r] = mediump_row_dot(st.matrix, r, obj, form, sp);
    const int p = static_cast<int>(sp);
    if (st.view == VertexStage::View::translation)
      for (int r = 0; r < 3; ++r)
        eye[r] = dp_shader_round(eye[r] + dp_shader_round(st.view_matrix[r * 4 + 3], p), p);
    else if (st.view == VertexStage::View::matrix) {
      const float v[4] = {eye[0], eye[1], eye[2], 1.0f};
      for (int r = 0; r < 3; ++r) eye[r] = mediump_row_dot(st.view_matrix, r, v, form, sp);
    }
    for (int r = 0; r < 4; ++r) clip[r] = mediump_row_dot(P, r, eye, form, sp);
    return;
  }
  if (st.path == VertexPath::premultiplied) {
    for (int r = 0; r < 4; ++r) clip[r] = object_row_dot(st.matrix, r, obj, form);
    return;
  }
  if (st.path == VertexPath::relative_to_eye) {
    // The kernels leave the planes' z = 0 out of the world row (dp_rte_world_row: (W0 x + W1 y) +
    // W3); with it, a + W2 0 adds a zero to a = W0 x + W1 y, which is exact unless a is a zero too,
    // so the two rows differ at most in the sign of a zero world coordinate, and dp_rte_eye gives
    // the same for +0 and -0: both split into high parts ±0 and the low part +0, so
    // (high - eye_high) differs at most in the sign of a zero, which adding (low - eye_low)
    // removes: that sum is low - eye_low when it is not zero, and +0 when it is (+0 - ±0 = +0).
    for (int r = 0; r < 3; ++r)
      eye[r] = dp_rte_eye(world_row(st.world, r, obj), st.eye_high[r], st.eye_low[r]);
  } else {
    // Rows 0-2 of M or MV; row 3 gives 1 exactly: the application's matrices are affine, and the
    // MTS's planes' last row (±0, ±0, ±0, 1) (glm's products of affine factors) makes
    // ((±0 x + ±0 y) + ±0 z) + 1 1, or its fused chain, exactly 1.
    for (int r = 0; r < 3; ++r) eye[r] = object_row_dot(st.matrix, r, obj, form);
  }
  if (st.view == VertexStage::View::translation) {  // a view without rotation: x + t
    for (int r = 0; r < 3; ++r) eye[r] = eye[r] + st.view_matrix[r * 4 + 3];
  } else if (st.view == VertexStage::View::matrix) {
    const float v[4] = {eye[0], eye[1], eye[2], 1.0f};
    for (int r = 0; r < 3; ++r) eye[r] = mat_row_dot(st.view_matrix, r, v, form);
  }
  for (int r = 0; r < 4; ++r) clip[r] = mat_row_dot(P, r, eye, form);
}

}  // namespace depthprec
