// The scene audit's per-pixel pass (docs/audit.md): every triangle of a tile's bin, in draw order,
// through the emulated pipeline's coverage, depth and storage (the MTS variant's program parts,
// built with its defines), the depth test against the stored code, and beside it the exact front
// surface: the nearest covering surface by its binary64 eye depth along the pixel's ray.
// The host reference (host/audit/audit_reference.cpp) computes the same per pixel in C++.
#pragma OPENCL EXTENSION cl_khr_fp64 : enable

#include "interface/audit_layout.h"
#include "kernels/mts/pipeline.cl" /* the defines checked; formats, layout, fragments */

// Coverage of 16 pixel centres by record R: every edge test passes, ties to the owning edge
// (host/mts/triangle_setup.cpp covers).
static inline int16 covers16(__global const float* R, float16 px, float py) {
  const uint bits = as_uint(R[MTS_T_BITS]);
  int16 in = (int16)-1;
  for (int e = 0; e < 3; ++e) {
    const float ax = R[MTS_T_EDGES + 4 * e], ay = R[MTS_T_EDGES + 4 * e + 1];
    const float dx = R[MTS_T_EDGES + 4 * e + 2], dy = R[MTS_T_EDGES + 4 * e + 3];
    float16 E = MTS_EDGE_FUNCTION(ax, ay, dx, dy, px, py);
    if (bits & MTS_BIT_NEGATE(e)) E = -E;
    const int16 owns = (int16)((bits & MTS_BIT_OWNS(e)) ? -1 : 0);
    in &= MTS_EDGE_PASSES(E, owns);
  }
  return in;
}

static inline int16 closer16(uint16 a, uint16 b) { /* a passes the depth test against b */
#if COMPARE_GREATER
  return a > b;
#else
  return a < b;
#endif
}

static inline long16 test_margin16(uint16 behind, uint16 front) { /* > 0: front wins by that */
#if COMPARE_GREATER
  return convert_long16(front) - convert_long16(behind);
#else
  return convert_long16(behind) - convert_long16(front);
#endif
}

/* the conversion's freedom in codes (AUDIT_CONVERSION_CODES) */
#if DF_KIND == 0
#define AUDIT_W AUDIT_CONVERSION_CODES(1, DF_BITS, 0)
#else
#define AUDIT_W AUDIT_CONVERSION_CODES(0, 0, (DF_E == 8 && DF_M == 23 && DF_IEEE && !DF_FLUSH))
#endif

/* The depths [lo, hi] a conformant implementation may store for these fragments: the record's
 * tolerance plane at the pixels around the interpolated value v, through the fragment shader's
 * depth where it computes one (h is monotone in q: its ends are the interval's), widened by the
 * shader's own error. Rounded outwards by 2^-20 of the tolerance; a value the sum cannot
 * represent apart from v stays v, which is then the only binary32 within the tolerance. */
static inline void tolerance16(__global const float* TL, __global const float* R, float16 v,
                               float16 d, __global const float* P, float16 px, float py,
                               float16* lo, float16* hi) {
  const float16 plane = TL[AUDIT_TOL_E0] + TL[AUDIT_TOL_EX] * (px - R[MTS_T_X0]) +
                        TL[AUDIT_TOL_EY] * (py - R[MTS_T_Y0]);
  const float16 tv = (TL[AUDIT_TOL_C] + fmax(plane, 0.0f)) * (1.0f + 0x1.0p-20f);
#if DEPTH_FROM == 2
  const float16 d1 = depth_of_value16(v - tv, P).d, d2 = depth_of_value16(v + tv, P).d;
  const float shader = TL[AUDIT_TOL_SHADER] * (1.0f + 0x1.0p-20f);
  *lo = fmin(d1, d2) - shader;
  *hi = fmax(d1, d2) + shader;
#else
  *lo = d - tv;
  *hi = d + tv;
#endif
}

