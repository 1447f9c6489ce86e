/* Storage formats of a depth buffer (docs/spec.md 4), shared verbatim by the OpenCL kernels and
 * the C++ host: what the GPU stores is computed by exactly this code on both sides.
 *
 *   unorm<b>   code = round(d * (2^b - 1)), b = 1..32
 *   float<N>   IEEE-style unsigned float, E exponent and M mantissa bits, bias 2^(E-1) - 1,
 *              the all-ones exponent reserved (no code stands for inf or NaN)
 *   e<E>m<M>   Lapidous-Jiao eq. 2: no sign, bias 2^E, every exponent field value is a number,
 *              so every code lies in [0, 1)
 *
 * Encoding is exact: a binary32 depth d is split into m * 2^k with an integer m < 2^24, scaled in
 * 64-bit integers and rounded once. Nothing goes through a binary32 product such as
 * d * 16777215.0f, which rounds twice for unorm24 and unorm32.
 *
 * Inputs outside [0, 1]: negative values, -0 and NaN store code 0; values above the largest code
 * (including +inf) saturate to it. */
#ifndef DF_DEPTH_FORMAT_H
#define DF_DEPTH_FORMAT_H

#include "formats/df_prelude.h"

#define DF_KIND_UNORM 0u
#define DF_KIND_FLOAT 1u

#define DF_ROUND_NEAREST_EVEN 0u
#define DF_ROUND_TRUNCATE 1u

/* How a unorm code is computed from the binary32 depth: exactly (one correct rounding, the
 * default), or with the binary32 arithmetic Mesa's llvmpipe uses (lp_bld_conv.c, Mesa 22.3):
 *   unorm16  rint_even(fl32(d * 0x1.fffep-1) * 65536)
 *   unorm24  rint_even(fl32(d * 16777215))                 two roundings
 *   unorm32  2 * trunc(d * 2^31), 2^32 - 1 at d = 1         31 bits, truncated
 * Only those three widths have an llvmpipe form. */
#define DF_CONVERT_EXACT 0u
#define DF_CONVERT_LLVMPIPE 1u
/* Or as Mesa's softpipe does (sp_quad_depth_test.c, convert_quad_depth): the product truncated,
 *   unorm16  (unsigned)fl32(d * 65535)
 *   unorm24  (unsigned)fl32(d * 16777215)
 *   unorm32  (unsigned)fl64(d * 4294967295)
 * again for those three widths only. */
#define DF_CONVERT_SOFTPIPE 2u

typedef struct df_format {
  df_u32 kind;     /* DF_KIND_UNORM or DF_KIND_FLOAT */
  df_u32 bits;     /* total storage bits, 1..32 */
  df_i32 exp_bits; /* E (0 for unorm) */
  df_i32 man_bits; /* M (b for unorm) */
  df_i32 bias;     /* exponent bias (0 for unorm) */
  df_u32 max_code; /* largest code that stands for a finite value */
  df_u32 rounding; /* DF_ROUND_* */
  df_u32 flush;    /* 1: a code that would be subnormal is stored as 0 */
  df_u32 convert;  /* DF_CONVERT_* (unorm only) */
} df_format;

DF_FN df_format df_make_unorm(df_u32 bits, df_u32 rounding, df_u32 flush) {
  df_format f;
  f.kind = DF_KIND_UNORM;
  f.bits = bits;
  f.exp_bits = 0;
  f.man_bits = (df_i32)bits;
  f.bias = 0;
  f.max_code = (df_u32)((((df_u64)1) << bits) - 1u);
  f.rounding = rounding;
  f.flush = flush;
  f.convert = DF_CONVERT_EXACT;
  return f;
}

DF_FN df_format df_with_convert(df_format f, df_u32 convert) {
  f.convert = convert;
  return f;
}

