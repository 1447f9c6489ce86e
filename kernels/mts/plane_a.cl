// The plane-A cache's row records.

// What row_from_reference found for the records a row meets, kept for the next rows of a
// work-item, which meet the same records while they stay in the same quad rows.
typedef struct {
  int first, end; /* the records (first > end: nothing kept yet) */
  int keeps;      /* b_keeps_a_edges */
  float moved;    /* b_moved_from_a */
} ref_records_t;

// Plane A projects to the same window triangles at every distance in exact arithmetic (it is
// scaled with its distance), so a row's coverage at one distance is, most of the time, its
// coverage at the first distance the cache filled (the reference, ref_*: every frame of it). The
// argument of coverage_margin shows when: plane A here keeps the reference's edges
// (b_keeps_a_edges), lies less than the reference row's margin from it (b_moved_from_a over the
// records the row meets) and owns each pixel of the row through one triangle (row_covered). The row
// then takes the reference's segments, and its margin for plane B is what is left of the
// reference's: a B within it of this plane lies within the reference's margin of the reference (the
// movements add), so B's coverage is the reference's too. Else the row is computed as at the
// reference. kept: the comparison of the records the work-item's previous row met.
static inline int row_from_reference(__global const float* T, uint vf, __global const float* R,
                                     __global const uint* ref_rec, int row, uint band_rows,
                                     float py, ref_records_t* kept, int* seg_x, int* seg_t,
                                     float* margin) {
  const int n = (int)ref_rec[MTS_RW_N];
  if (n == 0 || !row_covered(T, vf, row, band_rows)) return 0;
  int first, end;
  records_meeting(R, py, py, &first, &end);
  if (first != kept->first || end != kept->end) {
    kept->first = first;
    kept->end = end;
    kept->keeps = b_keeps_a_edges(R, T, first, end);
    kept->moved = kept->keeps ? b_moved_from_a(R, T, first, end) : INFINITY;
  }
  if (!kept->keeps) return 0;
  /* margin - moved, rounded down: the exact sum of this plane's movement and B's stays below the
   * reference's margin */
  const float left =
      (((__global const float*)ref_rec)[MTS_RW_MARGIN] - kept->moved) * (1.0f - 0x1.0p-20f);
  if (!(left > 0.0f)) return 0;
  *margin = left;
  return record_segments(ref_rec, seg_x, seg_t);
}

// Row records of cached plane A. Global id: plane * groups + group, planes from first_plane, a
// group the MTS_A_ROWS_PER_ITEM rows from group * MTS_A_ROWS_PER_ITEM (groups: kernel_h in
// groups); a plane's frame is its index among the per_probe planes of its distance, and the
// reference's planes and rows are indexed by frame (use_ref 0: this fill is the reference).
__kernel void mts_a_rows(MTS_A_ROWS_BUFFERS(MTS_ARG_IN, MTS_ARG_OUT) const MtsARowsArgs args) {
  const uint first_plane = args.first_plane, per_probe = args.per_probe, items = args.items;
  const uint use_ref = args.use_ref;
  const uint kernel_w = args.area.kernel_w, kernel_h = args.area.kernel_h;
  const uint band_rows = args.area.band_rows;
  const float origin_x = args.area.origin_x, origin_y = args.area.origin_y;
  const uint id = get_global_id(0);
  if (id >= items) return;
  const uint groups = MTS_A_ROW_GROUPS(kernel_h);
  const uint plane = first_plane + id / groups, r0 = id % groups * MTS_A_ROWS_PER_ITEM;
  __global const float* T = tris + (size_t)plane * PLANE_STRIDE;
  const uint frame = plane % per_probe;
  ref_records_t kept = {1, 0, 0, INFINITY};
  for (uint row = r0; row < min(kernel_h, r0 + MTS_A_ROWS_PER_ITEM); ++row) {
    __global uint* out = rows + ((size_t)plane * kernel_h + row) * MTS_ROW_WORDS;
    if (vflags[plane] & MTS_V_NONFINITE) {
      out[MTS_RW_N] = 0u;
      continue;
    }
    const float py = origin_y + (float)row + 0.5f;
    int seg_x[MAX_SEG + 1], seg_t[MAX_SEG];
    float margin = 0.0f;
    int n = 0;
    if (use_ref)
      n = row_from_reference(T, vflags[plane], ref_tris + (size_t)frame * PLANE_STRIDE,
                             ref_rows + ((size_t)frame * kernel_h + row) * MTS_ROW_WORDS, (int)row,
                             band_rows, py, &kept, seg_x, seg_t, &margin);
    const int from_ref = n > 0;
    if (!from_ref) {
      n = row_segments(T, py, origin_x, (int)kernel_w, seg_x, seg_t);
      if (n > MTS_MAXC) {
        out[MTS_RW_N] = 0u;
        continue;
      }
    }
#if CACHE_A_CODES
    __global const float* P = probes + (plane / per_probe) * MTS_PROBE_STRIDE;
    __global uint* c = codes + ((size_t)plane * kernel_h + row) * (kernel_w + MTS_CODE_ROW_PAD);
    /* a chunk's distance is probed once: mts_raster computes A's codes where it needs them */
    for (int k = 0; k < n && args.fill_codes; ++k) {
      if (seg_t[k] < 0) continue;
      const row_plane16_t rp = broadcast16(row_plane(T, seg_t[k], py));
      for (int i0 = seg_x[k]; i0 < seg_x[k + 1]; i0 += 16)
        vstore16(fragment16(rp, P, (origin_x + convert_float16(i0 + LANES)) + 0.5f).code, 0,
                 c + i0);
    }
#endif
    out[MTS_RW_N] = (uint)n;
    for (int k = 0; k <= n; ++k) out[MTS_RW_X + k] = (uint)seg_x[k];
    for (int k = 0; k < n; ++k) out[MTS_RW_T + k] = (uint)seg_t[k];
    /* A's own certification is not needed: only B's ownership enters the proof (coverage_margin) */
    ((__global float*)out)[MTS_RW_MARGIN] =
        from_ref ? margin : coverage_margin(T, py, origin_x, n, seg_x, seg_t);
  }
}
