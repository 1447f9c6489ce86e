/* Relative-to-eye positions as Cesium ships them (docs/spec.md 2, pipeline.transform), one source
 * for the kernels' vertex stage, the host reference and `render`: a binary64 coordinate split into
 * a high part, a multiple of 65536, and the rest, each stored as binary32 (CesiumJS
 * EncodedCartesian3.encode: high = 65536 floor(|x| / 65536) with x's sign, low = x - high), and
 * the vertex shader's eye-space coordinate (high - eye_high) + (low - eye_low) in binary32
 * (czm_translateRelativeToEye). The high parts of a vertex and of an eye within 65536 of each
 * other are equal or 65536 apart, so their difference is exact; the low part's binary32 rounding
 * (up to 2^-8 below 65536) is what the vertex keeps of its position, wherever the world is.
 * Valid C++ and OpenCL C (with cl_khr_fp64). */
#ifndef DEPTHPREC_RELATIVE_TO_EYE_H
#define DEPTHPREC_RELATIVE_TO_EYE_H

#if !(defined(__OPENCL_VERSION__) || defined(__OPENCL_C_VERSION__))
#include <math.h>
#endif

static inline void dp_rte_encode(double x, float* high, float* low) {
  const double h = floor((x >= 0.0 ? x : -x) / 65536.0) * 65536.0;
  *high = (float)(x >= 0.0 ? h : -h);
  *low = (float)(x >= 0.0 ? x - h : x + h);
}

/* The eye-space coordinate of a vertex at world coordinate x seen from an eye encoded as
 * (eye_high, eye_low). */
static inline float dp_rte_eye(double x, float eye_high, float eye_low) {
  float high, low;
  dp_rte_encode(x, &high, &low);
  return (high - eye_high) + (low - eye_low);
}

/* Row r of a binary64 world matrix (row-major) times a plane's object position (ox, oy, 0, 1):
 * the position the application computes on the CPU, every operation rounded (the host compiles
 * with -ffp-contract=off; here contraction is off whatever the scene's pipeline.contraction says,
 * since this is the CPU's arithmetic, not the GPU's). */
#if defined(__OPENCL_VERSION__) || defined(__OPENCL_C_VERSION__)
static inline double dp_rte_world_row(__global const double* m, int r, double ox, double oy) {
#pragma OPENCL FP_CONTRACT OFF
#else
static inline double dp_rte_world_row(const double* m, int r, double ox, double oy) {
#endif
  return (m[4 * r] * ox + m[4 * r + 1] * oy) + m[4 * r + 3];
}

#endif
