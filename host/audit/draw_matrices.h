// The matrices the GPU gets per draw in the scene audit: made by draw_matrices (audit_setup.h),
// bounded in their vertex stage by the tolerance (depth_tolerance.h), uploaded by `render`'s audit.
#pragma once

#include <array>

#include "host/model/frame_setup.h"
#include "host/model/matrix.h"

namespace depthprec {

// What the GPU gets per draw (docs/audit.md "Vertex stage"): absolute: the model matrix and the
// view matrix, each rounded to binary32 from binary64, applied in turn; camera_relative: the
// model-view V * M, compose premultiplied: P * V * M, each formed as matrix_precision says (in
// binary32 from rounded factors, or in binary64 rounded once); relative_to_eye: world positions in
// binary64, split (interface/relative_to_eye.h), then the view's rotation. `render` uploads the
// same matrices.
struct DrawMatrices {
  Mat4f first{}, second{};  // clip = P (second (first v)), P (first v), or first v (premultiplied)
  bool premultiplied = false, view_on_gpu = false, relative_to_eye = false;
  Mat4d world{};
  std::array<float, 3> eye_high{}, eye_low{};
};

}  // namespace depthprec
