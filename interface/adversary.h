/* An envelope's adversary (pipeline.envelope, docs/spec.md 2, "Envelopes"): at each freedom an
 * API's specification leaves an implementation, the choice that makes plane B win over plane A
 * most often. Plane A's values move towards the far side of the depth test, plane B's towards
 * the near side ("toward": +1 for A, -1 for B, 0 for no adversary). One source for the kernels
 * (kernels/mts/setup/vertex.cl, triangles.cl, kernels/mts/fragment.cl) and the host reference
 * (host/mts/triangle_setup.cpp, reference_pipeline.cpp), each choice within the tolerance the
 * envelope's bound model states (host/model/bound_model.cpp), written beside it.
 *
 * OpenCL: cl_khr_fp64 must be enabled before this is included. */
#ifndef DP_ADVERSARY_H
#define DP_ADVERSARY_H

#include "formats/depth_format.h"
#if !defined(DF_OPENCL)
#include <math.h>
#endif

/* The reciprocal of w within 1 ulp (D3D 11.3 3.1.3: "1.0f / x ... within 1 ulp"): of the two
 * binary32 neighbours of 1/w (its faithful roundings, each within 1 ulp of it) the upper when
 * up, else the lower. r is the correctly rounded 1/w; the residual e = 1 - w r, exact with an
 * fma, says on which side of 1/w it lies: r < 1/w exactly when e and w have the same sign. The
 * neighbour beyond r then lies on 1/w's other side, within one ulp of it. Non-finite or exact
 * quotients are left as they are. */
#define DP_ADV_RECIPROCAL_DEFINE(NAME, FMA, NEXTAFTER)                     \
  static inline float NAME(float w, float r, int up) {                     \
    const float e = FMA(-w, r, 1.0f);                                      \
    if (!(e > 0.0f || e < 0.0f)) return r; /* exact, or w 0, inf or NaN */ \
    const int below = (e > 0.0f) == (w > 0.0f);                            \
    if (up && below) return NEXTAFTER(r, (float)INFINITY);                 \
    if (!up && !below) return NEXTAFTER(r, -(float)INFINITY);              \
    return r;                                                              \
  }

/* Which way the adversary moves what it moves, for a plane whose window depth moves in direction
 * adv_depth (MTS_C_ADV_DEPTH: +1 up, -1 down): the interpolated value (the depth, or 1/w where
 * the fragment stage computes the depth, which every fragment form makes increase with w, so 1/w
 * moves against it), and the reciprocal of w, which moves the depth through z_clip / w where the
 * depth is projected (the same way as 1/w where z_clip > 0) and through w itself otherwise. */
static inline int dp_adv_value_sign(int depth_from_fragment, float adv_depth) {
  return (adv_depth > 0.0f) != (depth_from_fragment != 0) ? 1 : -1;
}
static inline int dp_adv_reciprocal_up(int depth_from_fragment, float z_clip, float adv_depth) {
  return depth_from_fragment ? adv_depth < 0.0f : (z_clip > 0.0f) == (adv_depth > 0.0f);
}

/* A triangle's interpolated value (depth, or 1/w where the fragment stage computes depth) moved
 * by `sign` times `tolerance` times the smallest magnitude at its vertices, the most an
 * interpolation within `tolerance` of each value (Vulkan, "Floating-Point Computation": 1 part in
 * 10^5) allows at every point of the triangle: the exact value at a point is a convex combination
 * of the vertices' values, so its magnitude is at least their smallest when they share a sign
 * (none otherwise). The constant c0 of the plane's record is moved, in binary64, then rounded
 * towards c0 (never further than the shift), so the plane evaluated as before carries it. */
static inline float dp_adv_shift_plane(float c0, float v0, float v1, float v2, double tolerance,
                                       int sign) {
  const int same = (v0 > 0.0f && v1 > 0.0f && v2 > 0.0f) || (v0 < 0.0f && v1 < 0.0f && v2 < 0.0f);
  if (sign == 0 || !same || !(tolerance > 0.0)) return c0;
  const double a0 = fabs((double)v0), a1 = fabs((double)v1), a2 = fabs((double)v2);
  const double shift = (double)sign * tolerance * fmin(a0, fmin(a1, a2));
  const double want = (double)c0 + shift;
  float c = (float)want;
  if (shift > 0.0 && (double)c > want) c = nextafter(c, -(float)INFINITY);
  if (shift < 0.0 && (double)c < want) c = nextafter(c, (float)INFINITY);
  return c;
}

/* The unorm code an adversarial conversion stores for a depth d in [0, 1], of x = d (2^b - 1):
 * up (plane A under LEQUAL) ceil(x - slack), else floor(x + slack), so the code lies within
 * 1 - slack of x on the side that helps B. D3D 11.3 3.2.3.6 allows 0.6 ulp: slack 0.4 plus a
 * hair (2^-20); Vulkan allows either of the two nearest codes: slack 0, the exact ceiling or
 * floor. x is exact in binary64 up to 29 bits; for unorm32 its product rounds by at most 2^-21
 * codes, which the hair covers, and with slack 0 the product's exact residual (an fma) decides
 * an integer product. Outside [0, 1] (and NaN) as df_encode: 0 below, the largest code above. */
static inline df_u32 dp_adv_unorm_code(float d, df_format f, int up, double slack) {
  if (!(d > 0.0f)) return 0u;
  if (d >= 1.0f) return f.max_code;
  const double x = (double)d * (double)f.max_code;
  double c = up ? ceil(x - slack) : floor(x + slack);
  if (slack == 0.0 && c == x) { /* x rounded to an integer: its residual says which side */
    const double residual = fma((double)d, (double)f.max_code, -x);
    c += up ? (residual > 0.0 ? 1.0 : 0.0) : (residual < 0.0 ? -1.0 : 0.0);
  }
  return c <= 0.0 ? 0u : (c >= (double)f.max_code ? f.max_code : (df_u32)c);
}

#endif /* DP_ADVERSARY_H */
