// Binary64 4x4 matrices, row-major: the glTF file's node transforms composed into each draw's
// world matrix (host/model/gltf_nodes.h), the audit's camera.
#pragma once

#include <array>

namespace depthprec {

using Mat4d = std::array<double, 16>;  // row-major: m[r * 4 + c]

// a * b, row-major, binary64.
Mat4d mat_mul(const Mat4d& a, const Mat4d& b);
Mat4d mat_identity();
// The point m * (x, y, z, 1) in binary64.
std::array<double, 3> transform_point(const Mat4d& m, double x, double y, double z);

}  // namespace depthprec
