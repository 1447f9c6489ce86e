/* The storage-limited pipeline of MTS attribution (docs/stability.md): the same probes as
 * kernels/mts.cl, but every step before storage exact up to binary64 -- the depth of each plane
 * at each kernel pixel centre from the ray through it (no vertex rounding, no binary32
 * arithmetic, no interpolation error), the technique's exact mapping D(w), then the storage
 * format's correctly rounded code (df_encode_f64). What is left is the error of storage alone.
 *
 * Defines: A_CACHED (1: plane A's codes and status at every pixel come from mts_exact_a's cache,
 * filled once per distance and frame for the probes that follow), ROW_ENDS (1: decide a row from
 * its end pixels where that is certain, and its pixels from plane B's chords against A's cached
 * codes or A's chords (CHORDS), below; 0: every pixel, to check that the shortcuts change nothing),
 * DEPTH_MAP (0 standard, 1 infinite, 2 reversed, 3 n/w, 4 log, 5 linear, 6 w/f, 7 log2(1
 * + w) / log2(1 + f), 8 log2(w - n + 1) / log2(f
 * - n + 1); host/model/technique.h DepthMap), CLIP_W (1: the technique writes depth in the fragment
 * stage -- clip by the standard volume n <= w <= f and clamp d; 0: clip where d leaves [0, 1]),
 * PARALLEL_RAYS (1: an orthographic view's parallel rays), COMPARE_GREATER, and the format's. */
#pragma OPENCL EXTENSION cl_khr_fp64 : enable
#define DF_ENABLE_FP64 1
#include "formats/depth_format.h"
#include "interface/mts_layout.h" /* the row result word the host folds (R_*), as kernels/mts.cl writes it */

/* The exact mapping D(w) of the technique, 8 lanes at a time. */
static double8 exact_depth8(double8 w, double n, double f, double k) {
#if DEPTH_MAP == 0
  return f * (w - n) / (w * (f - n));
#elif DEPTH_MAP == 1
  return (w - n) / w;
#elif DEPTH_MAP == 2
  return n * (f - w) / (w * (f - n));
#elif DEPTH_MAP == 3
  return n / w;
#elif DEPTH_MAP == 4
  return log1p(k * w) / log1p(k * f);
#elif DEPTH_MAP == 5
  return (w - n) / (f - n);
#elif DEPTH_MAP == 7
  return log1p(w) / log1p(f);
#elif DEPTH_MAP == 8
  return log1p(w - n) / log1p(f - n);
#else
  return w / f;
#endif
}

/* Storage codes of 8 binary64 depths in [0, 1]: the shared df_encode_f64, with the common
 * cases in vector form (unorm by the same FMA rounding; float32 keeping denormals is binary64 ->
 * binary32 conversion, round to nearest even). */
static uint8 encode8(double8 d, df_format fmt) {
#if DF_KIND == 0
  if (fmt.rounding == DF_ROUND_NEAREST_EVEN) {
    const double M = (double)fmt.max_code;
    const double8 hi = d * M;
    const double8 err = fma(d, (double8)M, -hi);
    const double8 q = floor(hi);
    const double8 t = (hi - q - 0.5) + err;
    ulong8 code = convert_ulong8(q);
    const long8 up = (t > 0.0) | ((t == 0.0) & convert_long8((code & (ulong8)1) != (ulong8)0));
    code += as_ulong8(up) & (ulong8)1;
    code = select(code, (ulong8)fmt.max_code, (d >= 1.0) | (code > (ulong8)fmt.max_code));
    return convert_uint8(select(code, (ulong8)0, !(d > 0.0)));
  }
#elif DF_E == 8 && DF_M == 23 && DF_IEEE == 1
  if (fmt.rounding == DF_ROUND_NEAREST_EVEN && !fmt.flush)
    return select(as_uint8(convert_float8_rte(d)), (uint8)0, convert_int8(!(d > 0.0)));
#endif
  double a[8];
  uint c[8];
  vstore8(d, 0, a);
  for (int i = 0; i < 8; ++i) c[i] = df_encode_f64(a[i], fmt);
  return vload8(0, c);
}

