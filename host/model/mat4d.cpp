#include "host/model/mat4d.h"

namespace depthprec {

Mat4d mat_identity() {
  Mat4d m{};
  for (int i = 0; i < 4; ++i) m[i * 5] = 1;
  return m;
}

Mat4d mat_mul(const Mat4d& a, const Mat4d& b) {
  Mat4d m{};
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) {
      double s = 0;
      for (int k = 0; k < 4; ++k) s += a[r * 4 + k] * b[k * 4 + c];
      m[r * 4 + c] = s;
    }
  return m;
}

std::array<double, 3> transform_point(const Mat4d& m, double x, double y, double z) {
  std::array<double, 3> p{};
  for (int r = 0; r < 3; ++r)
    p[r] = m[r * 4] * x + m[r * 4 + 1] * y + m[r * 4 + 2] * z + m[r * 4 + 3];
  return p;
}

}  // namespace depthprec
