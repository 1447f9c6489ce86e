/* The few words that differ between OpenCL C and C/C++, so that formats/ is one source for
 * both the kernels and the host. Everything after this prelude is the common subset. */
#ifndef DF_PRELUDE_H
#define DF_PRELUDE_H

#if defined(__OPENCL_VERSION__) || defined(__OPENCL_C_VERSION__)
#define DF_OPENCL 1
typedef uint df_u32;
typedef ulong df_u64;
typedef int df_i32;
typedef long df_i64;
#define DF_FN static inline
#define df_float_bits(x) as_uint(x)
#define df_bits_float(u) as_float(u)
#define df_clz32(x) clz(x)
#else
#include <stdint.h>
#include <string.h>
typedef uint32_t df_u32;
typedef uint64_t df_u64;
typedef int32_t df_i32;
typedef int64_t df_i64;
#define DF_FN static inline
DF_FN df_u32 df_float_bits(float x) {
  df_u32 u;
  memcpy(&u, &x, sizeof u);
  return u;
}
DF_FN float df_bits_float(df_u32 u) {
  float x;
  memcpy(&x, &u, sizeof x);
  return x;
}
DF_FN df_u32 df_clz32(df_u32 x) {
  return x ? (df_u32)__builtin_clz(x) : 32u;
}
#endif

#endif /* DF_PRELUDE_H */