/* One plane's per-row terms: along the row, the ray meets the plane at t = num / (den0 + den1 x),
 * and the in-plane coordinates are t (ua0 + ua1 x) - ca along the a axis, likewise b. An
 * orthographic view's rays (PARALLEL_RAYS) are parallel, at (X x, Y y) across it (X, Y its
 * half-extents at plane A's distance, which its plane record carries in a.w): there
 * t = (num + num1 x) / den0 and the in-plane coordinate is (ua0 + ua1 x) - t az - ca. */
typedef struct {
  double num, den0, den1, ua0, ua1, ca, ha, ub0, ub1, cb, hb;
#if PARALLEL_RAYS
  double num1, az, bz;
#endif
} exact_row_t;

static exact_row_t exact_row(__global const double4* pl, double ndc_y, double sx, double sy) {
  const double3 a = pl[0].xyz, b = pl[1].xyz, nrm = pl[2].xyz, c = pl[3].xyz;
  exact_row_t r;
#if PARALLEL_RAYS
  const double X = sx * pl[0].w, Y = sy * pl[0].w;
  r.num = nrm.y * (ndc_y * Y) - dot(nrm, c);
  r.num1 = nrm.x * X;
  r.den0 = nrm.z;
  r.den1 = 0.0;
  r.ua0 = a.y * (ndc_y * Y);
  r.ua1 = a.x * X;
  r.az = a.z;
  r.ub0 = b.y * (ndc_y * Y);
  r.ub1 = b.x * X;
  r.bz = b.z;
#else
  r.num = dot(nrm, c);
  r.den0 = ndc_y * sy * nrm.y - nrm.z;
  r.den1 = sx * nrm.x;
  r.ua0 = ndc_y * sy * a.y - a.z;
  r.ua1 = sx * a.x;
  r.ub0 = ndc_y * sy * b.y - b.z;
  r.ub1 = sx * b.x;
#endif
  r.ca = dot(c, a);
  r.ha = 0.5 * dot(a, a);
  r.cb = dot(c, b);
  r.hb = 0.5 * dot(b, b);
  return r;
}

/* w at 8 pixels of the row (ndc_x), and whether the plane's square, its half-sides times
 * shrink (1: the square itself), covers them. */
static double8 exact_w8(exact_row_t r, double8 ndc_x, double shrink, long8* covered) {
#if PARALLEL_RAYS
  const double8 t = (r.num + r.num1 * ndc_x) / r.den0;
  const double8 u = (r.ua0 + r.ua1 * ndc_x) - t * r.az - r.ca;
  const double8 v = (r.ub0 + r.ub1 * ndc_x) - t * r.bz - r.cb;
#else
  const double8 t = r.num / (r.den0 + r.den1 * ndc_x);
  const double8 u = t * (r.ua0 + r.ua1 * ndc_x) - r.ca, v = t * (r.ub0 + r.ub1 * ndc_x) - r.cb;
#endif
  *covered = (t > 0.0) & (fabs(u) <= r.ha * shrink) & (fabs(v) <= r.hb * shrink);
  return t;
}

/* Eight pixels of the row from x0: their flags and fragment pairs, as mts_raster reports them. */
/* Plane A's status bits at a pixel (A_CACHED), as pixels8 computes them. */
#define A_COVERED 1
#define A_FINITE 2
#define A_INSIDE 4

/* One plane at 8 pixels: its code (clamped into [0, 1] first under CLIP_W) and whether the
 * pixels are covered (by the square's half-sides times shrink), finite and inside (!CLIP_W: D at
 * most top). The pixel loop takes the plane itself, shrink = top = 1; the end-pixel shortcut
 * (ROW_ENDS) its margins. */
static uint8 plane8(exact_row_t r, double8 ndc_x, double shrink, double top, double n, double f,
                    double k, df_format fmt, long8* covered, long8* finite, long8* inside) {
  const double8 w = exact_w8(r, ndc_x, shrink, covered);
  double8 d = exact_depth8(w, n, f, k);
  *finite = isfinite(d);
#if CLIP_W
  (void)top;
  *inside = (w >= n) & (w <= f);
  d = clamp(d, 0.0, 1.0);
#else
  *inside = (d >= 0.0) & (d <= top);
#endif
  return encode8(d, fmt);
}

/* Eight pixels of the row from x0: their flags and fragment pairs, as mts_raster reports them.
 * a_code, a_bits: plane A's codes and status bits of the row (A_CACHED; unread otherwise). */
