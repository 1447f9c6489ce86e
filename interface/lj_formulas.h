/* The Lapidous-Jiao per-sample quantities (LJ99 eqs. 3-7, docs/spec.md 6), one source for the host
 * (host/lj/lj_metric.cpp) and the OpenCL kernel (kernels/lj.cl). Binary64 throughout.
 *
 * Stable forms: eq. 7 as written, |Ze(D + delta) - Ze(D)|, subtracts two nearly equal distances
 * when delta is small (32-bit formats, large f/d). Each buffer's difference is rewritten in closed
 * form with no subtraction of nearly equal terms, except the Z buffer's d/Ze - delta·g, which is
 * the distance to its pole and is the quantity itself. D is formed from Ze - d = (f - d)·t and
 * f - Ze = (f - d)·(1 - t) with t = i/(N - 1) taken from integers. */
#ifndef LJ_FORMULAS_H
#define LJ_FORMULAS_H

#include "formats/depth_format.h"

#define LJ_Z 0
#define LJ_W 1
#define LJ_INVERSE_W 2
#define LJ_COMPLEMENTARY_Z 3

#define LJ_UNIFORM 0
#define LJ_INCREASING 1

typedef struct lj_config {
  int buffer;   /* LJ_* */
  int sampling; /* LJ_UNIFORM, LJ_INCREASING */
  double d, f;  /* near and far */
  df_i64 n;     /* samples, both ends included */
} lj_config;

DF_FN double lj_t(lj_config c, df_i64 i) {
  return (double)i / (double)(c.n - 1);
}
DF_FN double lj_rest(lj_config c, df_i64 i) {
  return (double)(c.n - 1 - i) / (double)(c.n - 1);
}

/* Eye distance of sample i: d + (f - d)·i/(N - 1), exactly f at the last. */
DF_FN double lj_distance(lj_config c, df_i64 i) {
  return i == c.n - 1 ? c.f : c.d + (c.f - c.d) * lj_t(c, i);
}

/* Window depth D(Ze) of sample i (LJ eqs. 3-5 and the complementary Z of sec. 3). */
DF_FN double lj_depth(lj_config c, df_i64 i) {
  const double Ze = lj_distance(c, i);
  if (c.buffer == LJ_Z) return c.f * lj_t(c, i) / Ze; /* f/(f-d)·(1 - d/Ze) */
  if (c.buffer == LJ_W) return Ze / c.f;
  if (c.buffer == LJ_INVERSE_W) return c.d / Ze;
  return c.d * lj_rest(c, i) / Ze; /* d/(f-d)·(f/Ze - 1) */
}

/* Per-vertex error dDv: the full binary32 spacing above D, 2^-149 below 2^-126 and at 0. */
DF_FN double lj_vertex_error(double D) {
  if (!(D >= 0x1p-126)) return 0x1p-149;
  int e = 0;
  (void)frexp(D, &e); /* D = m·2^e, m in [0.5, 1): floor(log2 D) = e - 1 */
  return ldexp(1.0, e - 1 - 23);
}

/* dZe for depth D at distance Ze with representation error delta; +inf past the Z pole. */
DF_FN double lj_distance_error(lj_config c, double D, double Ze, double delta) {
  const double d = c.d, f = c.f;
  if (c.buffer == LJ_W) return delta * f;                             /* Ze(D) = D·f */
  if (c.buffer == LJ_INVERSE_W) return d * delta / (D * (D + delta)); /* d/D - d/(D + delta) */
  if (c.buffer == LJ_COMPLEMENTARY_Z) {
    /* Ze(D) = f/(1 + D·k), k = (f - d)/d, 1 + D·k = f/Ze */
    const double k = (f - d) / d;
    const double a = f / Ze;
    return f * delta * k / (a * (a + delta * k));
  }
  /* Z: Ze(D) = d/(1 - D·g), g = (f - d)/f, 1 - D·g = d/Ze */
  const double g = (f - d) / f;
  const double a = d / Ze;
  const double rest = a - delta * g;
  if (!(rest > 0.0)) return INFINITY;
  return d * delta * g / (a * rest);
}

/* Sampling weight s(Ze): 1, or Ze - d = (f - d)·t. */
DF_FN double lj_weight(lj_config c, df_i64 i) {
  return c.sampling == LJ_UNIFORM ? 1.0 : (c.f - c.d) * lj_t(c, i);
}

/* Neumaier's compensated addition: sum and compensation kept apart, added at the end. */
DF_FN void lj_add(double* sum, double* comp, double x) {
  const double t = *sum + x;
  *comp += fabs(*sum) >= fabs(x) ? (*sum - t) + x : (x - t) + *sum;
  *sum = t;
}

/* Sums over samples [first, last): numerator, denominator (each with its compensation),
 * infinite-sample count and vertex-limited count. */
typedef struct lj_partial {
  double num, num_c, den, den_c;
  df_i64 infinite, vertex_limited;
} lj_partial;

DF_FN lj_partial lj_sum_range(lj_config c, df_format fmt, df_i64 first, df_i64 last) {
  lj_partial p;
  p.num = p.num_c = p.den = p.den_c = 0.0;
  p.infinite = p.vertex_limited = 0;
  for (df_i64 i = first; i < last; ++i) {
    const double Ze = lj_distance(c, i);
    const double D = lj_depth(c, i);
    const double dv = lj_vertex_error(D), dp = df_spacing_at(D, fmt);
    if (dv >= dp) ++p.vertex_limited; /* the vertex term limits (ties: both do) */
    const double err = lj_distance_error(c, D, Ze, dv > dp ? dv : dp);
    if (isinf(err)) {
      ++p.infinite;
      continue;
    }
    const double w = lj_weight(c, i);
    lj_add(&p.num, &p.num_c, err * w);
    lj_add(&p.den, &p.den_c, w);
  }
  return p;
}

#endif /* LJ_FORMULAS_H */