/* ieee_style = 1: bias 2^(E-1) - 1 and the all-ones exponent reserved; 0: LJ bias 2^E. */
DF_FN df_format df_make_float(df_i32 exp_bits, df_i32 man_bits, df_u32 ieee_style, df_u32 rounding,
                              df_u32 flush) {
  df_format f;
  f.kind = DF_KIND_FLOAT;
  f.bits = (df_u32)(exp_bits + man_bits) +
           (ieee_style ? 1u : 0u); /* IEEE-style keeps a sign bit, always 0 */
  f.exp_bits = exp_bits;
  f.man_bits = man_bits;
  f.bias = ieee_style ? (1 << (exp_bits - 1)) - 1 : (1 << exp_bits);
  f.max_code = ieee_style ? (df_u32)(((((df_u64)1) << exp_bits) - 1u) << man_bits) - 1u
                          : (df_u32)((((df_u64)1) << (exp_bits + man_bits)) - 1u);
  f.rounding = rounding;
  f.flush = flush;
  f.convert = DF_CONVERT_EXACT;
  return f;
}

/* Where a format's codes follow binary32 order exactly: the bit pattern T of a binary32 such that
 * for depths d, d' in [-0, 1] of which at least one is >= T, code(d) <= code(d') exactly when
 * d <= d'. A depth test of two such fragments then needs no encoding, only a comparison of the
 * depths. unorm24: from T on, d = k 2^-24 with 2^23 < k <= 2^24, and d (2^24 - 1) = k - k 2^-24
 * lies less than half a unit above k - 1 (round to nearest even; T = 0.5 + 2^-23, since
 * 0.5 + 2^-24 rounds down to code(0.5) = 2^23) or less than a unit (truncation; T = 0.5 + 2^-24,
 * code(0.5) = 2^23 - 1): every code from T on is k - 1, above the codes of all smaller depths.
 * Other formats: none (0xffffffff, no depth reaches it); binary32 storage is already a bit copy.
 * tests/formats/storage_format.cpp checks the property on every binary32 from T's predecessor
 * to 1. */
DF_FN df_u32 df_order_exact_from(df_format f) {
  /* llvmpipe's unorm24, rint(fl32(d (2^24 - 1))): from 0.5 on, fl32(k - d) lies within a unit
   * of k and rounds to k - 1 (0.5 itself stores 2^23, as 0.5 + 2^-24 does): the same T as
   * round to nearest even. softpipe's, trunc(fl32(d (2^24 - 1))), stores k - 1 from 0.5 + 2^-24
   * on but 2^23 - 1 at 0.5, as its predecessor does: truncation's T. */
  if (f.kind == DF_KIND_UNORM && f.bits == 24u)
    return f.convert == DF_CONVERT_LLVMPIPE ||
                   (f.rounding == DF_ROUND_NEAREST_EVEN && f.convert == DF_CONVERT_EXACT)
               ? 0x3f000002u
               : 0x3f000001u;
  return 0xffffffffu;
}

/* floor or round-half-even of p / 2^s for s in 1..63 */
DF_FN df_u64 df_shift_round(df_u64 p, df_u32 s, df_u32 rounding) {
  df_u64 q = p >> s;
  if (rounding == DF_ROUND_NEAREST_EVEN) {
    df_u64 rem = p - (q << s);
    df_u64 halfway = ((df_u64)1) << (s - 1u);
    if (rem > halfway || (rem == halfway && (q & 1u))) q += 1u;
  }
  return q;
}

DF_FN df_u32 df_encode_unorm(df_u32 u, df_format f) {
  df_u32 ex = u >> 23;
  if (ex >= 127u) return f.max_code; /* d >= 1 (and +inf) */
  df_u32 m = ex ? ((u & 0x7fffffu) | 0x800000u) : (u & 0x7fffffu);
  /* d * max_code = m * max_code * 2^-s, s >= 24; the product has at most 56 bits */
  df_u32 s = 150u - (ex ? ex : 1u);
  if (s >= 60u) return 0u; /* product * 2^-s < 2^-4: both rounding modes give 0 */
  df_u64 q = df_shift_round((df_u64)m * (df_u64)f.max_code, s, f.rounding);
  return (df_u32)q;
}

