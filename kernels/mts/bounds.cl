// Code bounds per band and the gap certificate: bands decided clean without rasterising.

// The smallest and largest stored code of one plane over the kernel pixels of rows [r0, r1) that
// any of its triangles may own (each triangle's bounding box, one pixel wider, clipped to the
// band), and whether any of them is clipped or non-finite. Depth is monotone in px along a row
// and, through the row term, in py (every rounding step is monotone), so its extremes over a box
// of pixel centres lie at the box's corners; the corners are evaluated with the very expressions
// of the per-pixel loop, 16 at a time (4 triangles x 4 corners).
typedef struct {
  ulong lo, hi;
  int bad;
} code_bounds_t;

// The kernel pixels (column i0..i1, row j0..j1) of rows [r0, r1) that triangle R may own
// (pixel_boxes16, stored by mts_setup). Empty when i0 > i1 or j0 > j1.
static inline int4 pixel_box(__global const float* R, int r0, int r1) {
  const int4 box = vload4(0, (__global const int*)R + MTS_T_BOX);
  return (int4)(box.s0, box.s1, max(box.s2, r0), min(box.s3, r1 - 1));
}

static inline code_bounds_t plane_code_bounds(__global const float* T, __global const float* P,
                                              float ox, float oy, int W, int r0, int r1) {
  code_bounds_t b;
  b.lo = 0xffffffffUL;
  b.hi = 0UL;
  b.bad = !PLANE_MONOTONE; /* extremes need not lie at the corners: no bounds */
  if (b.bad) return b;
  row_plane_lanes_t l;
  float px[16];
  int n = 0, first, end;
  records_boxed_in_rows(T, r0, r1, &first, &end);
  for (int t = first; t <= end; ++t) {
    if (t < end) {
      const int4 box = pixel_box(T + t * MTS_TRI_STRIDE, r0, r1);
      const int i0 = box.s0, i1 = box.s1, j0 = box.s2, j1 = box.s3;
      if (i0 > i1 || j0 > j1) continue;
      for (int q = 0; q < 4; ++q) {
        const float py = oy + (float)((q & 2) ? j1 : j0) + 0.5f;
        set_lane(&l, n, row_plane(T, t, py));
        px[n] = ox + (float)((q & 1) ? i1 : i0) + 0.5f;
        ++n;
      }
    }
    if (n == 16 || (t == end && n > 0)) {
      for (int k = n; k < 16; ++k) { /* pad with the first corner */
        l.c0[k] = l.c0[0];
        l.slope[k] = l.slope[0];
        l.x0[k] = l.x0[0];
        l.row_term[k] = l.row_term[0];
        l.dy[k] = l.dy[0];
        l.y[k] = l.y[0];
        l.up[k] = l.up[0];
        px[k] = px[0];
      }
      const frag16_t f = fragment16(load_lanes(&l), P, vload16(0, px));
      b.bad |= any16(f.nonfinite | f.clipped);
      /* halving reductions: 16 -> 8 -> 4 -> 2 -> 1 lanes */
      const uint8 lo8 = min(f.code.lo, f.code.hi), hi8 = max(f.code.lo, f.code.hi);
      const uint4 lo4 = min(lo8.lo, lo8.hi), hi4 = max(hi8.lo, hi8.hi);
      const uint2 lo2 = min(lo4.lo, lo4.hi), hi2 = max(hi4.lo, hi4.hi);
      b.lo = min(b.lo, (ulong)min(lo2.x, lo2.y));
      b.hi = max(b.hi, (ulong)max(hi2.x, hi2.y));
      n = 0;
    }
  }
  return b;
}