static void pixels8(exact_row_t ra, exact_row_t rb, uint x0, double ox, double vw, uint kw,
                    double n, double f, double k, df_format fmt, __global const uint* a_code,
                    __global const uchar* a_bits, ulong* pairs, uint* flags) {
  const double8 xs = (double8)((double)x0) + (double8)(0, 1, 2, 3, 4, 5, 6, 7);
  const long8 active = xs < (double)kw;
  const double8 ndc_x = 2.0 * (ox + xs + 0.5) / vw - 1.0;
  long8 cov_a, cov_b, fin_a, fin_b, in_a, in_b;
#if A_CACHED
  const uint8 ca = vload8(0, a_code + x0);
  const long8 bits = convert_long8(vload8(0, a_bits + x0));
  cov_a = (bits & (long8)A_COVERED) != (long8)0;
  fin_a = (bits & (long8)A_FINITE) != (long8)0;
  in_a = (bits & (long8)A_INSIDE) != (long8)0;
#else
  const uint8 ca = plane8(ra, ndc_x, 1.0, 1.0, n, f, k, fmt, &cov_a, &fin_a, &in_a);
#endif
  const uint8 cb = plane8(rb, ndc_x, 1.0, 1.0, n, f, k, fmt, &cov_b, &fin_b, &in_b);
  const long8 covered = active & cov_a & cov_b;
  if (any(active & ~covered)) *flags |= MTS_R_UNCOVERED;
  const long8 finite = fin_a & fin_b;
  if (any(covered & ~finite)) *flags |= MTS_R_NONFINITE;
  const long8 inside = in_a & in_b;
  if (any(covered & finite & ~inside)) *flags |= MTS_R_CLIPPED;
  const long8 ok = covered & finite & inside;
  *pairs += (ulong)(-(long)(ok.s0 + ok.s1 + ok.s2 + ok.s3 + ok.s4 + ok.s5 + ok.s6 + ok.s7));
#if COMPARE_GREATER
  const int8 fight = cb >= ca;
#else
  const int8 fight = cb <= ca;
#endif
  if (any(convert_long8(fight) & ok)) *flags |= MTS_R_FIGHT;
}

#if ROW_ENDS
/* Stretches of a row decided clean from their two end pixels alone: where plane B's codes lie
 * many codes beyond A's (the descent's probes, far above the MTS) no pixel between can fight.
 * - Along the row ndc_x, den0 + den1 ndc_x (rounding is monotone) and t = num / den are
 *   monotone in x as computed, while den keeps its sign -- it does between two ends where t > 0.
 *   Orthographic: num + num1 ndc_x and its quotient by the constant den0 are monotone as
 *   computed. So w, inside (w in [n, f]) and finiteness hold at every pixel between ends where
 *   they hold. The exact u and v are Moebius maps of x (orthographic: affine), monotone, and
 *   their computed values within ha 2^-37 (hb 2^-37) of them where row_trusted says so: ends
 *   covered by the square shrunk by 2^-36 (kShrink) then put every pixel between inside the
 *   square itself.
 * - D(w) as computed, at the computed w (monotone along the row), is the exact, monotone D(w)
 *   times (1 + e), |e| a few binary64 ulps (its quotients and products; log1p within 2 ulp), far
 *   below a code's step, so a pixel's code is within one of the code of the exact D, which is
 *   monotone along the row: every code of the stretch lies within 2 of the range its ends span.
 *   A stretch whose plane-B codes lie 5 or more beyond its plane-A codes at both ends is clean at
 *   every pixel (ENDS_MARGIN, 6).
 * - !CLIP_W: D inside [0, 1] is checked at the ends with a margin of 2^-46 below 1 (its sign is
 *   exact), so no pixel between leaves it by D's own rounding. */
#define ENDS_MARGIN 6
#define kShrink (1.0 - 0x1.0p-36)

/* Both planes' codes at 8 pixels xs of the row, 'ahead' the codes of the plane that must be
 * ahead (B's; A's under COMPARE_GREATER), and which pixels are certain (above). */
typedef struct {
  long8 ok, ahead, behind;
} ends8_t;