/* binary32 itself (float32 storage): a code is the depth's bit pattern. */
DF_FN int df_is_binary32(df_format f) {
  return f.kind == DF_KIND_FLOAT && f.exp_bits == 8 && f.man_bits == 23 && f.bias == 127 &&
         !f.flush;
}

DF_FN df_u32 df_encode_float(df_u32 u, df_format f) {
  /* binary32 itself (float32): every finite non-negative input is its own code. A specialised
   * kernel folds this test away, leaving no work at all. */
  if (df_is_binary32(f)) return u;
  df_u32 ex = u >> 23;
  df_u32 m = ex ? ((u & 0x7fffffu) | 0x800000u) : (u & 0x7fffffu);
  if (m == 0u) return 0u;
  df_i32 k = (df_i32)(ex ? ex : 1u) - 150;   /* d = m * 2^k exactly */
  df_i32 p = (31 - (df_i32)df_clz32(m)) + k; /* binade: 2^p <= d < 2^(p+1) */
  df_i32 min_p = 1 - f.bias;                 /* binade of the smallest normal */
  df_i32 qp = p > min_p ? p : min_p;
  df_i32 sh = k - (qp - f.man_bits); /* d / quantum = m * 2^sh */
  df_u64 n;
  if (sh >= 0) {
    n = ((df_u64)m) << sh; /* exact; sh <= M so n < 2^(M+1) */
  } else if (sh <= -40) {
    n = 0u; /* m * 2^sh < 2^-16: rounds to 0 either way */
  } else {
    n = df_shift_round((df_u64)m, (df_u32)(-sh), f.rounding);
  }
  /* n carries the hidden bit for normal values, so the exponent field enters as (e - 1); a
   * mantissa that rounds up to 2^(M+1) carries into the exponent by the same addition. */
  df_u64 field = (df_u64)(qp + f.bias - 1);
  df_u64 code = (field << f.man_bits) + n;
  if (code > (df_u64)f.max_code) code = f.max_code;
  if (f.flush && code < (((df_u64)1) << f.man_bits)) code = 0u;
  return (df_u32)code;
}

/* Round half to even of 0 <= x < 2^24 in binary32: below 2^23 adding 2^23 leaves the integer in
 * the sum (the adder rounds); from 2^23 on x is an integer already. */
DF_FN float df_rint_small(float x) {
  return x >= 8388608.0f ? x : (x + 8388608.0f) - 8388608.0f;
}

/* llvmpipe's unorm conversion (DF_CONVERT_LLVMPIPE) of 0 < d < 1. */
DF_FN df_u32 df_encode_unorm_llvmpipe(float d, df_format f) {
  if (f.bits == 16u) return (df_u32)df_rint_small((d * 0x1.fffep-1f) * 65536.0f);
  if (f.bits == 24u) return (df_u32)df_rint_small(d * 16777215.0f);
  const df_u32 t = (df_u32)(d * 2147483648.0f); /* truncating */
  return (t << 1) - (t >> 31);
}

/* softpipe's unorm conversion (DF_CONVERT_SOFTPIPE) of 0 < d < 1. unorm32's binary64 product in
 * integers: d = m 2^-s exactly, m (2^32 - 1) has at most 56 bits, rounded to 53 (half to even)
 * as the binary64 product is, then truncated by the shift. */