// The gap certificate: a band is clean when, at every pixel, plane B's stored code lies beyond
// plane A's, judged from the distance between the two planes rather than from their code ranges.
// Code bounds (above) compare B's smallest code over the band with A's largest, which fails
// whenever the band's own depth range exceeds the separation, as it does near the MTS at small
// distances where depth changes by many codes per pixel. B is A scaled about the eye, so in window
// space the two depth planes are nearly parallel and their distance hardly changes over the band.
// Each triangle's depth is d = fl(fl(c0 + fl(s fl(px - x0))) + fl(t fl(py - y0))) (row_plane,
// fragment16), which lies within E = 4.01 u (|c0| + |s (px - x0)| + |t (py - y0)|) + 2^-140 of the
// exact L = c0 + s (px - x0) + t (py - y0), u = 2^-24: each of the six roundings contributes at
// most u times its result, which the three terms bound; the 0.01 covers evaluating L and E in
// binary64, 2^-140 the absolute error of subnormal results; fused operations only remove roundings.
// llvmpipe's form (PLANE_FORM 1), fma(t, fl(py - y0), fma(s, fl(px - x0), c0)) with x0 = y0 = 1/2,
// rounds at most four times, so the same E bounds it.
// Measured against one reference plane R (the exact L of plane A's triangle 0): every pixel a
// triangle may own lies in its pixel_box, over which L - R is linear and E convex, so
// L - E - R is smallest and L + E - R largest at the box's corners. With lo/hi the smallest
// L - E - R and largest L + E - R over a plane's triangles in the band, d_B - d_A >= lo_B - hi_A at
// every pixel, whichever triangles own it. B's code exceeds A's (LEQUAL) when that is above
// GAP_STEP: for unorm, w / N when code(d) - d N lies in an interval of width w, since depths more
// than that apart then have codes in order (no saturation in an unclipped band): w = 1 for the
// exact conversion (round(d N) or floor(d N)); llvmpipe's (DF_CONVERT 1, df_encode_unorm_llvmpipe)
// are monotone too: unorm16 rint(fl(d (1 - 2^-16)) 2^16) within 1/2 + 2^16 u of d N, so w < 1 +
// 2^-7; unorm24 rint(fl(d (2^24 - 1))) within 3/4 (the product rounds by at most 1/4 below 2^23,
// where rint adds up to 1/2, and by 1/2 from 2^23 on, where it is an integer already), w = 3/2;
// unorm32 2 trunc(d 2^31) - d N in (-2, 1], w = 3; softpipe's (DF_CONVERT 2) truncate a product
// that rounds by at most half its ulp, r, so code - d N lies in (-1 - r, r]: unorm16 r <= 2^-9,
// w = 1 + 2^-8; unorm24 r <= 1/2, w = 2; unorm32 (binary64) r <= 2^-22, w < 1 + 2^-20. Any
// positive amount for float32 (codes are the bit patterns, monotone in d). GEQUAL mirrors it (hi_B
// below lo_A). Other formats, and fragment-stage depth (not an interpolated plane), are not
// certified this way.
//
// Fragment-stage depth (DEPTH_FROM 2) interpolates q = 1/w the same way, so lo/hi bound q against
// a reference plane R of q; d = h(q) is then a decreasing, convex function of q (frag_gap_clear),
// and only LEQUAL set-ups use it.
#if DF_KIND == 0
#if ADVERSARY_CODES /* A's code in [x - s, x - s + 1), B's in (x + s - 1, x + s], s the slack */
#define GAP_CODE_WIDTH (2.0 - 2.0 * ADVERSARY_CODE_SLACK)
#elif DF_CONVERT == 0
#define GAP_CODE_WIDTH 1.0
#elif DF_CONVERT == 1
#define GAP_CODE_WIDTH (DF_BITS == 16 ? 1.0078125 : DF_BITS == 24 ? 1.5 : 3.0)
#else
#define GAP_CODE_WIDTH (DF_BITS == 16 ? 1.00390625 : DF_BITS == 24 ? 2.0 : 1.000001)
#endif
#define GAP_STEP (GAP_CODE_WIDTH / (double)DF_FORMAT_FROM_DEFINES().max_code)
#elif DF_KIND == 1 && DF_E == 8 && DF_M == 23 && DF_IEEE && !DF_FLUSH
#define GAP_STEP 0.0
#endif
#if defined(GAP_STEP) && (DEPTH_FROM != 2 || !COMPARE_GREATER) && PLANE_MONOTONE && !FRAG_MEDIUMP
#define GAP_CERT 1
#else
#define GAP_CERT 0
#endif
#if DEPTH_FROM == 2 /* the interpolated plane: q = 1/w_clip, or depth itself */
#define G_C0 MTS_T_Q0
#define G_DX MTS_T_DQDX
#define G_DY MTS_T_DQDY
#else
#define G_C0 MTS_T_D0
#define G_DX MTS_T_DZDX
#define G_DY MTS_T_DZDY
#endif

