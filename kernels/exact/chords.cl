/* Part of kernels/mts_exact.cl (included after its rows, depths, codes and end pixels): pixels
 * decided clean from plane B's chords against plane A's cached codes, or against A's own chords,
 * and the test-only audit of the chords' margin. */
#if ROW_ENDS && !PARALLEL_RAYS
/* Pixels decided clean from plane B's depth at knots of the row and plane A's cached codes
 * (CHORDS; without A's cache, from A's chords as well: below, chords_clean8). With every pixel of
 * the row covered, finite and inside (its ends' `ok`, ROW_ENDS), a pixel is clean where the depth
 * the pixel loop would compute, D_c, stores a code beyond A's. B's exact depth along the row, G(x)
 * = F(num / den(x)) with den affine in x, is smooth: on a segment of Ls pixels between knots it
 * lies within (Ls^2 / 8) max |G''| of its chord, and for the maps D = p + q/w (standard, infinite,
 * reversed, n/w) it is affine (1/w is), G'' = 0. D_c lies within `margin` of the chord through the
 * knots' computed depths, so a chord value beyond A's code's rounding boundary by more than the
 * margin decides the pixel without computing B there. With u = 2^-53, each bound for the values as
 * computed from the row's binary64 terms (num, den0, den1, n, f, k):
 * - den = den0 + den1 ndc_x is within Delta of its exact value, its least exact magnitude over the
 *   row is dmin, and w = num / den as computed is w (1 + e_w), |e_w| <= rho (t_error, used only
 *   where rho < 2^-20); w is monotone along the row, so every exact w of the row lies in
 *   [wl, wh], the ends' computed w widened by 2 rho;
 * - a computed w moves F(w) by at most |F'(w)| w |e_w| 1.01 <= fw rho 1.01, fw a bound on
 *   |F'(w)| w over [wl, wh] (chord_row); the map's own operations (at most five correctly
 *   rounded products, quotients and differences of the computed w and constants; for the logs
 *   k w, two log1p within 2 ulp, 4u of their values, and a quotient: at most 11u) add at most
 *   16u |D| <= 16u (inside: 0 <= D <= 1);
 *   so D_c is within E = 16u + 1.01 fw rho of the exact depth, at every pixel and at the knots;
 * - G'' = F''(w) w'^2 + F'(w) w'' with w' = -w b/den, w'' = 2 w (b/den)^2 (b = den1 2/vw, den's
 *   step per pixel): |G''| <= (b/dmin)^2 C, C a bound on |F''| w^2 + 2|F'| w over [wl, wh];
 * - the chord through the knots' computed depths is within E of the exact depth's chord, plus
 *   its own roundings ((x - xa) / Ls by a rounded reciprocal, the difference, the product and the
 *   sum, each at most u of a value <= 2): 8u;
 * so |D_c - chord| <= 2E + 8u + (Ls^2 / 8) (b/dmin)^2 C; `margin` adds 8u for the comparisons'
 * own roundings (a product by the code scale M is one rounding, u M; a sum of values <= 2, 2u).
 * The codes then (the encode8 forms): unorm, round to nearest even of D_c M, so D_c M > c + 1/2
 * stores more than c, D_c M < c - 1/2 less (c < max_code, c >= 1: neither clamp can meet it);
 * binary32, round to nearest even of D_c, so D_c above the midpoint of c and the next binary32 up
 * (exact in binary64) stores more than c (c below 1.0f, which CLIP_W's clamp stores at most), and
 * below the midpoint of c and the one down less (c >= 1). */
#define CHORD_SEGMENT 32
typedef struct {
  double base, curve; /* margin = base + curve Ls^2 */
  int usable;
} chord_row_t;