__kernel void audit_pixels(AUDIT_PIXELS_BUFFERS(MTS_ARG_IN, MTS_ARG_OUT) AuditPixelsArgs args) {
  const uint id = get_global_id(0);
  const uint tile = id / AUDIT_TILE, row = id % AUDIT_TILE;
  if (tile >= args.tiles_x * args.tiles_y) return;
  const uint x0 = (tile % args.tiles_x) * AUDIT_TILE, y = (tile / args.tiles_x) * AUDIT_TILE + row;
  if (y >= args.height) return;
  const float py = (float)y + 0.5f;
  const float16 px = (float)x0 + convert_float16(LANES) + 0.5f;
  const double hw = ray[0], hh = ray[1], sx = ray[2], sy = ray[3];
  const double16 ray_x = (convert_double16(px) / hw - 1.0) / sx;
  const double ray_y = ((double)py / hh - 1.0) / sy;
  uint16 stored = (uint16)args.clear_code, front_code = (uint16)0u, second_code = (uint16)0u;
  int16 win = (int16)-1, frnt = (int16)-1, coplanar = (int16)0, discarded = (int16)0;
  double16 winner_s = (double16)INFINITY, front_s = (double16)INFINITY;
  double16 second_s = (double16)INFINITY;
  float16 front_lo = 0.0f, front_hi = 0.0f, second_lo = 0.0f, second_hi = 0.0f;
  for (uint k = bins[tile]; k < bins[tile + 1]; ++k) {
    const uint r = bin_records[k];
    __global const float* R = records + (size_t)r * MTS_TRI_STRIDE;
    if (!(as_uint(R[MTS_T_BITS]) & MTS_BIT_VALID) || py < R[MTS_T_YMIN] || py > R[MTS_T_YMAX])
      continue;
    const int16 in = covers16(R, px, py);
    if (!any16(in)) continue;
    /* fragment16's code, with the interpolated value kept for the tolerance */
    const float16 v = plane_at16(broadcast16(row_plane(records, (int)r, py)), px);
    const depth16_t z = depth_of_value16(v, probe);
    frag16_t f;
    f.code = df_encode16(z.d, DF_FORMAT_FROM_DEFINES());
    f.nonfinite = z.nonfinite;
    f.clipped = z.clipped;
    const int16 ok = in & ~(f.nonfinite | f.clipped);
    discarded |= in & (f.nonfinite | f.clipped);
    if (!any16(ok)) continue;
    float16 lo, hi;
    tolerance16(tolerance + (size_t)r * AUDIT_TOL_WORDS, R, v, z.d, probe, px, py, &lo, &hi);
    const uint src = source[r];
    __global const double* pl = planes + (size_t)src * AUDIT_PLANE_WORDS;
    const double16 s = pl[3] / ((pl[0] * ray_x + pl[1] * ray_y) - pl[2]);
    /* the depth test, in draw order */
    const int16 pass = ok & closer16(f.code, stored);
    stored = select(stored, f.code, pass);
    win = select(win, (int16)src, pass);
    winner_s = select(winner_s, s, convert_long16(pass));
    /* the exact front surface, and the nearest distinct surface behind it */
    const long16 ok_l = convert_long16(ok);
    /* double comparisons give long masks */
    const long16 same = ok_l & (fabs(s - front_s) <= AUDIT_COPLANAR_RELATIVE * fmin(s, front_s));
    const long16 nearer = ok_l & ~same & (s < front_s);
    const long16 behind = ok_l & ~same & ~nearer & (s < second_s);
    /* coplanar with the front surface; a nearer surface hides the pair, so it starts afresh */
    coplanar = (coplanar | convert_int16(same)) & ~convert_int16(nearer);
    second_s = select(select(second_s, front_s, nearer), s, behind);
    second_code = select(select(second_code, front_code, convert_int16(nearer)), f.code,
                         convert_int16(behind));
    second_lo =
        select(select(second_lo, front_lo, convert_int16(nearer)), lo, convert_int16(behind));
    second_hi =
        select(select(second_hi, front_hi, convert_int16(nearer)), hi, convert_int16(behind));
    /* in one plane the front is the surface drawn last: where the depth test kept an earlier
     * one, that one is the coplanar pair's kept surface, the last-drawn the lost one */
    const long16 take = nearer | same;
    front_s = select(front_s, s, take);
    frnt = select(frnt, (int16)src, convert_int16(take));
    front_code = select(front_code, f.code, convert_int16(take));
    front_lo = select(front_lo, lo, convert_int16(take));
    front_hi = select(front_hi, hi, convert_int16(take));
  }
  const int16 covered = frnt >= 0;
  const int16 lost = covered & (win != frnt);
  const int16 tie =
      convert_int16(fabs(winner_s - front_s) <= AUDIT_COPLANAR_RELATIVE * fmin(winner_s, front_s));
  const int16 undrawn = covered & (win < 0);
  const int16 fight = lost & ~tie & ~undrawn;
  /* margin: how far the front surface's code is ahead of the next one's; where it lost, how far
   * the winner's is ahead of it (negative) */
  long16 m = test_margin16(second_code, front_code);
  m = select(m, -test_margin16(front_code, stored), convert_long16(lost));
  m = clamp(m, (long16)INT_MIN, (long16)INT_MAX);
  const int16 no_margin = covered & ~lost & convert_int16(isinf(second_s));
  m = select(m, (long16)INT_MAX, convert_long16(no_margin | ~covered));
  /* at risk: the front surface wins, but with both depths moved towards each other within their
   * tolerances it leads by at most the conversion's freedom */
#if COMPARE_GREATER
  const float16 front_edge = front_lo, second_edge = second_hi;
#else
  const float16 front_edge = front_hi, second_edge = second_lo;
#endif
  const uint16 front_worst = df_encode16(clamp(front_edge, 0.0f, 1.0f), DF_FORMAT_FROM_DEFINES());
  const uint16 second_worst = df_encode16(clamp(second_edge, 0.0f, 1.0f), DF_FORMAT_FROM_DEFINES());
  const int16 at_risk = covered & ~lost & ~no_margin & ~coplanar &
                        convert_int16(test_margin16(second_worst, front_worst) <= (long16)AUDIT_W);
  const uint16 fl = select((uint16)0u, (uint16)AUDIT_COVERED, covered) |
                    select((uint16)0u, (uint16)AUDIT_FIGHT, fight) |
                    select((uint16)0u, (uint16)AUDIT_COPLANAR, coplanar | (lost & tie)) |
                    select((uint16)0u, (uint16)AUDIT_DISCARDED, discarded) |
                    select((uint16)0u, (uint16)AUDIT_NO_MARGIN, no_margin) |
                    select((uint16)0u, (uint16)AUDIT_UNDRAWN, undrawn) |
                    select((uint16)0u, (uint16)AUDIT_AT_RISK, at_risk);
  uint w[16], fr[16], flg[16];
  int mg[16];
  vstore16(as_uint16(win), 0, w);
  vstore16(as_uint16(frnt), 0, fr);
  vstore16(fl, 0, flg);
  vstore16(convert_int16(m), 0, mg);
  const size_t base = (size_t)y * args.width + x0;
  for (int k = 0; k < 16 && x0 + (uint)k < args.width; ++k) {
    winner[base + k] = w[k];
    front[base + k] = fr[k];
    margin[base + k] = mg[k];
    flags[base + k] = flg[k];
  }
}
