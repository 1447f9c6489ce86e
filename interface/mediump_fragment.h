/* A fragment shader that writes depth (fragment-stage depth: linear, w_buffer and the log
 * techniques) in GLSL ES mediump (pipeline.shader_precision, docs/spec.md 2 "Shader precision"):
 * the varying q = 1/w arrives in mediump, and every uniform and every step of the shader is
 * rounded to binary16 (interface/binary16.h), the log's binary32 result too. A binary16 +, -, *
 * or / computed in binary32 and rounded to binary16 is the correctly rounded binary16 result
 * (24 >= 2 * 11 + 2 bits). The clip volume's test on w stays the fixed-function stage's, in
 * binary32. One source for the kernels (kernels/mts/fragment.cl) and the host reference
 * (host/mts/triangle_setup.cpp), each giving its own shader log. form: FRAG_DEPTH's numbers
 * (host/model/technique.h FragmentDepth): 1 linear, 2 w_buffer, 3 log, 4 three.js, 5 Cesium. */
#ifndef DP_MEDIUMP_FRAGMENT_H
#define DP_MEDIUMP_FRAGMENT_H

#include "interface/binary16.h"

#define DP_MEDIUMP_FRAGMENT_DEFINE(NAME, LOG, LOG2)                                              \
  static inline float NAME(int form, float q, float near, float range, float far, float log_k, \
                           float log_L, float threejs_fc, float cesium_inv_log2) {             \
    const float w = dp_binary16(1.0f / dp_binary16(q));                                         \
    if (form == 1) return dp_binary16(dp_binary16(w - dp_binary16(near)) / dp_binary16(range)); \
    if (form == 2) return dp_binary16(w / dp_binary16(far));                                    \
    if (form == 4) /* log2(1.0 + w) * fc * 0.5 */                                               \
      return dp_binary16(                                                                       \
          dp_binary16(dp_binary16(LOG2(dp_binary16(1.0f + w))) * dp_binary16(threejs_fc)) *    \
          0.5f);                                                                                \
    if (form == 5) /* log2((w - near) + 1.0) * inv_log2 */                                     \
      return dp_binary16(                                                                       \
          dp_binary16(LOG2(dp_binary16(dp_binary16(w - dp_binary16(near)) + 1.0f))) *           \
          dp_binary16(cesium_inv_log2));                                                        \
    /* log(k w + 1) / L */                                                                      \
    return dp_binary16(                                                                         \
        dp_binary16(LOG(dp_binary16(dp_binary16(dp_binary16(log_k) * w) + 1.0f))) /            \
        dp_binary16(log_L));                                                                    \
  }

#endif
