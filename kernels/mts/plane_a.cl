// The plane-A cache's row records.

// Row records of cached plane A. Global id: plane * kernel_h + row, planes from first_plane.
__kernel void mts_a_rows(__global const float* restrict probes, __global const float* restrict tris,
                         __global const uint* restrict vflags, const uint first_plane,
                         const uint per_probe, const uint kernel_w, const uint kernel_h,
                         const float origin_x, const float origin_y, __global uint* restrict rows,
                         __global uint* restrict codes, const uint items) {
  const uint id = get_global_id(0);
  if (id >= items) return;
  const uint plane = first_plane + id / kernel_h, row = id % kernel_h;
  __global const float* T = tris + (size_t)plane * PLANE_STRIDE;
  __global uint* out = rows + ((size_t)plane * kernel_h + row) * ROW_WORDS;
  if (vflags[plane] & V_NONFINITE) {
    out[RW_N] = 0u;
    return;
  }
  const float py = origin_y + (float)row + 0.5f;
  int seg_x[MAX_SEG + 1], seg_t[MAX_SEG];
  const int n = row_segments(T, py, origin_x, (int)kernel_w, seg_x, seg_t);
  if (n > MAXC) {
    out[RW_N] = 0u;
    return;
  }
#if CACHE_A_CODES
  __global const float* P = probes + (plane / per_probe) * PROBE_STRIDE;
  __global uint* c = codes + ((size_t)plane * kernel_h + row) * (kernel_w + CODE_ROW_PAD);
  for (int k = 0; k < n; ++k) {
    if (seg_t[k] < 0) continue;
    const row_plane16_t rp = broadcast16(row_plane(T, seg_t[k], py));
    for (int i0 = seg_x[k]; i0 < seg_x[k + 1]; i0 += 16)
      vstore16(fragment16(rp, P, (origin_x + convert_float16(i0 + LANES)) + 0.5f).code, 0, c + i0);
  }
#endif
  out[RW_N] = (uint)n;
  for (int k = 0; k <= n; ++k) out[RW_X + k] = (uint)seg_x[k];
  for (int k = 0; k < n; ++k) out[RW_T + k] = (uint)seg_t[k];
  /* A's own certification is not needed: only B's ownership enters the proof (coverage_margin) */
  ((__global float*)out)[RW_MARGIN] = coverage_margin(T, py, origin_x, n, seg_x, seg_t);
}
