// The kernels only the tests use: stored codes per pixel (mts_codes, compared with the host
// reference) and the audit of the coverage shortcut (mts_coverage_audit). A program of its own,
// built with a variant's defines only when a test asks for them (MtsEvaluator::codes,
// audit_coverage), so production variants carry none of it; they read the buffers the production
// program's kernels wrote. It holds the pipeline's parts but none of the production kernels.
#include "kernels/mts/pipeline.cl"

// Whether n segments found for a row differ from a cached row record's.
static inline int segments_differ(int n, const int* seg_x, const int* seg_t,
                                  __global const uint* rec) {
  int differs = n != (int)rec[MTS_RW_N];
  for (int k = 0; k < n && !differs; ++k)
    differs = seg_x[k] != (int)rec[MTS_RW_X + k] || seg_t[k] != (int)rec[MTS_RW_T + k];
  return differs;
}

// Audit of the coverage shortcut, for the tests: per (probe, frame, row) of a launch laid out as
// mts_raster's, bit 0: plane B's own coverage (row_segments) differs from plane A's cached one;
// bit 1: b_coverage_is_a says they are the same; bit 2: both (the shortcut would be wrong);
// bit 3: the row is cached; bit 4: plane A's own coverage differs from its cached record (wrong
// whenever it happens); bit 5: the record's margin is not A's own coverage_margin (the row took
// the reference's segments, mts_a_rows).
__kernel void mts_coverage_audit(
    __global const float* restrict tris, __global const uint* restrict vflags,
    __global const float* restrict a_tris, __global const uint* restrict a_vflags,
    __global const uint* restrict a_rows, __global const uint* restrict a_slots,
    const uint first_frame, const uint frames_total, const uint kernel_w, const uint kernel_h,
    const float origin_x, const float origin_y, const uint frames, const uint band_rows,
    __global uint* restrict out, const uint items) {
  const uint id = get_global_id(0);
  if (id >= items) return;
  const uint pf = id / kernel_h, row = id - pf * kernel_h;
  const uint ap = A_PLANE(pf);
  __global const float* TA = a_tris + (size_t)ap * PLANE_STRIDE;
  __global const float* TB = tris + (size_t)pf * PLANE_STRIDE;
  __global const uint* rec = a_rows + ((size_t)ap * kernel_h + row) * MTS_ROW_WORDS;
  out[id] = 0u;
  const int n = (int)rec[MTS_RW_N];
  if (n == 0 || ((a_vflags[ap] | vflags[pf]) & MTS_V_NONFINITE)) return;
  const float py = origin_y + (float)row + 0.5f;
  int seg_x[MAX_SEG + 1], seg_t[MAX_SEG];
  const int a_differs = segments_differ(row_segments(TA, py, origin_x, (int)kernel_w, seg_x, seg_t),
                                        seg_x, seg_t, rec);
  const int own_margin = !a_differs && coverage_margin(TA, py, origin_x, n, seg_x, seg_t) ==
                                           ((__global const float*)rec)[MTS_RW_MARGIN];
  const int differs = segments_differ(row_segments(TB, py, origin_x, (int)kernel_w, seg_x, seg_t),
                                      seg_x, seg_t, rec);
  /* as mts_frame_bounds finds them for the row's band */
  const uint r0 = row / band_rows * band_rows, r1 = min(kernel_h, r0 + band_rows);
  float moved;
  const uint oriented = band_b_against_a(TA, TB, origin_y, (int)r0, (int)r1, &moved);
  const int same = b_coverage_is_a(moved, oriented, TB, vflags[pf], (int)row, band_rows, rec);
  out[id] = 8u | (differs ? 1u : 0u) | (same ? 2u : 0u) | (differs && same ? 4u : 0u) |
            (a_differs ? 16u : 0u) | (own_margin ? 0u : 32u);
}

// Stored codes and fragment status of both planes at every kernel pixel of one (probe, frame),
// for the comparison with the host reference. Global id: row; out holds 4 uints per pixel:
// code A, code B, status A, status B.
__kernel void mts_codes(__global const float* restrict probes, __global const float* restrict tris,
                        const uint kernel_w, const float origin_x, const float origin_y,
                        __global uint* restrict out, const uint kernel_h) {
  const uint row = get_global_id(0);
  if (row >= kernel_h) return;
  __global const float* P = probes;
  __global const float* TA = tris;
  __global const float* TBp = tris + PLANE_STRIDE;
  const int W = (int)kernel_w;
  const float py = origin_y + (float)row + 0.5f;
  int seg_xa[MAX_SEG + 1], seg_ta[MAX_SEG], seg_xb[MAX_SEG + 1], seg_tb[MAX_SEG];
  row_segments(TA, py, origin_x, W, seg_xa, seg_ta);
  row_segments(TBp, py, origin_x, W, seg_xb, seg_tb);
  FOR_EACH_PIECE({
    const row_plane16_t ra = broadcast16(row_plane(TA, ta < 0 ? 0 : ta, py));
    const row_plane16_t rb = broadcast16(row_plane(TBp, tb < 0 ? 0 : tb, py));
    for (int i0 = x; i0 < x_end; i0 += 16) {
      const int16 idx = i0 + LANES;
      const float16 px = (origin_x + convert_float16(idx)) + 0.5f;
      const frag16_t fa = fragment16(ra, P, px), fb = fragment16(rb, P, px);
      uint ca[16], cb[16];
      int na[16], nb[16], la[16], lb[16];
      vstore16(fa.code, 0, ca);
      vstore16(fb.code, 0, cb);
      vstore16(fa.nonfinite, 0, na);
      vstore16(fb.nonfinite, 0, nb);
      vstore16(fa.clipped, 0, la);
      vstore16(fb.clipped, 0, lb);
      for (int k = 0; k < 16 && i0 + k < x_end; ++k) {
        const int sa = ta < 0  ? MTS_S_UNCOVERED
                       : na[k] ? MTS_S_NONFINITE
                       : la[k] ? MTS_S_CLIPPED
                               : MTS_S_OK;
        const int sb = tb < 0  ? MTS_S_UNCOVERED
                       : nb[k] ? MTS_S_NONFINITE
                       : lb[k] ? MTS_S_CLIPPED
                               : MTS_S_OK;
        __global uint* o = out + 4u * (row * kernel_w + (uint)(i0 + k));
        o[0] = sa == MTS_S_OK ? ca[k] : 0u;
        o[1] = sb == MTS_S_OK ? cb[k] : 0u;
        o[2] = (uint)sa;
        o[3] = (uint)sb;
      }
    }
  })
}