static ends8_t ends8(exact_row_t ra, exact_row_t rb, double8 xs, double ox, double vw, double n,
                     double f, double k, df_format fmt) {
  const double8 ndc_x = 2.0 * (ox + xs + 0.5) / vw - 1.0;
  const double top = 1.0 - 0x1.0p-46;
  long8 cov_a, cov_b, fin_a, fin_b, in_a, in_b;
  const long8 ca = convert_long8(
                  plane8(ra, ndc_x, kShrink, top, n, f, k, fmt, &cov_a, &fin_a, &in_a)),
              cb = convert_long8(
                  plane8(rb, ndc_x, kShrink, top, n, f, k, fmt, &cov_b, &fin_b, &in_b));
  ends8_t e;
  e.ok = cov_a & cov_b & fin_a & fin_b & in_a & in_b;
#if COMPARE_GREATER
  e.ahead = ca;
  e.behind = cb;
#else
  e.ahead = cb;
  e.behind = ca;
#endif
  return e;
}

/* How well a plane's ray parameter t = num / den (parallel rays: (num + num1 ndc_x) / den0) is
 * conditioned along the row: its varying part at the end pixels, e0 and e1, each within
 * delta = 2^-50 (the magnitudes of its terms) of its exact value (ndc_x within 3u, a sum and a
 * product, or one fma); that part is affine in x and keeps its sign (t > 0 at the ends), so its
 * least exact magnitude over the row is emin = min(|e0|, |e1|) - 2 delta (2: the ends' own
 * rounding), and t as computed is t (1 + e), |e| <= rho = 1.01 delta / emin + 2u (the quotient's
 * own rounding; 1.01 covers the higher orders where rho < 2^-20, the most either user allows). */
typedef struct {
  double e0, e1, delta, emin, rho;
} t_error_t;

static t_error_t t_error(exact_row_t r, double ox, double vw, uint kw) {
  const double last = (double)(kw - 1);
  const double ndc0 = 2.0 * (ox + 0.5) / vw - 1.0, ndc1 = 2.0 * (ox + last + 0.5) / vw - 1.0;
  t_error_t t;
#if PARALLEL_RAYS
  t.e0 = r.num + r.num1 * ndc0;
  t.e1 = r.num + r.num1 * ndc1;
  t.delta = 0x1.0p-50 * (fabs(r.num) + fabs(r.num1));
#else
  t.e0 = r.den0 + r.den1 * ndc0;
  t.e1 = r.den0 + r.den1 * ndc1;
  t.delta = 0x1.0p-50 * (fabs(r.den0) + fabs(r.den1));
#endif
  t.emin = min(fabs(t.e0), fabs(t.e1)) - 2.0 * t.delta;
  t.rho = 1.01 * t.delta / t.emin + 0x1.0p-52;
  return t;
}

/* Whether a plane's computed u and v lie within ha 2^-37 and hb 2^-37 of their exact values at
 * every pixel of the row (the covered argument above): u = t (ua0 + ua1 ndc_x) - ca (parallel:
 * (ua0 + ua1 ndc_x) - t az - ca) errs by at most (rho + 2^-50) times the magnitudes of its terms
 * (t's error, t_error, and each sum's and product's rounding, 2^-53 of a magnitude each). Where t
 * is ill-conditioned (a ray grazing the plane) this can fail, and the row takes the pixel loop. */
static int row_trusted(exact_row_t r, double ox, double vw, uint kw) {
  const t_error_t t = t_error(r, ox, vw, kw);
  if (!(t.emin > 0.0) || !(t.rho < 0x1.0p-20)) return 0;
#if PARALLEL_RAYS
  const double tmax =
      (max(fabs(t.e0), fabs(t.e1)) + 2.0 * t.delta) / fabs(r.den0) * (1.0 + 0x1.0p-50);
  const double ua = fabs(r.ua0) + fabs(r.ua1) + tmax * fabs(r.az),
               ub = fabs(r.ub0) + fabs(r.ub1) + tmax * fabs(r.bz);
#else
  const double tmax = fabs(r.num) / t.emin * (1.0 + 0x1.0p-50);
  const double ua = tmax * (fabs(r.ua0) + fabs(r.ua1)), ub = tmax * (fabs(r.ub0) + fabs(r.ub1));
#endif
  const double eu = (t.rho + 0x1.0p-50) * (ua + fabs(r.ca)),
               ev = (t.rho + 0x1.0p-50) * (ub + fabs(r.cb));
  return eu < r.ha * 0x1.0p-37 && ev < r.hb * 0x1.0p-37;
}