static chord_row_t chord_row(exact_row_t rb, double ox, double vw, uint kw, double n, double f,
                             double k) {
  chord_row_t c;
  c.usable = 0;
  const t_error_t t = t_error(rb, ox, vw, kw);
  const double dmin = t.emin, rho = t.rho;
  if (!(dmin > 0.0) || !(rho < 0x1.0p-20)) return c;
  const double w_a = rb.num / t.e0, w_b = rb.num / t.e1;
  const double wl = min(w_a, w_b) * (1.0 - 2.0 * rho), wh = max(w_a, w_b) * (1.0 + 2.0 * rho);
  if (!(wl > 0.0)) return c;
  /* fw >= |F'(w)| w and C >= |F''(w)| w^2 + 2 |F'(w)| w over [wl, wh], each computed bound
   * widened by 1.01 for its own roundings */
  double fw, C = 0.0;
#if DEPTH_MAP == 0
  fw = 1.0 + fabs(f / (f - n)); /* |F'(w) w| = |q/w| = |D - p| <= 1 + |p|; G'' = 0 */
#elif DEPTH_MAP == 1
  fw = 2.0;
#elif DEPTH_MAP == 2
  fw = 1.0 + fabs(n / (f - n));
#elif DEPTH_MAP == 3
  fw = 1.0;
#elif DEPTH_MAP == 4 || DEPTH_MAP == 7
  /* F = log1p(k w) / L (7: k = 1): F' w = kw / ((1 + kw) L) < 1/L, F'' w^2 = -(kw)^2 / ((1 +
   * kw)^2 L) */
#if DEPTH_MAP == 4
  const double L = log1p(k * f);
#else
  const double L = log1p(f);
#endif
  fw = 1.0 / L;
  C = 3.0 / L;
#elif DEPTH_MAP == 8
  /* F = log1p(w - n) / L: F' w = r / L and F'' w^2 = -r^2 / L, r = w / (1 + w - n) */
  const double L = log1p(f - n), one = 1.0 + wl - n;
  if (!(one > 0.0)) return c;
  const double r = wh / one;
  fw = r / L;
  C = (r * r + 2.0 * r) / L;
#elif DEPTH_MAP == 5
  fw = wh / fabs(f - n); /* F = (w - n)/(f - n): F'' = 0 */
  C = 2.0 * fw;
#else
  fw = wh / f; /* F = w / f */
  C = 2.0 * fw;
#endif
  fw *= 1.01;
  C *= 1.01;
  const double e = 16.0 * 0x1.0p-53 + 1.01 * fw * rho;
  const double b_over_d = fabs(rb.den1) * (2.0 / vw) / dmin;
  c.base = 2.0 * e + 16.0 * 0x1.0p-53;
  c.curve = 1.01 * b_over_d * b_over_d * C / 8.0;
  c.usable = isfinite(c.base) && isfinite(c.curve);
  return c;
}

/* Plane B's computed depth at the knots of four segments from pixel s0 (every CHORD_SEGMENT
 * pixels, the last at the row's last pixel): segment j runs from xk[2j] to xk[2j + 1]. */
static void chord_knots(exact_row_t rb, uint s0, uint kw, double ox, double vw, double n, double f,
                        double k, double* xk, double* d) {
  const double8 knots =
      min((double8)((double)s0) + (double8)(0, 1, 1, 2, 2, 3, 3, 4) * (double)CHORD_SEGMENT,
          (double8)((double)(kw - 1)));
  const double8 ndc_k = 2.0 * (ox + knots + 0.5) / vw - 1.0;
  vstore8(knots, 0, xk);
  vstore8(exact_depth8(rb.num / (rb.den0 + rb.den1 * ndc_k), n, f, k), 0, d);
}

/* The chord of segment j (above) at the 8 pixels from x0, and its margin. */
static double8 chord8(chord_row_t ch, const double* xk, const double* d, uint j, uint x0,
                      double* margin) {
  const double xa = xk[2 * j], xb = xk[2 * j + 1], ls = xb - xa;
  *margin = ch.base + ch.curve * ls * ls;
  const double slope = xb > xa ? (d[2 * j + 1] - d[2 * j]) * (1.0 / ls) : 0.0;
  const double8 xs = (double8)((double)x0) + (double8)(0, 1, 2, 3, 4, 5, 6, 7);
  return d[2 * j] + slope * (xs - xa);
}

#if A_CACHED
/* Whether chord_clean8's comparisons describe the format's codes (encode8's vector forms: unorm
 * rounded to nearest even, binary32 to nearest even keeping denormals); the other formats leave
 * the row to the end pixels' stretches. */
static int chord_codes(df_format fmt) {
#if DF_KIND == 0
  return fmt.rounding == DF_ROUND_NEAREST_EVEN;
#elif DF_E == 8 && DF_M == 23 && DF_IEEE == 1
  return fmt.rounding == DF_ROUND_NEAREST_EVEN && !fmt.flush;
#else
  (void)fmt;
  return 0;
#endif
}

/* Whether the 8 pixels from x0 (those of the row) are certainly clean: the chord beyond the
 * rounding boundary of A's cached code by more than the margin (a format chord_codes accepts). */
static int chord_clean8(double8 chord, double margin, uint x0, uint kw, __global const uint* a_code,
                        df_format fmt) {
  const double8 xs = (double8)((double)x0) + (double8)(0, 1, 2, 3, 4, 5, 6, 7);
  const long8 active = xs < (double)kw;
  const uint8 ca = vload8(0, a_code + x0);
#if DF_KIND == 0
  const double M = (double)fmt.max_code;
  const double8 c = convert_double8(ca);
#if COMPARE_GREATER
  const long8 certain = ((chord + margin) * M < c - 0.5) & (c >= 1.0);
#else
  const long8 certain = ((chord - margin) * M > c + 0.5) & (c < M);
#endif
#elif DF_E == 8 && DF_M == 23 && DF_IEEE == 1
  const double8 here = convert_double8(as_float8(ca));
#if COMPARE_GREATER
  const double8 mid = 0.5 * (convert_double8(as_float8(ca - (uint8)1)) + here);
  const long8 certain = (chord + margin < mid) & (convert_long8(ca) >= (long8)1);
#else
  const double8 mid = 0.5 * (here + convert_double8(as_float8(ca + (uint8)1)));
  const long8 certain = (chord - margin > mid) & (convert_long8(ca) < (long8)0x3f800000);
#endif
#else
  (void)chord;
  (void)ca;
  (void)margin;
  (void)fmt;
  const long8 certain = (long8)0;
#endif
  return !any(active & ~certain);
}
#else
/* The code of a depth as the pixel loop stores it (plane8: clamped first under CLIP_W). */
static uint8 stored8(double8 d, df_format fmt) {
#if CLIP_W
  d = clamp(d, 0.0, 1.0);
#endif
  return encode8(d, fmt);
}

