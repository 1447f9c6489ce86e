/* The storage-limited pipeline of MTS attribution (docs/stability.md): the same probes as
 * kernels/mts.cl, but every step before storage exact up to binary64 -- the depth of each plane
 * at each kernel pixel centre from the ray through it (no vertex rounding, no binary32
 * arithmetic, no interpolation error), the technique's exact mapping D(w), then the storage
 * format's correctly rounded code (df_encode_f64). What is left is the error of storage alone.
 *
 * Defines: DEPTH_MAP (0 standard, 1 infinite, 2 reversed, 3 n/w, 4 log, 5 linear, 6 w/f),
 * CLIP_W (1: the technique writes depth in the fragment stage -- clip by the standard volume
 * n <= w <= f and clamp d; 0: clip where d leaves [0, 1]), COMPARE_GREATER, and the format's. */
#pragma OPENCL EXTENSION cl_khr_fp64 : enable
#define DF_ENABLE_FP64 1
#include "formats/depth_format.h"

#define EXACT_FIGHT 1u
#define EXACT_CLIPPED 2u
#define EXACT_NON_FINITE 4u
#define EXACT_UNCOVERED 8u
#define EXACT_COUNT_SHIFT 8

static double exact_depth(double w, double n, double f, double k) {
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
#else
  return w / f;
#endif
}

/* A plane is four double4 columns of its binary64 model matrix: the scaled in-plane axes a and
 * b, the normal, and the centre. Returns its eye distance along ray dir (w = t, dir.z = -1);
 * covered tells whether the ray meets the plane's square. (centre.w carries near or far.) */
static double plane_w(__global const double4* pl, double3 dir, int* covered) {
  const double3 a = pl[0].xyz, b = pl[1].xyz, nrm = pl[2].xyz, c = pl[3].xyz;
  const double t = dot(nrm, c) / dot(nrm, dir);
  const double3 q = t * dir - c;
  const double u = dot(q, a) / dot(a, a), v = dot(q, b) / dot(b, b);
  *covered = t > 0.0 && fabs(u) <= 0.5 && fabs(v) <= 0.5;
  return t;
}

/* One work item per (probe, frame, kernel row): flags of the row's pixels and the number of
 * fragment pairs, as mts_raster reports them. */
__kernel void mts_exact(__global const double4* planes, const uint kw, const uint kh, const double ox,
                        const double oy, const double vw, const double vh, const double sx, const double sy,
                        const double k, __global uint* out, const uint items) {
  const uint item = get_global_id(0);
  if (item >= items) return;
  const uint y = item % kh, pf = item / kh;
  __global const double4* A = planes + (size_t)pf * 8;
  __global const double4* B = A + 4;
  const double n = A[3].w, f = B[3].w; /* the mapping's near and far (plane A's layer) */
  const df_format fmt = DF_FORMAT_FROM_DEFINES();
  const double ndc_y = 2.0 * (oy + (double)y + 0.5) / vh - 1.0;
  uint flags = 0, pairs = 0;
  for (uint x = 0; x < kw; ++x) {
    const double ndc_x = 2.0 * (ox + (double)x + 0.5) / vw - 1.0;
    const double3 dir = (double3)(ndc_x * sx, ndc_y * sy, -1.0);
    int cov_a = 0, cov_b = 0;
    const double wa = plane_w(A, dir, &cov_a), wb = plane_w(B, dir, &cov_b);
    if (!cov_a || !cov_b) {
      flags |= EXACT_UNCOVERED;
      continue;
    }
    double da = exact_depth(wa, n, f, k), db = exact_depth(wb, n, f, k);
    if (!isfinite(da) || !isfinite(db)) {
      flags |= EXACT_NON_FINITE;
      continue;
    }
#if CLIP_W
    if (!(wa >= n && wa <= f && wb >= n && wb <= f)) {
      flags |= EXACT_CLIPPED;
      continue;
    }
    da = clamp(da, 0.0, 1.0);
    db = clamp(db, 0.0, 1.0);
#else
    if (!(da >= 0.0 && da <= 1.0 && db >= 0.0 && db <= 1.0)) {
      flags |= EXACT_CLIPPED;
      continue;
    }
#endif
    ++pairs;
    const uint ca = df_encode_f64(da, fmt), cb = df_encode_f64(db, fmt);
#if COMPARE_GREATER
    if (cb >= ca) flags |= EXACT_FIGHT;
#else
    if (cb <= ca) flags |= EXACT_FIGHT;
#endif
  }
  out[item] = flags | (min(pairs, 0xffffffu) << EXACT_COUNT_SHIFT);
}