/* The row's two end pixels (lanes 0 and 1), `ok` only where both planes' rows are trusted. */
static ends8_t row_ends8(exact_row_t ra, exact_row_t rb, uint kw, double ox, double vw, double n,
                         double f, double k, df_format fmt) {
  const double last = (double)(kw - 1);
  ends8_t row =
      ends8(ra, rb, (double8)(0.0, last, 0.0, last, 0.0, last, 0.0, last), ox, vw, n, f, k, fmt);
  if (!(row_trusted(ra, ox, vw, kw) && row_trusted(rb, ox, vw, kw))) row.ok = (long8)0;
  return row;
}

/* Which of four stretches, the ends of stretch j in lanes 2j and 2j + 1, are clean throughout. */
static long4 stretches_clean(ends8_t e) {
  const long4 lo = min(e.ahead.even, e.ahead.odd), hi = max(e.behind.even, e.behind.odd);
  return e.ok.even & e.ok.odd & (lo - hi >= (long4)ENDS_MARGIN);
}
#endif

#include "kernels/exact/chords.cl" /* CHORDS: pixels decided from the planes' chords */

#if A_CACHED
/* Plane A's codes and status bits at every pixel of one kernel row of a (distance, frame), for
 * the probes at that distance that follow: one work item per (frame, kernel row) of `planes`
 * (plane A's records, then B's, whose centre.w holds the mapping's far), written at frame
 * first_frame + its index of the cache (rows of kw_pad pixels). */
__kernel void mts_exact_a(__global const double4* planes, const uint kw, const uint kh,
                          const double ox, const double oy, const double vw, const double vh,
                          const double sx, const double sy, const double k, const uint items,
                          const uint kw_pad, const uint first_frame, __global uint* a_code,
                          __global uchar* a_bits) {
  const uint item = get_global_id(0);
  if (item >= items) return;
  const uint y = item % kh, fr = item / kh;
  __global const double4* A = planes + (size_t)fr * 8;
  const double n = A[3].w, f = A[7].w;
  const df_format fmt = DF_FORMAT_FROM_DEFINES();
  const double ndc_y = 2.0 * (oy + (double)y + 0.5) / vh - 1.0;
  const exact_row_t ra = exact_row(A, ndc_y, sx, sy);
  const size_t base = ((size_t)(first_frame + fr) * kh + y) * kw_pad;
  for (uint x0 = 0; x0 < kw; x0 += 8) {
    const double8 xs = (double8)((double)x0) + (double8)(0, 1, 2, 3, 4, 5, 6, 7);
    const double8 ndc_x = 2.0 * (ox + xs + 0.5) / vw - 1.0;
    long8 cov, fin, in;
    vstore8(plane8(ra, ndc_x, 1.0, 1.0, n, f, k, fmt, &cov, &fin, &in), 0, a_code + base + x0);
    const long8 bits = (cov & (long8)A_COVERED) | (fin & (long8)A_FINITE) | (in & (long8)A_INSIDE);
    vstore8(convert_uchar8(bits), 0, a_bits + base + x0);
  }
}
#endif

/* One work item per (probe, frame, kernel row), 8 pixels at a time: flags of the row's pixels
 * and the number of fragment pairs, as mts_raster reports them; MTS_R_BOUNDS where pixels of the
 * row were decided from end pixels. A_CACHED: a_frame gives each (probe, frame) its frame of
 * plane A's cache. */