DF_FN df_u32 df_encode_unorm_softpipe(float d, df_format f) {
  if (f.bits == 16u) return (df_u32)(d * 65535.0f);
  if (f.bits == 24u) return (df_u32)(d * 16777215.0f);
  const df_u32 u = df_float_bits(d), ex = u >> 23;
  const df_u64 m = ex ? ((u & 0x7fffffu) | 0x800000u) : (u & 0x7fffffu);
  const df_u32 s = 150u - (ex ? ex : 1u);
  df_u64 p = m * (df_u64)0xffffffffu;
  const df_u32 extra = (p >> 55) ? 3u : (p >> 54) ? 2u : (p >> 53) ? 1u : 0u;
  if (extra) p = df_shift_round(p, extra, DF_ROUND_NEAREST_EVEN) << extra;
  return s > 56u ? 0u : (df_u32)(p >> s);
}

/* Storage code of a binary32 window depth. */
DF_FN df_u32 df_encode(float d, df_format f) {
  df_u32 u = df_float_bits(d);
  if (u >> 31) return 0u;         /* negative, -0 */
  if (u > 0x7f800000u) return 0u; /* NaN */
  if (u == 0x7f800000u) return f.max_code;
  if (f.kind == DF_KIND_UNORM && f.convert == DF_CONVERT_LLVMPIPE)
    return u == 0u ? 0u : (u >= 0x3f800000u ? f.max_code : df_encode_unorm_llvmpipe(d, f));
  if (f.kind == DF_KIND_UNORM && f.convert == DF_CONVERT_SOFTPIPE)
    return u == 0u ? 0u : (u >= 0x3f800000u ? f.max_code : df_encode_unorm_softpipe(d, f));
  return f.kind == DF_KIND_UNORM ? df_encode_unorm(u, f) : df_encode_float(u, f);
}

/* Branch-free unorm encoding, the same rounding as df_encode_unorm, written once for any
 * 64-bit lane type U (a scalar, or an OpenCL ulongN vector where the comparisons below act per
 * lane): `u` holds the binary32 bit pattern. The kernels' vector loop uses the vector
 * instantiation; tests prove it equal to df_encode on every binary32 in [0, 1]. */
#define DF_DEFINE_ENCODE_UNORM_BF(NAME, U)                                                     \
  DF_FN U NAME(U u, df_format f) {                                                             \
    const U ex = (u >> 23) & (U)0xffu;                                                         \
    const U man = u & (U)0x7fffffu;                                                            \
    const U m = ex != (U)0 ? (man | (U)0x800000u) : man;                                       \
    const U big = ex >= (U)127 ? (U)1 : (U)0; /* d >= 1, inf, NaN */                           \
    const U s0 = (U)150 - (ex != (U)0 ? ex : (U)1);                                            \
    const U s = big != (U)0 ? (U)23 : (s0 > (U)63 ? (U)63 : s0);                               \
    const U p = m * (U)f.max_code;                                                             \
    U q = p >> s;                                                                              \
    const U rem = p - (q << s);                                                                \
    const U halfway = ((U)1 << s) >> 1;                                                        \
    if (f.rounding == DF_ROUND_NEAREST_EVEN)                                                   \
      q = (rem > halfway || (rem == halfway && (q & (U)1) != (U)0)) ? q + (U)1 : q;            \
    const U zero = ((u >> 31) != (U)0 || (u & (U)0x7fffffffu) > (U)0x7f800000u) ? (U)1 : (U)0; \
    return zero != (U)0 ? (U)0 : (big != (U)0 ? (U)f.max_code : q);                            \
  }

/* Formats whose 16-lane encoders (OpenCL only, below) are df_encode lane by lane (the float formats
 * other than binary32): for them a comparison of the lanes with df_encode compares a function with
 * itself. */
DF_FN int df_encode16_is_scalar(df_format f) {
  return f.kind == DF_KIND_FLOAT && !df_is_binary32(f);
}

#if defined(DF_OPENCL)
DF_DEFINE_ENCODE_UNORM_BF(df_encode_unorm_bf16, ulong16)

