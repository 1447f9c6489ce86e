// The triangle set-up, 16 triangles a call: edges, ownership, depth and 1/w planes, y-range.

// Sixteen triangles at once, one per lane: window x, y, depth, 1/w and vertex id of each corner.
typedef struct {
  float16 x[3], y[3], d[3], q[3];
  int16 id[3];
  float adv_depth, adv_tolerance; /* the plane's MTS_C_ADV_DEPTH and MTS_C_ADV_INTERPOLATION */
} triangles16_t;

// An envelope's interpolation error (interface/adversary.h dp_adv_shift_plane), in the
// adversary's direction (dp_adv_value_sign): the interpolated plane's constant moved, lane by
// lane.
static inline void adversary_planes16(uint16* rec, const triangles16_t* v) {
  const int sign = dp_adv_value_sign(DEPTH_FROM == 2, v->adv_depth);
#if DEPTH_FROM == 2
  const int field = MTS_T_Q0;
  const float16* val = v->q;
#else
  const int field = MTS_T_D0;
  const float16* val = v->d;
#endif
  float c0[16], a[16], b[16], c[16];
  vstore16(as_float16(rec[field]), 0, c0);
  vstore16(val[0], 0, a);
  vstore16(val[1], 0, b);
  vstore16(val[2], 0, c);
  for (int k = 0; k < 16; ++k)
    c0[k] = dp_adv_shift_plane(c0[k], a[k], b[k], c[k], (double)v->adv_tolerance, sign);
  rec[field] = as_uint16(vload16(0, c0));
}