#if GAP_CERT
#pragma OPENCL EXTENSION cl_khr_fp64 : enable
// The reference plane's exact value R at (px, py), binary64 scalars or vectors alike.
#define REF_PLANE_AT(ref, px, py)                                                   \
  (((double)(ref)[G_C0] + (double)(ref)[G_DX] * ((px) - (double)(ref)[MTS_T_X0])) + \
   (double)(ref)[G_DY] * ((py) - (double)(ref)[MTS_T_Y0]))

// L - R, and E, of 16 corners: triangle planes in lanes (c0, s, x0, t, y0 of each) against the
// reference plane ref (same fields).
static inline void plane_minus_ref16(const float* f, __global const float* ref, double16 px,
                                     double16 py, double16* l, double16* e) {
  const double16 sx =
      convert_double16(vload16(0, f + 16)) * (px - convert_double16(vload16(0, f + 32)));
  const double16 ty =
      convert_double16(vload16(0, f + 48)) * (py - convert_double16(vload16(0, f + 64)));
  const double16 c0 = convert_double16(vload16(0, f));
  *l = ((c0 + sx) + ty) - REF_PLANE_AT(ref, px, py);
  *e = (4.01 * 0x1.0p-24) * ((fabs(c0) + fabs(sx)) + fabs(ty)) + 0x1.0p-140;
}

// lo (smallest L - E - R) and hi (largest L + E - R) of plane T over rows [r0, r1); NaN when any
// corner is not finite.
static inline double2 plane_gap_range(__global const float* T, __global const float* ref, float ox,
                                      float oy, int W, int r0, int r1) {
  double lo = INFINITY, hi = -INFINITY;
  int bad = 0;
  float f[80], px[16], py[16];
  int n = 0, first, end;
  records_boxed_in_rows(T, r0, r1, &first, &end);
  for (int t = first; t <= end; ++t) {
    if (t < end) {
      __global const float* R = T + t * MTS_TRI_STRIDE;
      const int4 box = pixel_box(R, r0, r1);
      if (box.s0 > box.s1 || box.s2 > box.s3) continue;
      for (int q = 0; q < 4; ++q) {
        f[n] = R[G_C0];
        f[16 + n] = R[G_DX];
        f[32 + n] = R[MTS_T_X0];
        f[48 + n] = R[G_DY];
        f[64 + n] = R[MTS_T_Y0];
        px[n] = ox + (float)((q & 1) ? box.s1 : box.s0) + 0.5f;
        py[n] = oy + (float)((q & 2) ? box.s3 : box.s2) + 0.5f;
        ++n;
      }
    }
    if (n == 16 || (t == end && n > 0)) {
      for (int k = n; k < 16; ++k) { /* pad with the first corner */
        for (int j = 0; j < 80; j += 16) f[j + k] = f[j];
        px[k] = px[0];
        py[k] = py[0];
      }
      double16 l, e;
      plane_minus_ref16(f, ref, convert_double16(vload16(0, px)), convert_double16(vload16(0, py)),
                        &l, &e);
      bad |= !all(isfinite(l) && isfinite(e));
      const double16 a = l - e, b = l + e;
      const double8 a8 = fmin(a.lo, a.hi), b8 = fmax(b.lo, b.hi);
      const double4 a4 = fmin(a8.lo, a8.hi), b4 = fmax(b8.lo, b8.hi);
      const double2 a2 = fmin(a4.lo, a4.hi), b2 = fmax(b4.lo, b4.hi);
      lo = fmin(lo, fmin(a2.x, a2.y));
      hi = fmax(hi, fmax(b2.x, b2.y));
      n = 0;
    }
  }
  return bad ? (double2)(NAN, NAN) : (double2)(lo, hi);
}

