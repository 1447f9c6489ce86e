// One plane in one frame: the stages above in order, the plane's record and flags.

// Vertex stage, divide, window transform and triangle set-up of one plane in one frame into
// record T and flags *vflag.
static inline void setup_plane(__global const float* P, __global const float* M, float half_w,
                               float half_h, float origin_x, float origin_y, uint kernel_w,
                               uint kernel_h, uint band_rows, __global float* T,
                               __global uint* vflag, int flip) {
  float xw[NV_PAD], yw[NV_PAD], dw[NV_PAD], qw[NV_PAD];
#if CLIP_SLOTS > 1
  const int depth_gl = P[MTS_C_DEPTH_GL] != 0.0f;
  const int snap_bits = (int)P[MTS_C_SNAP_BITS];
  float4 cv[NV_PAD]; /* clip coordinates, for the clip stage */
#endif
  uint nonfinite = 0u;
  for (int v0 = 0; v0 < NV; v0 += 16) { /* the grid's vertices, 16 at a time */
    const vertices16_t vs = vertex_stage16(P, M, min(v0 + LANES, NV - 1), half_w, half_h);
    vstore16(vs.x, 0, xw + v0);
    vstore16(vs.y, 0, yw + v0);
    vstore16(vs.d, 0, dw + v0);
    vstore16(vs.q, 0, qw + v0);
    nonfinite |= any16(vs.nonfinite) ? 1u : 0u; /* lanes past NV repeat vertex NV - 1 */
#if CLIP_SLOTS > 1
    float cx[16], cy[16], cz[16], cw[16];
    vstore16(vs.clip.x, 0, cx);
    vstore16(vs.clip.y, 0, cy);
    vstore16(vs.clip.z, 0, cz);
    vstore16(vs.clip.w, 0, cw);
    for (int k = 0; k < 16; ++k) cv[v0 + k] = (float4)(cx[k], cy[k], cz[k], cw[k]);
#endif
  }
  uint shapely = 1u; /* covers_kernel's argument holds at least outside the sliver bands */
  uint slivers = 0u; /* bands of kernel rows near a sliver triangle */
#if CLIP_SLOTS == 1
  /* every grid triangle in the record of its own index, 16 at a time, each corner's vertex stage
   * computed again in its lane (the same operations give the same values) rather than gathered */
  for (int g = 0; g < NT0; g += 16) {
    const int lanes = min(16, NT0 - g);
    int slot[16];
    for (int k = 0; k < 16; ++k) slot[k] = g + k;
    int16 corner[3];
    triangle_vertices16(min(g + LANES, NT0 - 1), flip, &corner[0], &corner[1], &corner[2]);
    triangles16_t tris;
    tris.adv_depth = P[MTS_C_ADV_DEPTH];
    tris.adv_tolerance = P[MTS_C_ADV_INTERPOLATION];
    for (int c = 0; c < 3; ++c) {
      const vertices16_t vs = vertex_stage16(P, M, corner[c], half_w, half_h);
      tris.x[c] = vs.x;
      tris.y[c] = vs.y;
      tris.d[c] = vs.d;
      tris.q[c] = vs.q;
      tris.id[c] = corner[c];
    }
    setup_triangles16(T, slot, lanes, &tris, origin_x, origin_y, kernel_w, kernel_h, band_rows,
                      &slivers, &shapely);
  }
  for (int qj = 0; qj < GRID; ++qj) ((__global int*)T)[Q_USED + qj] = Q_SLOTS;
#else
  pending_triangles_t pending; /* set up 16 at a time */
  pending.n = 0;
  pending.adv_depth = P[MTS_C_ADV_DEPTH];
  pending.adv_tolerance = P[MTS_C_ADV_INTERPOLATION];
  int next = 0; /* the next free record of the current quad row */
  for (int t0 = 0; t0 < NT0; ++t0) {
    const int qj = t0 / (2 * GRID);
    if (t0 % (2 * GRID) == 0) next = Q_SLOTS * qj;
    int16 corner[3];
    triangle_vertices16((int16)t0, flip, &corner[0], &corner[1], &corner[2]);
    const int vi[3] = {corner[0].s0, corner[1].s0, corner[2].s0};
    const uint m0 = clip_mask(cv[vi[0]]), m1 = clip_mask(cv[vi[1]]), m2 = clip_mask(cv[vi[2]]);
    if (!(m0 | m1 | m2)) {
      const float x[3] = {xw[vi[0]], xw[vi[1]], xw[vi[2]]};
      const float y[3] = {yw[vi[0]], yw[vi[1]], yw[vi[2]]};
      const float d[3] = {dw[vi[0]], dw[vi[1]], dw[vi[2]]};
      const float q[3] = {qw[vi[0]], qw[vi[1]], qw[vi[2]]};
      queue_triangle(&pending, next++, vi, x, y, d, q, T, origin_x, origin_y, kernel_w, kernel_h,
                     band_rows, &slivers, &shapely);
    } else if (!(m0 & m1 & m2)) { /* all outside one plane: culled */
      clip_vertex_t poly[3];
      for (int k = 0; k < 3; ++k) {
        const int v = vi[k];
        poly[k] = (clip_vertex_t){cv[v], xw[v], yw[v], dw[v], qw[v], v};
      }
      next +=
          clip_fan(T, t0, next, poly, m0 | m1 | m2, half_w, half_h, origin_x, origin_y, kernel_w,
                   kernel_h, band_rows, depth_gl, snap_bits, &pending, &slivers, &shapely);
    }
    if (t0 % (2 * GRID) == 2 * GRID - 1) {
      ((__global int*)T)[Q_USED + qj] = next - Q_SLOTS * qj;
      for (int k = next; k < Q_SLOTS * (qj + 1); ++k) empty_slot(T, k);
    }
  }
  setup_pending(&pending, T, origin_x, origin_y, kernel_w, kernel_h, band_rows, &slivers, &shapely);
#endif
  const int certify = !nonfinite && shapely; /* covers_kernel's preconditions */
  int bad_row[NV];
  *vflag = nonfinite | (certify ? covers_kernel(xw, yw, origin_x, origin_y, kernel_w, kernel_h,
                                                slivers, bad_row)
                                : 0u);
  for (int v = 0; v < NV_PAD; ++v)
    ((__global int*)T)[V_BAD_ROW + v] = v < NV && certify ? bad_row[v] : -1;
  for (int qj = 0; qj < GRID; ++qj) {
    float lo = INFINITY, hi = -INFINITY;
    int box_lo = INT_MAX, box_hi = -1;
    for (int t = Q_SLOTS * qj; t < Q_SLOTS * qj + ((__global int*)T)[Q_USED + qj]; ++t) {
      lo = fmin(lo, T[t * MTS_TRI_STRIDE + MTS_T_YMIN]);
      hi = fmax(hi, T[t * MTS_TRI_STRIDE + MTS_T_YMAX]);
      const int4 box = vload4(0, (__global const int*)T + t * MTS_TRI_STRIDE + MTS_T_BOX);
      if (box.s0 <= box.s1 && box.s2 <= box.s3) {
        box_lo = min(box_lo, box.s2);
        box_hi = max(box_hi, box.s3);
      }
    }
    T[Q_YRANGE + 2 * qj] = lo;
    T[Q_YRANGE + 2 * qj + 1] = hi;
    vstore2((int2)(box_lo, box_hi), 0, (__global int*)T + Q_BOX_ROWS + 2 * qj);
  }
  /* the edge arrays' padding repeats triangle 0's edge 0 */
  __global uint* SA = (__global uint*)T + NT * MTS_TRI_STRIDE;
  for (int k = NE; k < NE_PAD; ++k)
    for (int a = 0; a <= MTS_E_BITS; ++a) SA[a * NE_PAD + k] = SA[a * NE_PAD];
}
