/* A fragment shader that writes depth (fragment-stage depth: linear, w_buffer and the log
 * techniques) below binary32 (pipeline.shader_precision, docs/spec.md 2 "Shader precision"):
 * GLSL ES mediump or the GLSL ES 1.00 highp minimum, `prec` in dp_shader_round's numbers. The
 * varying q = 1/w arrives at that precision, and every uniform and every step of the shader is
 * rounded to it (interface/binary16.h), the log's binary32 result too. An operation computed in
 * binary32 and rounded to 11 or 17 bits is the correctly rounded result at that precision
 * (24 >= 2 p + 2 bits for p = 11; for 17, a double rounding can land one step off at a tie, as a
 * device computing in binary32 and storing 17 bits would). The clip volume's test on w stays the fixed-function stage's, in
 * binary32. One source for the kernels (kernels/mts/fragment.cl) and the host reference
 * (host/mts/triangle_setup.cpp), each giving its own shader log. form: FRAG_DEPTH's numbers
 * (host/model/technique.h FragmentDepth): 1 linear, 2 w_buffer, 3 log, 4 three.js, 5 Cesium. */
#ifndef DP_MEDIUMP_FRAGMENT_H
#define DP_MEDIUMP_FRAGMENT_H

#include "interface/binary16.h"

/* one step rounded at the shader's precision */
#define DP_MF_R(x) dp_shader_round((x), prec)
#define DP_MEDIUMP_FRAGMENT_DEFINE(NAME, LOG, LOG2)                                              \
  static inline float NAME(int form, float q, float near, float range, float far, float log_k, \
                           float log_L, float threejs_fc, float cesium_inv_log2, int prec) {   \
    const float w = DP_MF_R(1.0f / DP_MF_R(q));                                                 \
    if (form == 1) return DP_MF_R(DP_MF_R(w - DP_MF_R(near)) / DP_MF_R(range));                \
    if (form == 2) return DP_MF_R(w / DP_MF_R(far));                                            \
    if (form == 4) /* log2(1.0 + w) * fc * 0.5 */                                               \
      return DP_MF_R(DP_MF_R(DP_MF_R(LOG2(DP_MF_R(1.0f + w))) * DP_MF_R(threejs_fc)) * 0.5f);  \
    if (form == 5) /* log2((w - near) + 1.0) * inv_log2 */                                     \
      return DP_MF_R(DP_MF_R(LOG2(DP_MF_R(DP_MF_R(w - DP_MF_R(near)) + 1.0f))) *               \
                     DP_MF_R(cesium_inv_log2));                                                 \
    /* log(k w + 1) / L */                                                                      \
    return DP_MF_R(DP_MF_R(LOG(DP_MF_R(DP_MF_R(DP_MF_R(log_k) * w) + 1.0f))) / DP_MF_R(log_L)); \
  }

#endif
