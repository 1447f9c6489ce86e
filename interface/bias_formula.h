/* The depth bias (polygon offset) added to a primitive's depth, one source for the host
 * (host/bias/bias_rule.cpp, the tests) and the kernel (kernels/bias.cl), as the APIs define it
 * (docs/bias.md): o = m * factor + r * units, then clamped, in binary32 (no fused multiply-add:
 * the kernel's CONTRACT define and the host's -ffp-contract=off keep the two roundings).
 *
 *   m       the primitive's depth slope in window depth per pixel, max(|dz/dx|, |dz/dy|) or
 *           sqrt(dz/dx^2 + dz/dy^2)
 *   r       fixed-point storage: a constant per format; the host passes fl32(r * units) as
 *           units_term. Floating-point storage: 2^(e - 23), e the exponent of the largest |z| of
 *           the primitive's vertices; the host passes units itself.
 *   clamp   > 0: o = min(o, clamp); < 0: o = max(o, clamp); 0: none.
 *
 * Valid C++ and OpenCL C. */
#ifndef DEPTH_BIAS_FORMULA_H
#define DEPTH_BIAS_FORMULA_H

#include "formats/df_prelude.h"
#ifndef DF_OPENCL
#include <math.h>
#endif

#define BIAS_SLOPE_MAX 0
#define BIAS_SLOPE_SQRT 1

/* 2^(e - 23) for the binary32 z: one unit in the last place of a binary32 in z's binade. Zero and
 * subnormal z take the smallest normal binade's exponent, -126, so r is 2^-149 there. */
DF_FN float depth_bias_float_r(float z) {
  const df_u32 biased = (df_float_bits(z) >> 23) & 0xffu;
  const df_i32 e = (biased == 0u ? 1 : (df_i32)biased) - 127 - 23; /* >= -149 */
  return e >= -126 ? df_bits_float((df_u32)(e + 127) << 23) : df_bits_float(1u << (e + 149));
}

DF_FN float depth_bias_slope(float dzdx, float dzdy, int slope_form) {
  const float ax = dzdx < 0.0f ? -dzdx : dzdx, ay = dzdy < 0.0f ? -dzdy : dzdy;
  if (slope_form == BIAS_SLOPE_SQRT) return sqrt(ax * ax + ay * ay);
  return ax > ay ? ax : ay;
}

/* The offset of one primitive: z0, z1, z2 its vertices' window depths. float_rule 1: units_term is
 * the units, scaled here by the primitive's r; 0: units_term is fl32(r * units) already. */
DF_FN float depth_bias(float units_term, int float_rule, float factor, float clamp, float m,
                       float z0, float z1, float z2) {
  float r_units = units_term;
  if (float_rule) {
    const float a0 = z0 < 0.0f ? -z0 : z0, a1 = z1 < 0.0f ? -z1 : z1, a2 = z2 < 0.0f ? -z2 : z2;
    const float zmax = a0 > a1 ? (a0 > a2 ? a0 : a2) : (a1 > a2 ? a1 : a2);
    r_units = depth_bias_float_r(zmax) * units_term;
  }
  float o = m * factor + r_units;
  if (clamp > 0.0f && o > clamp) o = clamp;
  if (clamp < 0.0f && o < clamp) o = clamp;
  return o;
}

#endif