// Triangle records slot[0 .. lanes - 1] of plane T from lanes 0 .. lanes - 1 of v, each as a
// scalar set-up would make it, 16 at a time: the set-up is a few hundred operations per triangle,
// and this way they run in vector lanes (lanes past `lanes` are computed and not stored). Per
// triangle: vertex ids (an edge is evaluated from its lower-id vertex, so two triangles sharing it
// compute the same value), window x, y, depth and 1/w give the edges, orientation and ownership
// bits, the depth and 1/w planes in the set-up's form, the y-range, the largest |depth|, the edge
// arrays and the pixel box. A degenerate triangle, or one with an angle below ~6 degrees, is a
// sliver (mark_sliver, one lane at a time: rare).
#if MTS_NV(GRID) + 8 * NT0 > (1 << 15) /* the grid's vertices, then 8 per clipped triangle */
#error "vertex ids need more than the 15 bits the edge arrays keep for each (MTS_E_ID_SHIFT)"
#endif
static inline void setup_triangles16(__global float* T, const int* slot, int lanes,
                                     const triangles16_t* v, float origin_x, float origin_y,
                                     uint kernel_w, uint kernel_h, uint band_rows, uint* slivers,
                                     uint* shapely) {
  const float16 *x = v->x, *y = v->y, *d = v->d, *q = v->q;
  const int16* id = v->id;
  uint16 rec[MTS_TRI_STRIDE], edges[6][3]; /* the records' fields and edge arrays, a lane each */
  float16 ex[3], ey[3], edx[3], edy[3];
  int16 bits = (int16)0;
  for (int e = 0; e < 3; ++e) {
    const int a = e, b = (e + 1) % 3;
    const int16 a_low = id[a] < id[b]; /* the edge runs from its lower-id vertex */
    ex[e] = select(x[b], x[a], a_low);
    ey[e] = select(y[b], y[a], a_low);
    edx[e] = select(x[a], x[b], a_low) - ex[e];
    edy[e] = select(y[a], y[b], a_low) - ey[e];
    rec[MTS_T_EDGES + 4 * e + 0] = as_uint16(ex[e]);
    rec[MTS_T_EDGES + 4 * e + 1] = as_uint16(ey[e]);
    rec[MTS_T_EDGES + 4 * e + 2] = as_uint16(edx[e]);
    rec[MTS_T_EDGES + 4 * e + 3] = as_uint16(edy[e]);
    bits |= select((int16)0, (int16)MTS_BIT_NEGATE(e), id[a] > id[b]);
  }
  // orientation: edge 0 evaluated at vertex 2
  float16 orient = edx[0] * (y[2] - ey[0]) - edy[0] * (x[2] - ex[0]);
  orient = select(orient, -orient, (bits & (int)MTS_BIT_NEGATE(0)) != 0);
  bits = select(bits, bits ^ (int)MTS_BIT_NEGATE_ALL, orient < 0.0f);
  const int16 valid = (orient != 0.0f) & isfinite(orient);
  for (int e = 0; e < 3; ++e) {
    const float16 s = select((float16)1.0f, (float16)-1.0f, (bits & (int)MTS_BIT_NEGATE(e)) != 0);
    const float16 dx = s * edx[e], dy = s * edy[e];
    bits |= select((int16)0, (int16)MTS_BIT_OWNS(e), (dy < 0.0f) | ((dy == 0.0f) & (dx < 0.0f)));
  }
  bits |= select((int16)0, (int16)MTS_BIT_VALID, valid);
  const float16 e1x = x[1] - x[0], e1y = y[1] - y[0];
  const float16 e2x = x[2] - x[0], e2y = y[2] - y[0];
  const float16 det = e1x * e2y - e2x * e1y;
  {
    const float16 e3x = x[2] - x[1], e3y = y[2] - y[1];
    const float16 longest =
        fmax(fmax(e1x * e1x + e1y * e1y, e2x * e2x + e2y * e2y), e3x * e3x + e3y * e3y);
    /* |det| = l_j l_k sin(angle) >= longest * sin(angle) */
    const int16 sliver = (!valid | !(fabs(det) >= 0.1f * longest)) & (LANES < lanes);
    if (any16(sliver)) {
      float xs[3][16], ys[3][16], dets[16];
      int sl[16];
      for (int c = 0; c < 3; ++c) {
        vstore16(x[c], 0, xs[c]);
        vstore16(y[c], 0, ys[c]);
      }
      vstore16(det, 0, dets);
      vstore16(sliver, 0, sl);
      for (int k = 0; k < lanes; ++k) {
        if (!sl[k]) continue;
        const float xk[3] = {xs[0][k], xs[1][k], xs[2][k]}, yk[3] = {ys[0][k], ys[1][k], ys[2][k]};
        mark_sliver(xk, yk, dets[k], origin_x, origin_y, kernel_w, kernel_h, band_rows, slivers,
                    shapely);
      }
    }
  }
#if PLANE_FORM == 1
  {
    /* llvmpipe (lp_state_setup.c): the vertices as it passes them, (v1, v0, v2) when the area
     * is negative; gradients as differences times 1/area; the value at the framebuffer origin.
     * Evaluated at integer pixel coordinates (px - 0.5, py - 0.5): MTS_T_X0 = MTS_T_Y0 = 0.5. */
    const int16 neg = det < 0.0f; /* j0 = 1, j1 = 0 where set; j2 = 2 */
    const float16 xj0 = select(x[0], x[1], neg), xj1 = select(x[1], x[0], neg);
    const float16 yj0 = select(y[0], y[1], neg), yj1 = select(y[1], y[0], neg);
    const float16 dj0 = select(d[0], d[1], neg), dj1 = select(d[1], d[0], neg);
    const float16 qj0 = select(q[0], q[1], neg), qj1 = select(q[1], q[0], neg);
    const float16 x0c = xj0 - 0.5f, y0c = yj0 - 0.5f;
    const float16 dx01 = xj0 - xj1, dy01 = yj0 - yj1;
    const float16 dx20 = x[2] - xj0, dy20 = y[2] - yj0;
    const float16 ooa = 1.0f / (dx01 * dy20 - dx20 * dy01);
    const float16 dy20o = dy20 * ooa, dy01o = dy01 * ooa, dx20o = dx20 * ooa, dx01o = dx01 * ooa;
    const float16 dz01 = dj0 - dj1, dz20 = d[2] - dj0;
    const float16 dzdx = dz01 * dy20o - dz20 * dy01o, dzdy = dz20 * dx01o - dz01 * dx20o;
    const float16 dq01 = qj0 - qj1, dq20 = q[2] - qj0;
    const float16 dqdx = dq01 * dy20o - dq20 * dy01o, dqdy = dq20 * dx01o - dq01 * dx20o;
    origin_planes16(rec, x0c, y0c, dj0, dzdx, dzdy, qj0, dqdx, dqdy);
  }
#elif PLANE_FORM == 2
  {
    /* softpipe (sp_setup.c): vertices sorted by y as setup_sort_vertices does (ties keep its
     * order), ebot = vmid - vmin, emaj = vmax - vmin, gradients times 1/area, the value at the
     * framebuffer origin from vmin (tri_linear_coeff). Evaluated per 2x2 quad (row_plane). Its
     * branches, lane by lane: y0 <= y1: (0, 1, 2) if y1 <= y2, else (2, 0, 1) if y2 <= y0, else
     * (0, 2, 1); y0 > y1: (1, 0, 2) if y0 <= y2, else (2, 1, 0) if y2 <= y1, else (1, 2, 0). */
    const int16 c01 = y[0] <= y[1], c12 = y[1] <= y[2], c20 = y[2] <= y[0];
    const int16 c02 = y[0] <= y[2], c21 = y[2] <= y[1];
    const int16 lo = select(select(select((int16)1, (int16)2, c21), (int16)1, c02),
                            select(select((int16)0, (int16)2, c20), (int16)0, c12), c01);
    const int16 mid = select(select(select((int16)2, (int16)1, c21), (int16)0, c02),
                             select(select((int16)2, (int16)0, c20), (int16)1, c12), c01);
    const int16 hi = select(select(select((int16)0, (int16)0, c21), (int16)2, c02),
                            select(select((int16)1, (int16)1, c20), (int16)2, c12), c01);
    const float16 xl = pick16(x, lo), yl = pick16(y, lo), dl = pick16(d, lo), ql = pick16(q, lo);
    const float16 bot_dx = pick16(x, mid) - xl, bot_dy = pick16(y, mid) - yl;
    const float16 maj_dx = pick16(x, hi) - xl, maj_dy = pick16(y, hi) - yl;
    const float16 ooa = 1.0f / (maj_dx * bot_dy - bot_dx * maj_dy);
    const float16 xc = xl - 0.5f, yc = yl - 0.5f;
    const float16 botdz = pick16(d, mid) - dl, majdz = pick16(d, hi) - dl;
    const float16 dzdx = (bot_dy * majdz - botdz * maj_dy) * ooa;
    const float16 dzdy = (maj_dx * botdz - majdz * bot_dx) * ooa;
    const float16 botdq = pick16(q, mid) - ql, majdq = pick16(q, hi) - ql;
    const float16 dqdx = (bot_dy * majdq - botdq * maj_dy) * ooa;
    const float16 dqdy = (maj_dx * botdq - majdq * bot_dx) * ooa;
    origin_planes16(rec, xc, yc, dl, dzdx, dzdy, ql, dqdx, dqdy);
  }
#else
  const float16 e1d = d[1] - d[0], e2d = d[2] - d[0];
  const float16 e1q = q[1] - q[0], e2q = q[2] - q[0];
  rec[MTS_T_X0] = as_uint16(x[0]);
  rec[MTS_T_Y0] = as_uint16(y[0]);
  rec[MTS_T_D0] = as_uint16(d[0]);
  rec[MTS_T_DZDX] = as_uint16((e1d * e2y - e2d * e1y) / det);
  rec[MTS_T_DZDY] = as_uint16((e2d * e1x - e1d * e2x) / det);
  rec[MTS_T_Q0] = as_uint16(q[0]);
  rec[MTS_T_DQDX] = as_uint16((e1q * e2y - e2q * e1y) / det);
  rec[MTS_T_DQDY] = as_uint16((e2q * e1x - e1q * e2x) / det);
#endif
  const float16 ymin = fmin(fmin(y[0], y[1]), y[2]), ymax = fmax(fmax(y[0], y[1]), y[2]);
  rec[MTS_T_YMIN] = as_uint16(ymin);
  rec[MTS_T_YMAX] = as_uint16(ymax);
  rec[MTS_T_ZMAX] = as_uint16(fmax(fmax(fabs(d[0]), fabs(d[1])), fabs(d[2])));
  const uint16 ub = as_uint16(bits);
  for (int e = 0; e < 3; ++e) {
    const float16 dxdy = edx[e] / edy[e];
    rec[MTS_T_DXDY + e] = as_uint16(dxdy);
    edges[MTS_E_AX][e] = as_uint16(ex[e]);
    edges[MTS_E_AY][e] = as_uint16(ey[e]);
    edges[MTS_E_DX][e] = as_uint16(edx[e]);
    edges[MTS_E_DY][e] = as_uint16(edy[e]);
    edges[MTS_E_DXDY][e] = as_uint16(dxdy);
    edges[MTS_E_BITS][e] = ((ub & MTS_BIT_NEGATE(e)) >> e) |
                           (((ub & MTS_BIT_OWNS(e)) >> (3 + e)) << 1) |
                           (as_uint16(id[e]) << MTS_E_ID_SHIFT) |
                           (as_uint16(id[(e + 1) % 3]) << (MTS_E_ID_SHIFT + 15));
  }
  rec[MTS_T_BITS] = as_uint16(bits);
  pixel_boxes16(rec, ex, edx, ymin, ymax, origin_x, origin_y, (int)kernel_w, (int)kernel_h);
  /* kernels/bias.cl's bias, set after the set-up; kernels/mts.cl's adversary's code direction */
  rec[MTS_T_ADVERSARY] = as_uint16((float16)v->adv_depth);
  if (v->adv_depth != 0.0f && v->adv_tolerance > 0.0f) adversary_planes16(rec, v);
  write_records16(T, slot, lanes, rec);
  write_edges16(T, slot, lanes, edges);
}
