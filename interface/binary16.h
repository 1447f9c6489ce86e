/* GLSL ES mediump as binary16 (docs/spec.md 2, pipeline.shader_precision): a binary32 value rounded
 * to the nearest binary16 value, ties to even, subnormals kept (quantum 2^-24), beyond 65504
 * rounded to infinity as IEEE 754 does, returned as the binary32 that holds it exactly. One source
 * for the kernels' mediump vertex stage (kernels/mts/setup/vertex.cl) and the host's
 * (host/model/vertex_stage.cpp); tests/model/vertex_stage.cpp checks it against the compiler's
 * _Float16 on every binary32 of a wide range. Valid C++ and OpenCL C. */
#ifndef DP_BINARY16_H
#define DP_BINARY16_H

#include "formats/df_prelude.h"
#ifdef DF_OPENCL
#define DP_B16_FABS fabs
#define DP_B16_RINT rint
#define DP_B16_COPYSIGN copysign
#else
#include <math.h>
#define DP_B16_FABS fabsf
#define DP_B16_RINT rintf
#define DP_B16_COPYSIGN copysignf
#endif

static inline float dp_binary16(float x) {
  const df_u32 u = df_float_bits(x), sign = u & 0x80000000u, a = u & 0x7fffffffu;
  if (a >= 0x7f800000u) return x;                                 /* inf, NaN */
  if (a >= 0x477ff000u) return df_bits_float(sign | 0x7f800000u); /* from 65520 on: infinity */
  if (a < 0x38800000u) {                                       /* below 2^-14: multiples of 2^-24 */
    const float q = DP_B16_RINT(DP_B16_FABS(x) * 16777216.0f); /* exact scaling, then to even */
    return DP_B16_COPYSIGN(q / 16777216.0f, x);
  }
  /* 13 bits dropped, to nearest, ties to even; a carry moves into the exponent, as it should */
  const df_u32 r = (a + 0x0fffu + ((a >> 13) & 1u)) & 0xffffe000u;
  return df_bits_float(sign | r);
}

/* The GLSL ES 1.00 highp minimum (pipeline.shader_precision es2_highp): relative precision 2^-16
 * (17 significant bits) and magnitudes in [2^-62, 2^62] (GLSL ES 1.00 4.5.2), as a device that
 * offers no more runs it: to nearest, ties to even, 7 bits dropped from binary32's 24; from 2^62
 * on (after rounding) infinity, below 2^-62 zero. */
static inline float dp_es2_highp(float x) {
  const df_u32 u = df_float_bits(x), sign = u & 0x80000000u, a = u & 0x7fffffffu;
  if (a >= 0x7f800000u) return x;                     /* inf, NaN */
  if (a < 0x20800000u) return df_bits_float(sign);    /* below 2^-62: zero */
  const df_u32 r = (a + 0x3fu + ((a >> 7) & 1u)) & 0xffffff80u;
  return df_bits_float(sign | (r >= 0x5e800000u ? 0x7f800000u : r)); /* from 2^62: infinity */
}

/* A shader's rounding at its precision (host/model/scene.h ShaderPrecision, the same numbers):
 * binary32 as it is, mediump's binary16, or the GLSL ES 1.00 highp minimum. */
#define DP_SHADER_HIGHP 0
#define DP_SHADER_MEDIUMP 1
#define DP_SHADER_ES2_HIGHP 2
static inline float dp_shader_round(float x, int precision) {
  return precision == DP_SHADER_MEDIUMP     ? dp_binary16(x)
         : precision == DP_SHADER_ES2_HIGHP ? dp_es2_highp(x)
                                            : x;
}

#endif
