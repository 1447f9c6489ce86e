// The host's one small vocabulary of 3-vectors and 4x4 matrices, row-major (m[r * 4 + c]): binary64
// for geometry the application holds exactly (node transforms, cameras, exact planes), binary32
// for what the GPU is handed. The MTS's plane matrices are built with glm (host/model/frame_setup
// .cpp), as an application would; what they hand on is a Mat4f.
#pragma once

#include <array>
#include <cmath>

namespace depthprec {

using Vec3 = std::array<double, 3>;
using Mat4d = std::array<double, 16>;
using Mat4f = std::array<float, 16>;

inline Vec3 sub(const Vec3& a, const Vec3& b) {
  return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}
inline Vec3 add(const Vec3& a, const Vec3& b) {
  return {a[0] + b[0], a[1] + b[1], a[2] + b[2]};
}
inline Vec3 scaled(const Vec3& a, double k) {
  return {a[0] * k, a[1] * k, a[2] * k};
}
inline Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
inline double dot(const Vec3& a, const Vec3& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
inline Vec3 normalized(const Vec3& a) {
  const double n = std::sqrt(dot(a, a));
  return {a[0] / n, a[1] / n, a[2] / n};
}

inline Mat4d mat_identity() {
  Mat4d m{};
  for (int i = 0; i < 4; ++i) m[i * 5] = 1;
  return m;
}

// a * b in binary64.
inline Mat4d mat_mul(const Mat4d& a, const Mat4d& b) {
  Mat4d m{};
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) {
      double s = 0;
      for (int k = 0; k < 4; ++k) s += a[r * 4 + k] * b[k * 4 + c];
      m[r * 4 + c] = s;
    }
  return m;
}

// The point m * (x, y, z, 1) in binary64.
inline Vec3 transform_point(const Mat4d& m, double x, double y, double z) {
  Vec3 p{};
  for (int r = 0; r < 3; ++r)
    p[r] = m[r * 4] * x + m[r * 4 + 1] * y + m[r * 4 + 2] * z + m[r * 4 + 3];
  return p;
}

// Each entry rounded to binary32, as the application uploads it.
inline Mat4f rounded(const Mat4d& m) {
  Mat4f f{};
  for (int i = 0; i < 16; ++i) f[i] = static_cast<float>(m[i]);
  return f;
}

}  // namespace depthprec