#if DEPTH_FROM == 2
// The exact depth h(q) of fragment-stage depth, and the most the binary32 computation of d from a
// computed q can differ from it where h(q) <= h_max and w = 1/q <= w_max: w = fl(1/q) is within u
// relative (correctly rounded division), then
//   linear   d = fl(fl(w - n) / range): 2.001 u h + 1.001 u w / range
//   w_buffer d = fl(w / far):           2.001 u h
//   log      d = fl(log(fl(fl(k w) + 1)) / L): x = k w + 1 within 3.0001 u of ln x after the log,
//            the log itself within 3 ulp (the bound LOG_CODE_SLACK assumes), so 7.02 u h + 3.001 u
//            / L; llvmpipe's log (LLVMPIPE_LOG) is within 3.84 ulp over every binary32 x >= 1
//            (bench/llvmpipe_log_error, every one), so 8.7 u h + 3.001 u / L
//   three.js d = fl(fl(log2(fl(1 + w))) FC) / 2: x = 1 + w within 2.0001 u of ln x, the log2
//            within 3 ulp and the product one rounding, so 7.02 u h + 2.0001 u (FC / 2) / ln 2;
//            llvmpipe's log2 is within 3.60 ulp over every binary32 x >= 1 (the same bench, every
//            one), so 8.22 u h in its place
//   Cesium   d = fl(log2(fl(fl(w - n) + 1)) C): x = (w - n) + 1 carries w's rounding, u w, and two
//            more, u |w - n| + u x; unclipped, x > 1 - 2^-23, so within (1.0001 max(1, n) + 2.0001)
//            u of ln x (w / x <= max(1, n) for w >= n - 2^-23), then the log2 and the product as
//            three.js's
static inline double frag_h(__global const float* P, double q) {
#if FRAG_DEPTH == 1
  return (1.0 / q - (double)P[MTS_C_NEAR]) / (double)P[MTS_C_RANGE];
#elif FRAG_DEPTH == 2
  return 1.0 / (q * (double)P[MTS_C_FAR]);
#elif FRAG_DEPTH == 4
  return log2(1.0 / q + 1.0) * (0.5 * (double)P[MTS_C_THREEJS_FC]);
#elif FRAG_DEPTH == 5
  return log2((1.0 / q - (double)P[MTS_C_NEAR]) + 1.0) * (double)P[MTS_C_CESIUM_INV_LOG2];
#else
  return log((double)P[MTS_C_LOGK] / q + 1.0) / (double)P[MTS_C_LOGL];
#endif
}

static inline double frag_err(__global const float* P, double h_max, double w_max) {
  const double u = 0x1.0p-24;
#if FRAG_DEPTH == 1
  return 2.001 * u * h_max + 1.001 * u * w_max / (double)P[MTS_C_RANGE];
#elif FRAG_DEPTH == 2
  return 2.001 * u * h_max;
#elif FRAG_DEPTH == 4
  return (LLVMPIPE_LOG ? 8.22 : 7.02) * u * h_max +
         2.0001 * u * (0.5 * (double)P[MTS_C_THREEJS_FC]) / M_LN2;
#elif FRAG_DEPTH == 5
  const double ln_x_err = (1.0001 * fmax(1.0, (double)P[MTS_C_NEAR]) + 2.0001) * u;
  return (LLVMPIPE_LOG ? 8.22 : 7.02) * u * h_max +
         ln_x_err * (double)P[MTS_C_CESIUM_INV_LOG2] / M_LN2;
#else
  return (LLVMPIPE_LOG ? 8.7 : 7.02) * u * h_max + 3.001 * u / (double)P[MTS_C_LOGL];
#endif
}

// LEQUAL: whether B's code exceeds A's at every pixel of rows [r0, r1), given a = (lo, hi) of A's
// q and b = (lo, hi) of B's q against the reference plane ref (plane_gap_range). At a pixel with
// R = r: q_A >= r + lo_A, q_B <= r + hi_B, so (h decreasing) d_B - d_A >= h(r + hi_B) - h(r + lo_A)
// - 2 err, and for hi_B < lo_A that difference of a convex h falls with r: its least is at the
// band's largest R. Clamping d to [0, 1] keeps B's code above A's while A's d stays below 1 - step.
static inline int frag_gap_clear(__global const float* P, __global const float* ref, double2 a,
                                 double2 b, float ox, float oy, int W, int r0, int r1) {
  double r_min = INFINITY, r_max = -INFINITY;
  for (int q = 0; q < 4; ++q) {
    const double px = (double)(ox + (float)((q & 1) ? W - 1 : 0) + 0.5f);
    const double py = (double)(oy + (float)((q & 2) ? r1 - 1 : r0) + 0.5f);
    const double r = REF_PLANE_AT(ref, px, py);
    r_min = fmin(r_min, r);
    r_max = fmax(r_max, r);
  }
  const double q_min = r_min + fmin(a.x, b.x);
  if (!(q_min > 0.0) || !(b.y < a.x) || !isfinite(r_max)) return 0;
  const double err = frag_err(P, frag_h(P, q_min), 1.0 / q_min) + 1e-12;
  return frag_h(P, r_max + b.y) - frag_h(P, r_max + a.x) - 2.0 * err > GAP_STEP &&
         1.0 - (frag_h(P, r_min + a.x) + err) > GAP_STEP;
}
#endif
#endif