#if defined(cl_khr_fp64)
#pragma OPENCL EXTENSION cl_khr_fp64 : enable
/* unorm<b> for b <= 29 in binary64 of d in [-0, 1] (no NaN): d * (2^b - 1) is exact there (a
 * 24-bit significand times a b-bit integer), so one product and one rounding to an integer give
 * the code df_encode_unorm computes in 64-bit integers, in a few instructions per lane instead of
 * a 64-bit multiply and variable shifts. 0 <= p < 2^29: adding 2^52 rounds p to an integer, half
 * to even, in the adder itself (the library rint is slow in software), and leaves that integer in
 * the low bits of the sum's significand, so no subtraction or conversion back is needed; -0
 * gives 2^52, code 0. Truncation toward zero is the conversion itself. */
DF_FN uint16 df_encode_unorm_f64_16_unit(float16 d, df_format f) {
  const double16 p = convert_double16(d) * (double16)((double)f.max_code);
  return f.rounding == DF_ROUND_NEAREST_EVEN ? convert_uint16(as_ulong16(p + 0x1p52))
                                             : convert_uint16(p);
}

/* Any binary32: negative and NaN store 0, 1 and above (and +inf) the largest code. The
 * exhaustive format proof (kernels/encode.cl) compares it with df_encode_unorm. */
DF_FN uint16 df_encode_unorm_f64_16(float16 d, df_format f) {
  const uint16 u = as_uint16(d);
  const int16 zero = (u >> 31) != (uint16)0 || (u & (uint16)0x7fffffffu) > (uint16)0x7f800000u;
  const int16 big = !zero && d >= 1.0f;                 /* and +inf */
  const float16 in = (zero || big) ? (float16)0.0f : d; /* no inf or NaN reaches the conversion */
  const uint16 q = df_encode_unorm_f64_16_unit(in, f);
  return big ? (uint16)f.max_code : (zero ? (uint16)0 : q);
}
#endif

/* 16 depths at once: branch-free for unorm, the identity for float32 (keeping denormals), lane by
 * lane through the scalar encoder for the other float formats (df_encode16_is_scalar). */
/* llvmpipe's conversion (df_encode_unorm_llvmpipe) of 16 depths in [-0, 1], the same roundings
 * lane by lane: df_rint_small's trick, and the truncating conversion of convert_uint16. */
DF_FN uint16 df_encode_unorm_llvmpipe16_unit(float16 d, df_format f) {
  if (f.bits == 32u) {
    const uint16 t = convert_uint16(d * 2147483648.0f);
    return (t << 1) - (t >> 31);
  }
  const float16 x = f.bits == 16u ? (d * 0x1.fffep-1f) * 65536.0f : d * 16777215.0f;
  const float16 r = x >= 8388608.0f ? x : (x + 8388608.0f) - 8388608.0f;
  return convert_uint16(r);
}

/* softpipe's conversion (df_encode_unorm_softpipe) of 16 depths in [-0, 1]: convert_uint16
 * truncates as the C cast does; unorm32 lane by lane. */
DF_FN uint16 df_encode_unorm_softpipe16_unit(float16 d, df_format f) {
  if (f.bits == 16u) return convert_uint16(d * 65535.0f);
  if (f.bits == 24u) return convert_uint16(d * 16777215.0f);
  float a[16];
  uint c[16];
  vstore16(d, 0, a);
  for (int k = 0; k < 16; ++k) c[k] = a[k] > 0.0f ? df_encode_unorm_softpipe(a[k], f) : 0u;
  return vload16(0, c);
}

/* The unorm conversion of 16 depths in [-0, 1] for a format with a driver's conversion. */
DF_FN uint16 df_encode_unorm_driver16_unit(float16 d, df_format f) {
  return f.convert == DF_CONVERT_SOFTPIPE ? df_encode_unorm_softpipe16_unit(d, f)
                                          : df_encode_unorm_llvmpipe16_unit(d, f);
}