/* Without A's cache: whether the 8 pixels from x0 (those of the row) are certainly clean from
 * both planes' chords. A stored code is monotone in the depth (encode8 rounds, CLIP_W clamps
 * first), and each plane's computed depth lies within its margin of its chord (above), so A's
 * code is at most the code of its chord plus its margin and B's at least the code of its chord
 * less its margin (GEQUAL: the other way round); where those codes are in order the pixel is
 * clean. */
static int chords_clean8(double8 chord_a, double margin_a, double8 chord_b, double margin_b,
                         uint x0, uint kw, df_format fmt) {
  const double8 xs = (double8)((double)x0) + (double8)(0, 1, 2, 3, 4, 5, 6, 7);
  const long8 active = xs < (double)kw;
#if COMPARE_GREATER
  const long8 certain = convert_long8(stored8(chord_b + margin_b, fmt)) <
                        convert_long8(stored8(chord_a - margin_a, fmt));
#else
  const long8 certain = convert_long8(stored8(chord_b - margin_b, fmt)) >
                        convert_long8(stored8(chord_a + margin_a, fmt));
#endif
  return !any(active & ~certain);
}
#endif
#define CHORDS 1
#else
#define CHORDS 0
#endif

#if CHORDS && CHORD_AUDIT
/* Test only (tests/mts/chord_margin.cpp): per (probe, frame, kernel row) of mts_exact's items,
 * the largest (|D_c - chord| + 8u) / margin over the row's pixels of both planes (the margin keeps
 * 8u for the comparisons' roundings), D_c a plane's depth as the pixel loop computes it before
 * clamping and encoding (plane8); -1 where the chords do not apply. */
__kernel void mts_exact_chord_audit(__global const double4* planes, const uint kw, const uint kh,
                                    const double ox, const double oy, const double vw,
                                    const double vh, const double sx, const double sy,
                                    const double k, const uint items, __global double* out) {
  const uint item = get_global_id(0);
  if (item >= items) return;
  const uint y = item % kh, pf = item / kh;
  __global const double4* A = planes + (size_t)pf * 8;
  __global const double4* B = A + 4;
  const double n = A[3].w, f = B[3].w;
  const df_format fmt = DF_FORMAT_FROM_DEFINES();
  const double ndc_y = 2.0 * (oy + (double)y + 0.5) / vh - 1.0;
  const exact_row_t ra = exact_row(A, ndc_y, sx, sy), rb = exact_row(B, ndc_y, sx, sy);
  out[item] = -1.0;
  const ends8_t row = row_ends8(ra, rb, kw, ox, vw, n, f, k, fmt);
  if (!(row.ok.s0 && row.ok.s1 && kw >= 2)) return;
  double worst = 0.0;
  for (int p = 0; p < 2; ++p) {
    const exact_row_t r = p == 0 ? ra : rb;
    const chord_row_t ch = chord_row(r, ox, vw, kw, n, f, k);
    if (!ch.usable) return;
    for (uint s0 = 0; s0 < kw; s0 += 4 * CHORD_SEGMENT) {
      double xk[8], d[8];
      chord_knots(r, s0, kw, ox, vw, n, f, k, xk, d);
      for (uint x0 = s0; x0 < kw && x0 < s0 + 4 * CHORD_SEGMENT; x0 += 8) {
        double margin;
        const double8 chord = chord8(ch, xk, d, (x0 - s0) / CHORD_SEGMENT, x0, &margin);
        const double8 xs = (double8)((double)x0) + (double8)(0, 1, 2, 3, 4, 5, 6, 7);
        const double8 ndc_x = 2.0 * (ox + xs + 0.5) / vw - 1.0;
        long8 covered;
        const double8 dc = exact_depth8(exact_w8(r, ndc_x, 1.0, &covered), n, f, k);
        const double8 q =
            select((double8)0.0, (fabs(dc - chord) + 8.0 * 0x1.0p-53) / margin, xs < (double)kw);
        worst = max(worst, max(max(max(q.s0, q.s1), max(q.s2, q.s3)),
                               max(max(q.s4, q.s5), max(q.s6, q.s7))));
      }
    }
  }
  out[item] = worst;
}
#endif