// Per band of cached plane A: its code bounds lo, hi, bad, and the range of its gap certificate
// (plane_gap_range against its own triangle 0; NaN where not computed). Global id:
// plane * bands + band, planes from first_plane; the probe constants of plane p are those of p /
// per_probe.
__kernel void mts_a_bands(MTS_A_BANDS_BUFFERS(MTS_ARG_IN, MTS_ARG_OUT) const MtsABandsArgs args) {
  const uint first_plane = args.first_plane, per_probe = args.per_probe, items = args.items;
  const uint kernel_w = args.area.kernel_w, kernel_h = args.area.kernel_h;
  const uint bands = args.area.bands, band_rows = args.area.band_rows;
  const float origin_x = args.area.origin_x, origin_y = args.area.origin_y;
  const uint id = get_global_id(0);
  if (id >= items) return;
  const uint plane = first_plane + id / bands, band = id % bands;
  __global uint* o = out + ((size_t)plane * bands + band) * MTS_BAND_WORDS;
  o[2] = 1u;
  ((__global float*)o)[MTS_BW_GAP_LO] = NAN;
  ((__global float*)o)[MTS_BW_GAP_HI] = NAN;
  if (!band_covered(vflags[plane], band)) return;
  const int r0 = (int)(band * band_rows), r1 = min((int)kernel_h, r0 + (int)band_rows);
  __global const float* T = tris + (size_t)plane * PLANE_STRIDE;
  const code_bounds_t a = plane_code_bounds(T, probes + (plane / per_probe) * MTS_PROBE_STRIDE,
                                            origin_x, origin_y, (int)kernel_w, r0, r1);
  o[0] = (uint)a.lo;
  o[1] = (uint)a.hi;
  o[2] = (uint)a.bad;
#if GAP_CERT
  /* rounded outwards: the band's gap range is only ever widened */
  const double2 g = plane_gap_range(T, T, origin_x, origin_y, (int)kernel_w, r0, r1);
  ((__global float*)o)[MTS_BW_GAP_LO] = convert_float_rtn(g.x);
  ((__global float*)o)[MTS_BW_GAP_HI] = convert_float_rtp(g.y);
#endif
}