DF_FN uint16 df_encode16(float16 d, df_format f) {
  if (f.kind == DF_KIND_UNORM && f.convert != DF_CONVERT_EXACT) {
    const uint16 u = as_uint16(d);
    const int16 zero = (u >> 31) != (uint16)0 || (u & (uint16)0x7fffffffu) > (uint16)0x7f800000u;
    const int16 big = !zero && d >= 1.0f; /* and +inf */
    const uint16 q = df_encode_unorm_driver16_unit((zero || big) ? (float16)0.0f : d, f);
    return big ? (uint16)f.max_code : (zero ? (uint16)0 : q);
  }
#if defined(cl_khr_fp64)
  if (f.kind == DF_KIND_UNORM && f.bits <= 29u) return df_encode_unorm_f64_16(d, f);
#endif
  if (f.kind == DF_KIND_UNORM)
    return convert_uint16(df_encode_unorm_bf16(convert_ulong16(as_uint16(d)), f));
  if (!df_encode16_is_scalar(f)) { /* binary32 */
    const uint16 u = as_uint16(d);
    /* negative and NaN store 0; finite non-negative values are their own code */
    return ((u >> 31) != (uint16)0 || (u & (uint16)0x7fffffffu) > (uint16)0x7f800000u)
               ? (uint16)0
               : (u == (uint16)0x7f800000u ? (uint16)f.max_code : u);
  }
  float a[16];
  uint c[16];
  vstore16(d, 0, a);
  for (int k = 0; k < 16; ++k) c[k] = df_encode(a[k], f);
  return vload16(0, c);
}

/* df_encode16 for depths known to lie in [-0, 1] (a fragment whose depth is finite and unclipped,
 * or clamped): the checks for negative, NaN and too large values fall away, which is a good part
 * of the pixel loop. The exhaustive format proof compares it with df_encode on [0, 1] and -0. */
DF_FN uint16 df_encode16_unit(float16 d, df_format f) {
  if (f.kind == DF_KIND_UNORM && f.convert != DF_CONVERT_EXACT)
    return df_encode_unorm_driver16_unit(d, f);
#if defined(cl_khr_fp64)
  if (f.kind == DF_KIND_UNORM && f.bits <= 29u) return df_encode_unorm_f64_16_unit(d, f);
#endif
  if (df_is_binary32(f)) return as_uint16(d) & (uint16)0x7fffffffu; /* -0 stores 0 */
  return df_encode16(d, f);
}
#endif

/* The neighbouring codes, saturating at the ends of the code range. */
DF_FN df_u32 df_code_above(df_u32 c, df_format f) {
  return c < f.max_code ? c + 1u : c;
}
DF_FN df_u32 df_code_below(df_u32 c) {
  return c > 0u ? c - 1u : c;
}

/* A kernel specialised with -D defines (see host/model/storage_format.cpp) gets its format as a
 * compile-time constant, so every branch on the kind folds away. */
#if defined(DF_KIND) && defined(DF_ROUNDING) && defined(DF_FLUSH)
#if DF_KIND == 0
#define DF_FORMAT_FROM_DEFINES() \
  df_with_convert(df_make_unorm(DF_BITS, DF_ROUNDING, DF_FLUSH), DF_CONVERT)
#else
#define DF_FORMAT_FROM_DEFINES() df_make_float(DF_E, DF_M, DF_IEEE, DF_ROUNDING, DF_FLUSH)
#endif
#endif

#if !defined(DF_OPENCL) || defined(DF_ENABLE_FP64)
#if defined(DF_OPENCL)
#pragma OPENCL EXTENSION cl_khr_fp64 : enable
#else
#include <math.h>
#endif
/* Exact value of a code for float formats; correctly rounded binary64 of c / (2^b - 1) for unorm
 * (the only quotient here that binary64 cannot hold exactly). */