__kernel void mts_exact(__global const double4* planes, const uint kw, const uint kh,
                        const double ox, const double oy, const double vw, const double vh,
                        const double sx, const double sy, const double k, const uint items,
                        __global uint* out
#if A_CACHED
                        ,
                        const uint kw_pad, __global const uint* a_frame,
                        __global const uint* a_code_all, __global const uchar* a_bits_all
#endif
) {
  const uint item = get_global_id(0);
  if (item >= items) return;
  const uint y = item % kh, pf = item / kh;
  __global const double4* A = planes + (size_t)pf * 8;
  __global const double4* B = A + 4;
  const double n = A[3].w, f = B[3].w; /* the mapping's near and far (plane A's layer) */
  const df_format fmt = DF_FORMAT_FROM_DEFINES();
  const double ndc_y = 2.0 * (oy + (double)y + 0.5) / vh - 1.0;
  const exact_row_t ra = exact_row(A, ndc_y, sx, sy), rb = exact_row(B, ndc_y, sx, sy);
#if A_CACHED
  const size_t a_row = ((size_t)a_frame[pf] * kh + y) * kw_pad;
  __global const uint* a_code = a_code_all + a_row;
  __global const uchar* a_bits = a_bits_all + a_row;
#else
  __global const uint* a_code = 0;
  __global const uchar* a_bits = 0;
#endif
  ulong pairs = 0;
  uint flags = 0;
#if ROW_ENDS
  /* The whole row first; where its ends leave room for stretches of 8 pixels (the codes' gap
   * beyond the margin and twice a stretch's share of the row's spread), stretches of 8. */
  const double last = (double)(kw - 1);
  const ends8_t row = row_ends8(ra, rb, kw, ox, vw, n, f, k, fmt);
  if (stretches_clean(row).s0) {
    out[item] = MTS_R_BOUNDS | ((uint)min(kw, 0xffffffu) << MTS_R_COUNT_SHIFT);
    return;
  }
#if CHORDS
  if (row.ok.s0 && row.ok.s1 && kw >= 2) {
    const chord_row_t ch = chord_row(rb, ox, vw, kw, n, f, k);
#if A_CACHED
    if (ch.usable && chord_codes(fmt)) {
#else
    const chord_row_t cha = chord_row(ra, ox, vw, kw, n, f, k);
    if (ch.usable && cha.usable) {
#endif
      /* knots every CHORD_SEGMENT pixels and at the last: four segments' ends at once */
      for (uint s0 = 0; s0 < kw; s0 += 4 * CHORD_SEGMENT) {
        double xk[8], d[8];
        chord_knots(rb, s0, kw, ox, vw, n, f, k, xk, d);
#if !A_CACHED
        double da[8];
        chord_knots(ra, s0, kw, ox, vw, n, f, k, xk, da);
#endif
        for (uint x0 = s0; x0 < kw && x0 < s0 + 4 * CHORD_SEGMENT; x0 += 8) {
          double margin;
          const uint j = (x0 - s0) / CHORD_SEGMENT;
          const double8 chord = chord8(ch, xk, d, j, x0, &margin);
#if A_CACHED
          if (chord_clean8(chord, margin, x0, kw, a_code, fmt)) {
#else
          double margin_a;
          const double8 chord_a = chord8(cha, xk, da, j, x0, &margin_a);
          if (chords_clean8(chord_a, margin_a, chord, margin, x0, kw, fmt)) {
#endif
            pairs += min(8u, kw - x0);
            flags |= MTS_R_CHORDS;
          } else {
            pixels8(ra, rb, x0, ox, vw, kw, n, f, k, fmt, a_code, a_bits, &pairs, &flags);
          }
        }
      }
      out[item] = flags | ((uint)min(pairs, (ulong)0xffffff) << MTS_R_COUNT_SHIFT);
      return;
    }
  }
#endif
  const long gap = min(row.ahead.s0 - row.behind.s0, row.ahead.s1 - row.behind.s1);
  const long spread = abs(row.ahead.s1 - row.ahead.s0) + abs(row.behind.s1 - row.behind.s0);
  if (row.ok.s0 && row.ok.s1 && gap >= ENDS_MARGIN + 2 * (spread * 8 / (long)kw + 1)) {
    for (uint x0 = 0; x0 < kw; x0 += 32) {
      const double8 xs =
          min((double8)((double)x0) + (double8)(0, 7, 8, 15, 16, 23, 24, 31), (double8)last);
      const long4 clean = stretches_clean(ends8(ra, rb, xs, ox, vw, n, f, k, fmt));
      const long c[4] = {clean.s0, clean.s1, clean.s2, clean.s3};
      for (uint j = 0; j < 4 && x0 + 8 * j < kw; ++j) {
        if (c[j]) {
          pairs += min(8u, kw - (x0 + 8 * j));
          flags |= MTS_R_BOUNDS;
        } else {
          pixels8(ra, rb, x0 + 8 * j, ox, vw, kw, n, f, k, fmt, a_code, a_bits, &pairs, &flags);
        }
      }
    }
    out[item] = flags | ((uint)min(pairs, (ulong)0xffffff) << MTS_R_COUNT_SHIFT);
    return;
  }
#endif
  for (uint x0 = 0; x0 < kw; x0 += 8)
    pixels8(ra, rb, x0, ox, vw, kw, n, f, k, fmt, a_code, a_bits, &pairs, &flags);
  out[item] = flags | ((uint)min(pairs, (ulong)0xffffff) << MTS_R_COUNT_SHIFT);
}