// The verdict of one band of a (probe, frame), for its rows but those band_bad_rows names:
// MTS_D_CLEAN when both planes certainly own every pixel of those rows (band_covered) and their
// code bounds over it exclude a fight: LEQUAL: B's smallest code above A's largest (log depth: by
// LOG_CODE_SLACK more, as for pieces), or, where that fails, the gap certificate (plane_gap_range,
// frag_gap_clear). Otherwise MTS_D_RASTER, or MTS_D_INSIDE / MTS_D_ORDERED where the bounds show
// both planes finite and unclipped over the band.
static inline uint band_verdict(__global const float* P, __global const float* TB,
                                __global const float* ref, uint vflags_b, uint vflags_a,
                                __global const uint* a, float origin_x, float origin_y,
                                uint kernel_w, int r0, int r1, uint band) {
  if (!band_covered(vflags_a, band) || !band_covered(vflags_b, band) || a[2]) return MTS_D_RASTER;
  const code_bounds_t b = plane_code_bounds(TB, P, origin_x, origin_y, (int)kernel_w, r0, r1);
  if (b.bad) return MTS_D_RASTER;
#if COMPARE_GREATER
  uint clean = b.hi + LOG_SLACK_OR_0 < (ulong)a[0];
#else
  uint clean = b.lo > (ulong)a[1] + LOG_SLACK_OR_0;
#endif
#if GAP_CERT
  if (!clean) {
    const double2 g = plane_gap_range(TB, ref, origin_x, origin_y, (int)kernel_w, r0, r1);
    __global const float* ga = (__global const float*)a;
#if DEPTH_FROM == 2
    clean = frag_gap_clear(P, ref, (double2)(ga[MTS_BW_GAP_LO], ga[MTS_BW_GAP_HI]), g, origin_x,
                           origin_y, (int)kernel_w, r0, r1);
#elif COMPARE_GREATER
    clean = (double)ga[MTS_BW_GAP_LO] - g.y > GAP_STEP;
#else
    clean = g.x - (double)ga[MTS_BW_GAP_HI] > GAP_STEP;
#endif
  }
#endif
  /* Not clean, but both planes are finite and unclipped at every pixel of the band (their bounds
   * are not bad), so the status of every piece's ends is known. What the end-code pass could still
   * do is exclude a piece whose B codes all clear A's, which near the MTS, where rows are
   * rasterised, rarely happens: mts_raster goes straight to the pixel loop. Both paths give the
   * same row verdict and count; only the work differs. If A's lowest code is at or above code(T)
   * (T = df_order_exact_from), every depth of A is at or above T, and the pixel loop can compare
   * depths instead of codes. */
  const uint from = df_order_exact_from(DF_FORMAT_FROM_DEFINES());
  /* an adversary's codes do not compare as the depths do */
  const int ordered = !ADVERSARY_CODES && from <= 0x3f800000u &&
                      a[0] >= df_encode(as_float(from), DF_FORMAT_FROM_DEFINES());
  return clean ? MTS_D_CLEAN : ordered ? MTS_D_ORDERED : MTS_D_INSIDE;
}

// Decides bands of kernel rows of a (probe, frame) clean without rasterising them (band_verdict).
// Most probes of a search's descent from s = z are decided here. A band that is not decided goes
// through mts_raster row by row, so the answer never depends on this pass, only the work does;
// for it, whether B's edges are A's and how far they moved (b_coverage_is_a).
// Global id: (probe * frames + frame) * bands + band.
__kernel void mts_frame_bounds(MTS_FRAME_BOUNDS_BUFFERS(MTS_ARG_IN, MTS_ARG_OUT)
                                   const MtsFrameBoundsArgs args) {
  const uint first_frame = args.first_frame, frames_total = args.frames_total;
  const uint frames = args.frames, items = args.items;
  const uint kernel_w = args.area.kernel_w, kernel_h = args.area.kernel_h;
  const uint bands = args.area.bands, band_rows = args.area.band_rows;
  const float origin_x = args.area.origin_x, origin_y = args.area.origin_y;
  const uint id = get_global_id(0);
  if (id >= items) return;
  const uint pf = id / bands, band = id - pf * bands;
  const uint ap = A_PLANE(pf);
  __global const float* P = probes + (pf / frames) * MTS_PROBE_STRIDE;
  __global uint* out = decided + (size_t)id * MTS_DECIDED_WORDS;
  __global const float* TB = tris + (size_t)pf * PLANE_STRIDE;
  __global const float* ref = a_tris + (size_t)ap * PLANE_STRIDE;
  const int r0 = (int)(band * band_rows), r1 = min((int)kernel_h, r0 + (int)band_rows);
  const uint verdict = band_verdict(P, TB, ref, vflags[pf], a_vflags[ap],
                                    a_bands + ((size_t)ap * bands + band) * MTS_BAND_WORDS,
                                    origin_x, origin_y, kernel_w, r0, r1, band);
  float moved = INFINITY;
  uint oriented = 0u;
  if (verdict != MTS_D_CLEAN && !((a_vflags[ap] | vflags[pf]) & MTS_V_NONFINITE))
    oriented = band_b_against_a(ref, TB, origin_y, r0, r1, &moved);
  ((__global float*)out)[MTS_DW_MOVED] = moved;
  out[MTS_DW_VERDICT] = verdict | oriented;
  out[MTS_DW_BAD_ROWS] = band_bad_rows(TB, r0, r1) | band_bad_rows(ref, r0, r1);
}