DF_FN double df_decode(df_u32 c, df_format f) {
  if (c > f.max_code) c = f.max_code;
  if (f.kind == DF_KIND_UNORM) return (double)c / (double)f.max_code;
  df_u32 e = (df_u32)(((df_u64)c) >> f.man_bits);
  df_u64 frac = ((df_u64)c) & ((((df_u64)1) << f.man_bits) - 1u);
  if (e == 0u) return ldexp((double)frac, 1 - f.bias - f.man_bits);
  return ldexp((double)((((df_u64)1) << f.man_bits) + frac), (df_i32)e - f.bias - f.man_bits);
}

/* Storage code of a binary64 window depth, correctly rounded from the binary64 value (the
 * storage-limited pipeline of MTS attribution: depth exact up to binary64, then stored). Same
 * rules as df_encode; for a binary32 input the same code. d * max_code needs up to 85 bits for
 * unorm, so its rounding error is recovered with an FMA and decides the rounding; floats split d
 * into m * 2^k with m < 2^53 as df_encode_float does with m < 2^24. */
DF_FN df_u32 df_encode_f64(double d, df_format f) {
  if (!(d > 0.0)) return 0u; /* negative, zero and NaN */
  if (d >= 1.0 && f.kind == DF_KIND_UNORM) return f.max_code;
  if (f.kind == DF_KIND_UNORM) {
    const double M = (double)f.max_code;
    const double hi = d * M;
    const double err = fma(d, M, -hi); /* d * M = hi + err exactly */
    const double q = floor(hi);
    const double frac = hi - q; /* exact: hi < 2^32 keeps >= 20 fraction bits */
    df_u64 code = (df_u64)q;
    if (f.rounding == DF_ROUND_NEAREST_EVEN) {
      const double t =
          (frac - 0.5) + err; /* sign exact: |err| <= ulp(hi)/2 <= |frac - 0.5| unless 0 */
      if (t > 0.0 || (t == 0.0 && (code & 1u))) code += 1u;
    } else if (frac == 0.0 && err < 0.0) {
      code -= 1u;
    }
    return code > (df_u64)f.max_code ? f.max_code : (df_u32)code;
  }
  if (d > df_decode(f.max_code, f) * 2.0)
    return f.max_code; /* far above the largest code, and +inf */
  int e = 0;
  const double fr = frexp(d, &e);
  const df_u64 m = (df_u64)ldexp(fr, 53); /* d = m * 2^k exactly, 2^52 <= m < 2^53 */
  const df_i32 k = e - 53;
  const df_i32 p = e - 1;
  const df_i32 min_p = 1 - f.bias;
  const df_i32 qp = p > min_p ? p : min_p;
  const df_i32 sh = k - (qp - f.man_bits); /* < 0: M <= 31 < 52 */
  const df_u64 n = -sh >= 60 ? 0u : df_shift_round(m, (df_u32)(-sh), f.rounding);
  const df_u64 field = (df_u64)(qp + f.bias - 1);
  df_u64 code = (field << f.man_bits) + n;
  if (code > (df_u64)f.max_code) code = f.max_code;
  if (f.flush && code < (((df_u64)1) << f.man_bits)) code = 0u;
  return (df_u32)code;
}

/* Spacing between the code at or below v and the next code above it (docs/spec.md 6: the per-pixel
 * error dDp), exact: 1/(2^b - 1) correctly rounded for unorm, a power of two for floats (the
 * quantum of v's binade, or of the subnormal range); at or above the largest code, the spacing
 * below it. */
DF_FN double df_spacing_at(double v, df_format f) {
  if (f.kind == DF_KIND_UNORM) return 1.0 / (double)f.max_code;
  const double top = df_decode(f.max_code, f);
  if (v >= top) return top - df_decode(f.max_code - 1u, f);
  int e = 0;
  const int min_p = 1 - f.bias;
  int p = min_p;
  if (v > 0.0) {
    (void)frexp(v, &e);
    p = e - 1 > min_p ? e - 1 : min_p;
  }
  return ldexp(1.0, p - f.man_bits);
}
#endif

#endif /* DF_DEPTH_FORMAT_H */
