/* The natural log as a shader's log() computes it on Mesa's llvmpipe (22.3), one source for the
 * host reference and the kernels (pipeline.log = llvmpipe, docs/spec.md 2).
 *
 * GLSL's log(x) reaches llvmpipe as log2(x) * fl32(ln 2); gallivm's log2 (lp_bld_arit.c,
 * lp_build_log2_approx) is not the library's: the exponent field e of x, the mantissa m in
 * [1, 2), y = (m - 1) / (m + 1), z = y^2, and log2(x) = fma(y, P(z), e - 127), where P is the
 * degree-4 minimax fit of log2((1 + sqrt z) / (1 - sqrt z)) / sqrt z, evaluated as two Horner
 * chains over z^2 (even and odd coefficients) with fused steps. That form, with these five
 * coefficients, stores every pixel's depth as llvmpipe does (tests/render/render.cpp); the other
 * degrees and the unfused steps do not.
 *
 * The coefficients are gallivm's binary64 constants rounded to binary32, as its code generator
 * rounds them (0x1.a07ab2p-2 is 0.406718052498846252698, and so on, in the order above).
 *
 * GLSL's log2(x) is the same approximation without the final product (NIR lowers log to
 * flog2 * fl32(ln 2); flog2 is lp_build_log2_safe): the engines' log depths (three.js, Cesium) call
 * log2.
 *
 * DP_LLVMPIPE_LOG_DEFINE(LOG2, LOG, F, AS_U, AS_F, TO_F, FMA) defines F LOG2(F x) and F LOG(F x)
 * for a float type F (scalar or vector), given its bit casts, the conversion of an unsigned field
 * to F, and fma. */
#ifndef DP_LLVMPIPE_LOG_H
#define DP_LLVMPIPE_LOG_H

#define DP_LLVMPIPE_LOG_DEFINE(LOG2, LOG, F, AS_U, AS_F, TO_F, FMA)                           \
  static inline F LOG2(F x) {                                                                 \
    const F e = TO_F((AS_U(x) >> 23) & 0xffu) - 127.0f;                                       \
    const F m = AS_F((AS_U(x) & 0x007fffffu) | 0x3f800000u);                                  \
    const F y = (m - 1.0f) / (m + 1.0f);                                                      \
    const F z = y * y, z2 = z * z;                                                            \
    const F even = FMA(z2, FMA(z2, (F)0x1.a07ab2p-2f, (F)0x1.27a642p-1f), (F)0x1.715476p+1f); \
    const F odd = FMA(z2, (F)0x1.9d062cp-2f, (F)0x1.ec6ff2p-1f);                              \
    F r = FMA(y, FMA(odd, z, even), e);                                                       \
    /* lp_build_log2_safe's edge cases: +inf stays, 0 gives -inf, below 0 or NaN gives NaN */ \
    r = x == (F)INFINITY ? x : r;                                                             \
    r = x == (F)0.0f ? (F)(-INFINITY) : r;                                                    \
    r = (x < (F)0.0f || x != x) ? (F)NAN : r;                                                 \
    return r;                                                                                 \
  }                                                                                           \
  /* the edge cases carry through the product: inf, -inf and NaN stay what they are */        \
  static inline F LOG(F x) {                                                                  \
    return LOG2(x) * 0x1.62e430p-1f;                                                          \
  }

#endif /* DP_LLVMPIPE_LOG_H */
