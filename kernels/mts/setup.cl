// Vertex set-up of a plane, and the certificate that it covers the kernel.

// Window x and y as the rasterizer stores them (pipeline.snap, kernels/snap.h).
DP_SNAP_WINDOW_DEFINE(snap_window_bits, fabs, rint)

// A certificate that the plane's rasterisation owns every kernel pixel centre (no pixel
// uncovered), so a frame can be decided from code bounds without walking its rows
// (mts_frame_bounds). In exact arithmetic the triangles tile the plane's outline; the binary32 edge
// tests can disagree with that only within their rounding error of an edge line, where two
// triangles share the edge and compute the same value with opposite signs (exactly one owns the
// pixel), unless the pixel is also near another edge, i.e. near a vertex. So the certificate asks
// for: the kernel's pixel area inside every boundary edge's half-plane (the intersection of those
// half-planes lies inside the outline) with half a pixel to spare; no vertex within 1/8 pixel of a
// pixel centre in both x and y; all coordinates below 8192 in magnitude (edge-test error below
// 0.006 px) and no triangle angle below ~6 degrees (mts_setup), so a pixel centre 1/8 px from a
// vertex is > 0.0125 px from that vertex's other edges. docs/mts.md ("Shortcuts") has the argument.
// A vertex near a pixel centre only spoils the certificate for the one pixel near it, so the
// rest stays certified and the pixel's row is written to bad_row[vertex] (-1 for a vertex near no
// pixel centre) for row_covered and band_bad_rows. Bands a sliver spoils, whose rows are not
// known, are named in the flags (bit V_BAND_SHIFT + band, bands of band_rows rows).
static inline uint covers_kernel(const float* xw, const float* yw, float ox, float oy, uint kw,
                                 uint kh, uint sliver_bands, int* bad_row) {
  const float x0 = ox, x1 = ox + (float)kw, y0 = oy, y1 = oy + (float)kh; /* pixel area */
  for (int v = 0; v < NV; ++v) bad_row[v] = -1;
  for (int v = 0; v < NV; ++v) {
    if (!(fabs(xw[v]) <= 8192.0f && fabs(yw[v]) <= 8192.0f)) return 0u;
    if (xw[v] < x0 - 1.0f || xw[v] > x1 + 1.0f || yw[v] < y0 - 1.0f || yw[v] > y1 + 1.0f) continue;
    const float fx = xw[v] - ox - 0.5f, fy = yw[v] - oy - 0.5f;
    if (fabs(fx - rint(fx)) < 0.125f && fabs(fy - rint(fy)) < 0.125f)
      bad_row[v] = clamp((int)rint(fy), 0, (int)kh - 1);
  }
  /* the reference point: the mean of the four corner vertices, inside the outline */
  const int c[4] = {0, GRID, NV - 1, NV - 1 - GRID};
  float rx = 0.0f, ry = 0.0f;
  for (int k = 0; k < 4; ++k) {
    rx += 0.25f * xw[c[k]];
    ry += 0.25f * yw[c[k]];
  }
  for (int side = 0; side < 4; ++side) {
    for (int k = 0; k < GRID; ++k) {
      /* vertices along the side, in grid order: bottom row, right column, top row, left column */
      const int va = side == 0   ? k
                     : side == 1 ? k * (GRID + 1) + GRID
                     : side == 2 ? GRID * (GRID + 1) + k
                                 : k * (GRID + 1);
      const int vb = side == 0   ? k + 1
                     : side == 1 ? (k + 1) * (GRID + 1) + GRID
                     : side == 2 ? GRID * (GRID + 1) + k + 1
                                 : (k + 1) * (GRID + 1);
      const int lo = min(va, vb), hi = max(va, vb);
      const float ax = xw[lo], ay = yw[lo], dx = xw[hi] - xw[lo], dy = yw[hi] - yw[lo];
      const float inner = dx * (ry - ay) - dy * (rx - ax);
      const float margin = 0.5f * (fabs(dx) + fabs(dy)); /* half a pixel: |E| / length >= 0.5 */
      for (int q = 0; q < 4; ++q) {
        const float px = (q & 1) ? x1 : x0, py = (q & 2) ? y1 : y0;
        float E = dx * (py - ay) - dy * (px - ax);
        if (inner < 0.0f) E = -E;
        if (!(E > margin)) return 0u;
      }
    }
  }
  return V_COVERS | (sliver_bands ? V_SLIVERS : 0u) | (sliver_bands << V_BAND_SHIFT);
}

// Whether the strip of points within w of the line through the origin along (dx, dy) (length l)
// meets row offset ry, and where: the x offsets (*lo, *hi) it spans there, narrowed.
static inline int strip_at_row(float dx, float dy, float l, float w, float ry, float* lo,
                               float* hi) {
  if (dy == 0.0f) return fabs(ry * dx) < w * l;           /* horizontal: all of the row, or none */
  const float c = ry * dx / dy, width = w * l / fabs(dy); /* half the strip's width in x */
  *lo = fmax(*lo, c - width);
  *hi = fmin(*hi, c + width);
  return 1;
}

// Whether the span [x_lo, x_hi] of a row holds a kernel pixel centre (ox + i + 0.5, i < kw).
static inline int holds_pixel_column(float x_lo, float x_hi, float ox, uint kw) {
  return max((int)ceil(x_lo - ox - 0.5f), 0) <= min((int)floor(x_hi - ox - 0.5f), (int)kw - 1);
}

// Where covers_kernel's argument fails near a sliver (a triangle with an angle below ~6 degrees):
// a pixel centre within the edge tests' rounding error (< 0.006 px) of both edges meeting at
// vertex V at angle a, a thin rhombus about V along the angle's bisector, reaching 0.006 /
// sin(a/2) from V; no pixel centre is near two edges of a triangle anywhere else. So the bands of
// the kernel rows holding a pixel centre within 0.0125 px of both edge lines (twice the error, as
// covers_kernel keeps; the rhombus then reaches less than 0.025 / sin a), or within 1/8 of V in x
// and y (covers_kernel's vertex rule), are set in *slivers and left out of the certificate; the
// rest of the kernel keeps it. Most slivers, the clip stage's fans along the viewport's edge, then
// cost nothing: their rhombi are thinner than the distance between pixel centres. sin a = |det| /
// (|e1| |e2|) for the edges at V, taken 1 % smaller; a degenerate triangle (det 0 or not a
// number) marks every row of its box. A band past V_MAX_BANDS clears *shapely.
static inline void mark_sliver(const float* x, const float* y, float det, float ox, float oy,
                               uint kw, uint kh, uint band_rows, uint* slivers, uint* shapely) {
  for (int v = 0; v < 3; ++v) {
    const int a = (v + 1) % 3, b = (v + 2) % 3;
    const float ax = x[a] - x[v], ay = y[a] - y[v], bx = x[b] - x[v], by = y[b] - y[v];
    const float la = sqrt(ax * ax + ay * ay), lb = sqrt(bx * bx + by * by);
    const float sin_v = 0.99f * fabs(det) / (la * lb);
    const int degenerate = !(sin_v > 0.0f);
    const float reach = fmax(0.125f, 0.025f / sin_v);
    const float rx = !degenerate ? reach : fmax(fmax(fabs(ax), fabs(bx)), 1.0f) + 1.0f;
    const float ry = !degenerate ? reach : fmax(fmax(fabs(ay), fabs(by)), 1.0f) + 1.0f;
    if (!(rx < 16384.0f && ry < 16384.0f)) { /* not a number, or beyond any kernel */
      *shapely = 0u;
      return;
    }
    /* rows within ry of y[v]; of a degenerate triangle every one, else those the rhombus or the
     * 1/8 square about V meets at a pixel centre */
    const int j0 = max((int)ceil(y[v] - ry - oy - 0.5f), 0);
    const int j1 = min((int)floor(y[v] + ry - oy - 0.5f), (int)kh - 1);
    for (int j = j0; j <= j1; ++j) {
      const float dy = oy + (float)j + 0.5f - y[v];
      float lo = -rx, hi = rx;
      int hit = degenerate;
      if (!hit && strip_at_row(ax, ay, la, 0.0125f, dy, &lo, &hi) &&
          strip_at_row(bx, by, lb, 0.0125f, dy, &lo, &hi))
        hit = holds_pixel_column(x[v] + lo, x[v] + hi, ox, kw);
      if (!hit && fabs(dy) < 0.125f) hit = holds_pixel_column(x[v] - 0.125f, x[v] + 0.125f, ox, kw);
      if (!hit) continue;
      if ((uint)j / band_rows >= V_MAX_BANDS) {
        *shapely = 0u;
        return;
      }
      *slivers |= 1u << ((uint)j / band_rows);
    }
  }
}

// Sixteen triangles at once, one per lane: window x, y, depth, 1/w and vertex id of each corner.
typedef struct {
  float16 x[3], y[3], d[3], q[3];
  int16 id[3];
} triangles16_t;

// 16 x 16 transpose: out[k] lane f = in[f] lane k, by swapping the off-diagonal b x b blocks of
// every 2b x 2b block for b = 8, 4, 2, 1 (each swap exchanges bit b of the row and column). The
// shuffles' lane lists are constants (__builtin_shufflevector), so each is one instruction: with
// masks computed at run time, PoCL's shuffle2 made the set-up slower than storing lane by lane.
#define SWAP_BLOCKS(m, b)                                          \
  _Pragma("unroll") for (int i = 0; i < 16; ++i) if (!(i & (b))) { \
    const uint16 a_ = m[i], c_ = m[i + (b)];                       \
    m[i] = __builtin_shufflevector(a_, c_, FIRST_##b);             \
    m[i + (b)] = __builtin_shufflevector(a_, c_, SECOND_##b);      \
  }
#define FIRST_8 0, 1, 2, 3, 4, 5, 6, 7, 16, 17, 18, 19, 20, 21, 22, 23
#define SECOND_8 8, 9, 10, 11, 12, 13, 14, 15, 24, 25, 26, 27, 28, 29, 30, 31
#define FIRST_4 0, 1, 2, 3, 16, 17, 18, 19, 8, 9, 10, 11, 24, 25, 26, 27
#define SECOND_4 4, 5, 6, 7, 20, 21, 22, 23, 12, 13, 14, 15, 28, 29, 30, 31
#define FIRST_2 0, 1, 16, 17, 4, 5, 20, 21, 8, 9, 24, 25, 12, 13, 28, 29
#define SECOND_2 2, 3, 18, 19, 6, 7, 22, 23, 10, 11, 26, 27, 14, 15, 30, 31
#define FIRST_1 0, 16, 2, 18, 4, 20, 6, 22, 8, 24, 10, 26, 12, 28, 14, 30
#define SECOND_1 1, 17, 3, 19, 5, 21, 7, 23, 9, 25, 11, 27, 13, 29, 15, 31
static inline void transpose16(uint16* m) {
  SWAP_BLOCKS(m, 8)
  SWAP_BLOCKS(m, 4)
  SWAP_BLOCKS(m, 2)
  SWAP_BLOCKS(m, 1)
}
#undef SWAP_BLOCKS

// Triangle records slot[0 .. lanes - 1] from their fields (rec[field], a lane per record):
// transposed in registers, each record is two 16-word stores rather than 32 scattered ones.
static inline void write_records16(__global float* T, const int* slot, int lanes, uint16* rec) {
  transpose16(rec);
  transpose16(rec + 16);
  for (int k = 0; k < lanes; ++k) {
    __global uint* R = (__global uint*)T + slot[k] * TRI_STRIDE;
    vstore16(rec[k], 0, R);
    vstore16(rec[16 + k], 0, R + 16);
  }
}

// Their edges in the edge arrays (structure of arrays: edge e of record t at 3 t + e), from
// edges[array][e] (a lane per record): each array's 48 words interleaved in registers.
static inline void write_edges16(__global float* T, const int* slot, int lanes,
                                 uint16 edges[6][3]) {
  /* 16 records in a row (the grid's, without a clip stage): 3 stores per array */
  const int run = lanes == 16 && slot[15] == slot[0] + 15;
  for (int a = 0; a < 6; ++a) {
    /* word w = 16 h + j of out[h] is edge w % 3 of lane w / 3: edges 0 and 1 first, then 2 */
    const uint16 e0 = edges[a][0], e1 = edges[a][1], e2 = edges[a][2];
    const uint16 t0 =
        __builtin_shufflevector(e0, e1, 0, 16, 0, 1, 17, 1, 2, 18, 2, 3, 19, 3, 4, 20, 4, 5);
    const uint16 t1 =
        __builtin_shufflevector(e0, e1, 21, 5, 6, 22, 6, 7, 23, 7, 8, 24, 8, 9, 25, 9, 10, 26);
    const uint16 t2 = __builtin_shufflevector(e0, e1, 10, 11, 27, 11, 12, 28, 12, 13, 29, 13, 14,
                                              30, 14, 15, 31, 15);
    const uint16 out[3] = {
        __builtin_shufflevector(t0, e2, 0, 1, 16, 3, 4, 17, 6, 7, 18, 9, 10, 19, 12, 13, 20, 15),
        __builtin_shufflevector(t1, e2, 0, 21, 2, 3, 22, 5, 6, 23, 8, 9, 24, 11, 12, 25, 14, 15),
        __builtin_shufflevector(t2, e2, 26, 1, 2, 27, 4, 5, 28, 7, 8, 29, 10, 11, 30, 13, 14, 31)};
    __global uint* SA = (__global uint*)T + NT * TRI_STRIDE + a * NE_PAD;
    if (run) {
      for (int h = 0; h < 3; ++h) vstore16(out[h], 0, SA + 3 * slot[0] + 16 * h);
    } else {
      uint words[48];
      for (int h = 0; h < 3; ++h) vstore16(out[h], 0, words + 16 * h);
      for (int k = 0; k < lanes; ++k)
        for (int e = 0; e < 3; ++e) SA[3 * slot[k] + e] = words[3 * k + e];
    }
  }
}

#if PLANE_FORM != 0
// The depth and 1/w planes of a record referred to the framebuffer origin, as llvmpipe and softpipe
// refer them: the anchor vertex's value minus the gradients times its offset (xc, yc) from the
// origin pixel's centre; evaluated at integer pixel coordinates, so x0 = y0 = 1/2.
static inline void origin_planes16(uint16* rec, float16 xc, float16 yc, float16 d0, float16 dzdx,
                                   float16 dzdy, float16 q0, float16 dqdx, float16 dqdy) {
  rec[T_X0] = as_uint16((float16)0.5f);
  rec[T_Y0] = as_uint16((float16)0.5f);
  rec[T_D0] = as_uint16(d0 - (dzdx * xc + dzdy * yc));
  rec[T_DZDX] = as_uint16(dzdx);
  rec[T_DZDY] = as_uint16(dzdy);
  rec[T_Q0] = as_uint16(q0 - (dqdx * xc + dqdy * yc));
  rec[T_DQDX] = as_uint16(dqdx);
  rec[T_DQDY] = as_uint16(dqdy);
}

// v[i[lane]] per lane, i in 0..2.
static inline float16 pick16(const float16* v, int16 i) {
  return select(select(v[0], v[1], i == 1), v[2], i == 2);
}
#endif

// The kernel pixels (column i0..i1, row j0..j1: fields T_BOX .. T_BOX + 3) that a triangle may own:
// those whose centre lies within its bounding box widened by one pixel (an edge test can pass only
// within its rounding error outside the exact triangle). Empty when i0 > i1 or j0 > j1. The x
// extent is taken from the edges as the record stores them (anchor, anchor + direction).
static inline void pixel_boxes16(uint16* rec, const float16* ex, const float16* edx, float16 ymin,
                                 float16 ymax, float ox, float oy, int W, int H) {
  float16 xmin = (float16)INFINITY, xmax = (float16)-INFINITY;
  for (int e = 0; e < 3; ++e) {
    const float16 ax = ex[e], bx = ax + edx[e];
    xmin = fmin(xmin, fmin(ax, bx));
    xmax = fmax(xmax, fmax(ax, bx));
  }
  const int16 i0 = max(convert_int16(ceil(fmax(xmin - 1.0f - ox - 0.5f, -1.0f))), 0);
  const int16 i1 = min(convert_int16(floor(fmin(xmax + 1.0f - ox - 0.5f, (float)W))), W - 1);
  const int16 j0 = max(convert_int16(ceil(fmax(ymin - 1.0f - oy - 0.5f, -1.0f))), 0);
  const int16 j1 = min(convert_int16(floor(fmin(ymax + 1.0f - oy - 0.5f, (float)H))), H - 1);
  rec[T_BOX + 0] = as_uint16(i0);
  rec[T_BOX + 1] = as_uint16(i1);
  rec[T_BOX + 2] = as_uint16(j0);
  rec[T_BOX + 3] = as_uint16(j1);
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
#error "vertex ids need more than the 15 bits the edge arrays keep for each (E_ID_SHIFT)"
#endif
static inline void setup_triangles16(__global float* T, const int* slot, int lanes,
                                     const triangles16_t* v, float origin_x, float origin_y,
                                     uint kernel_w, uint kernel_h, uint band_rows, uint* slivers,
                                     uint* shapely) {
  const float16 *x = v->x, *y = v->y, *d = v->d, *q = v->q;
  const int16* id = v->id;
  uint16 rec[TRI_STRIDE], edges[6][3]; /* the records' fields and edge arrays, a lane each */
  float16 ex[3], ey[3], edx[3], edy[3];
  int16 bits = (int16)0;
  for (int e = 0; e < 3; ++e) {
    const int a = e, b = (e + 1) % 3;
    const int16 a_low = id[a] < id[b]; /* the edge runs from its lower-id vertex */
    ex[e] = select(x[b], x[a], a_low);
    ey[e] = select(y[b], y[a], a_low);
    edx[e] = select(x[a], x[b], a_low) - ex[e];
    edy[e] = select(y[a], y[b], a_low) - ey[e];
    rec[T_EDGES + 4 * e + 0] = as_uint16(ex[e]);
    rec[T_EDGES + 4 * e + 1] = as_uint16(ey[e]);
    rec[T_EDGES + 4 * e + 2] = as_uint16(edx[e]);
    rec[T_EDGES + 4 * e + 3] = as_uint16(edy[e]);
    bits |= select((int16)0, (int16)(1 << e), id[a] > id[b]);
  }
  // orientation: edge 0 evaluated at vertex 2
  float16 orient = edx[0] * (y[2] - ey[0]) - edy[0] * (x[2] - ex[0]);
  orient = select(orient, -orient, (bits & 1) != 0);
  bits = select(bits, bits ^ 7, orient < 0.0f);
  const int16 valid = (orient != 0.0f) & isfinite(orient);
  for (int e = 0; e < 3; ++e) {
    const float16 s = select((float16)1.0f, (float16)-1.0f, ((bits >> e) & 1) != 0);
    const float16 dx = s * edx[e], dy = s * edy[e];
    bits |= select((int16)0, (int16)(8 << e), (dy < 0.0f) | ((dy == 0.0f) & (dx < 0.0f)));
  }
  bits |= select((int16)0, (int16)64, valid);
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
     * Evaluated at integer pixel coordinates (px - 0.5, py - 0.5): T_X0 = T_Y0 = 0.5. */
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
  rec[T_X0] = as_uint16(x[0]);
  rec[T_Y0] = as_uint16(y[0]);
  rec[T_D0] = as_uint16(d[0]);
  rec[T_DZDX] = as_uint16((e1d * e2y - e2d * e1y) / det);
  rec[T_DZDY] = as_uint16((e2d * e1x - e1d * e2x) / det);
  rec[T_Q0] = as_uint16(q[0]);
  rec[T_DQDX] = as_uint16((e1q * e2y - e2q * e1y) / det);
  rec[T_DQDY] = as_uint16((e2q * e1x - e1q * e2x) / det);
#endif
  const float16 ymin = fmin(fmin(y[0], y[1]), y[2]), ymax = fmax(fmax(y[0], y[1]), y[2]);
  rec[T_YMIN] = as_uint16(ymin);
  rec[T_YMAX] = as_uint16(ymax);
  rec[T_ZMAX] = as_uint16(fmax(fmax(fabs(d[0]), fabs(d[1])), fabs(d[2])));
  const uint16 ub = as_uint16(bits);
  for (int e = 0; e < 3; ++e) {
    const float16 dxdy = edx[e] / edy[e];
    rec[T_DXDY + e] = as_uint16(dxdy);
    edges[E_AX][e] = as_uint16(ex[e]);
    edges[E_AY][e] = as_uint16(ey[e]);
    edges[E_DX][e] = as_uint16(edx[e]);
    edges[E_DY][e] = as_uint16(edy[e]);
    edges[E_DXDY][e] = as_uint16(dxdy);
    edges[E_BITS][e] = ((ub >> e) & 1u) | (((ub >> (3 + e)) & 1u) << 1) |
                       (as_uint16(id[e]) << E_ID_SHIFT) |
                       (as_uint16(id[(e + 1) % 3]) << (E_ID_SHIFT + 15));
  }
  rec[T_BITS] = as_uint16(bits);
  pixel_boxes16(rec, ex, edx, ymin, ymax, origin_x, origin_y, (int)kernel_w, (int)kernel_h);
  rec[T_BIAS] = (uint16)0u; /* kernels/bias.cl's, set after the set-up */
  write_records16(T, slot, lanes, rec);
  write_edges16(T, slot, lanes, edges);
}

#if CLIP_SLOTS > 1
// Triangles waiting for their set-up, a lane each (corner c of lane k), with the record each goes
// to: the set-up takes them 16 at a time (setup_pending). With a clip stage the grid's triangles
// and the fans take records in the order they come.
typedef struct {
  float x[3][16], y[3][16], d[3][16], q[3][16];
  int id[3][16];
  int slot[16];
  int n;
} pending_triangles_t;

// Sets up the pending triangles, 16 lanes of which the ones past p->n repeat the last (so no lane
// computes on undefined values), and empties the queue.
static inline void setup_pending(pending_triangles_t* p, __global float* T, float origin_x,
                                 float origin_y, uint kernel_w, uint kernel_h, uint band_rows,
                                 uint* slivers, uint* shapely) {
  if (p->n == 0) return;
  triangles16_t v;
  for (int c = 0; c < 3; ++c) {
    for (int k = p->n; k < 16; ++k) {
      p->x[c][k] = p->x[c][p->n - 1];
      p->y[c][k] = p->y[c][p->n - 1];
      p->d[c][k] = p->d[c][p->n - 1];
      p->q[c][k] = p->q[c][p->n - 1];
      p->id[c][k] = p->id[c][p->n - 1];
    }
    v.x[c] = vload16(0, p->x[c]);
    v.y[c] = vload16(0, p->y[c]);
    v.d[c] = vload16(0, p->d[c]);
    v.q[c] = vload16(0, p->q[c]);
    v.id[c] = vload16(0, p->id[c]);
  }
  setup_triangles16(T, p->slot, p->n, &v, origin_x, origin_y, kernel_w, kernel_h, band_rows,
                    slivers, shapely);
  p->n = 0;
}

// Queues the triangle for record `slot` (corners: vertex ids, window x, y, depth, 1/w), setting up
// the queue when it is full.
static inline void queue_triangle(pending_triangles_t* p, int slot, const int* id, const float* x,
                                  const float* y, const float* d, const float* q, __global float* T,
                                  float origin_x, float origin_y, uint kernel_w, uint kernel_h,
                                  uint band_rows, uint* slivers, uint* shapely) {
  const int k = p->n++;
  p->slot[k] = slot;
  for (int c = 0; c < 3; ++c) {
    p->x[c][k] = x[c];
    p->y[c][k] = y[c];
    p->d[c][k] = d[c];
    p->q[c][k] = q[c];
    p->id[c][k] = id[c];
  }
  if (p->n == 16)
    setup_pending(p, T, origin_x, origin_y, kernel_w, kernel_h, band_rows, slivers, shapely);
}

// A slot no triangle uses: invalid, empty y-range and pixel box, zero edges.
static inline void empty_slot(__global float* T, int t) {
  __global float* R = T + t * TRI_STRIDE;
  for (int k = 0; k < TRI_STRIDE; ++k) R[k] = 0.0f;
  R[T_YMIN] = INFINITY;
  R[T_YMAX] = -INFINITY;
  vstore4((int4)(1, 0, 1, 0), 0, (__global int*)R + T_BOX);
  __global float* SA = T + NT * TRI_STRIDE;
  for (int e = 0; e < 3; ++e)
    for (int a = 0; a <= E_BITS; ++a) SA[a * NE_PAD + 3 * t + e] = 0.0f;
}

// Triangles crossing the viewport edge, as llvmpipe's clip stage draws them (Mesa 22.3,
// draw_pipe_clip.c; with a depth buffer bound it has no guard band). A vertex's clip mask is
// draw_llvm.c's: bit k set when it lies outside plane k of draw's order x <= w, x >= -w, y <= w,
// y >= -w. A triangle with every vertex outside one plane is culled; one with a vertex outside
// any is clipped, plane by plane in that order for the planes its vertices' masks name, by
// Sutherland-Hodgman on the clip coordinates: distances dot4(clip, plane), a new vertex
// out + t (in - out) with t = dp_out / (dp_out - dp_in) (the same whichever way an edge is walked,
// so both triangles sharing a clipped edge make the same vertex), its window coordinates in C
// without FMA, pos * (1/w) * scale + translate. The polygon is drawn as the fan (p[i-1], p[i],
// p[0]) (GL's provoking vertex, the last), into the triangle's slots in order.
typedef struct {
  float4 c;         /* clip coordinates */
  float x, y, d, q; /* window x, y, depth, 1/w */
  int id;           /* grid vertices 0..NV-1; a triangle's new vertices NV + 8 t0 + k */
} clip_vertex_t;

static inline uint clip_mask(float4 c) {
  return (c.x > c.w ? 1u : 0u) | (0.0f > c.x + c.w ? 2u : 0u) | (c.y > c.w ? 4u : 0u) |
         (0.0f > c.y + c.w ? 8u : 0u);
}

static inline float clip_dist(float4 c, int k) {
  const float4 p = k == 0   ? (float4)(-1.0f, 0.0f, 0.0f, 1.0f)
                   : k == 1 ? (float4)(1.0f, 0.0f, 0.0f, 1.0f)
                   : k == 2 ? (float4)(0.0f, -1.0f, 0.0f, 1.0f)
                            : (float4)(0.0f, 1.0f, 0.0f, 1.0f);
  return ((c.x * p.x + c.y * p.y) + c.z * p.z) + c.w * p.w;
}

// Clips grid triangle t0 (its vertices in tri[0..2], mask the union of their clip masks) and
// queues its fan for records first, first + 1, ...; returns how many it takes.
static inline int clip_fan(__global float* T, int t0, int first, const clip_vertex_t* tri,
                           uint mask, float half_w, float half_h, float origin_x, float origin_y,
                           uint kernel_w, uint kernel_h, uint band_rows, int depth_gl,
                           int snap_bits, pending_triangles_t* pending, uint* slivers,
                           uint* shapely) {
  clip_vertex_t a[9], b[9];
  clip_vertex_t* in = a;
  clip_vertex_t* out = b;
  for (int k = 0; k < 3; ++k) in[k] = tri[k];
  int n = 3, next_id = NV + 8 * t0;
  for (int p = 0; p < 4 && n >= 3; ++p) {
    if (!((mask >> p) & 1u)) continue;
    in[n] = in[0];
    clip_vertex_t prev = in[0];
    float dp_prev = clip_dist(prev.c, p);
    if (!isfinite(dp_prev)) {
      *shapely = 0u; /* the triangle is dropped: its pixels may be uncovered */
      return 0;
    }
    int m = 0;
    for (int i = 1; i <= n; ++i) {
      const clip_vertex_t cur = in[i];
      const float dp = clip_dist(cur.c, p);
      if (!isfinite(dp)) {
        *shapely = 0u;
        return 0;
      }
      int cross;
      if (dp_prev >= 0.0f) {
        out[m++] = prev;
        cross = dp < 0.0f;
      } else {
        cross = !(dp < 0.0f);
      }
      if (cross) {
        const int leaving = dp < 0.0f;
        const clip_vertex_t o = leaving ? cur : prev, v_in = leaving ? prev : cur;
        const float t = leaving ? dp / (dp - dp_prev) : dp_prev / (dp_prev - dp);
        clip_vertex_t nv;
        nv.c = o.c + t * (v_in.c - o.c);
        const float oow = 1.0f / nv.c.w;
        nv.x = snap_window_bits(nv.c.x * oow * half_w + half_w, snap_bits);
        nv.y = snap_window_bits(nv.c.y * oow * half_h + half_h, snap_bits);
        nv.d = depth_gl ? nv.c.z * oow * 0.5f + 0.5f : nv.c.z * oow * 1.0f + 0.0f;
        nv.q = oow;
        nv.id = next_id++;
        out[m++] = nv;
      }
      prev = cur;
      dp_prev = dp;
    }
    n = m;
    clip_vertex_t* swap = in;
    in = out;
    out = swap;
  }
  if (n < 3) return 0;
  for (int i = 2; i < n; ++i) {
    const clip_vertex_t* f[3] = {&in[i - 1], &in[i], &in[0]};
    const int id[3] = {f[0]->id, f[1]->id, f[2]->id};
    const float x[3] = {f[0]->x, f[1]->x, f[2]->x}, y[3] = {f[0]->y, f[1]->y, f[2]->y};
    const float d[3] = {f[0]->d, f[1]->d, f[2]->d}, q[3] = {f[0]->q, f[1]->q, f[2]->q};
    queue_triangle(pending, first + i - 2, id, x, y, d, q, T, origin_x, origin_y, kernel_w,
                   kernel_h, band_rows, slivers, shapely);
  }
  return n - 2;
}
#endif

// The vertex stage of 16 grid vertices (index j (GRID + 1) + i: column i, row j), a lane each: clip
// coordinates, then the divide and the window transform to window x, y, depth and 1/w, and
// whether any of those (depth only where the set-up interpolates it) is not finite.
typedef struct {
  vec4x16_t clip;
  float16 x, y, d, q;
  int16 nonfinite;
} vertices16_t;

static inline vertices16_t vertex_stage16(__global const float* P, __global const float* M,
                                          int16 vertex, float half_w, float half_h) {
  /* the probe constants this stage alone reads (kernels/mts_layout.h) */
  const int depth_gl = P[C_DEPTH_GL] != 0.0f;
  const uint forms = (uint)P[C_FORMS];
  const int snap_bits = (int)P[C_SNAP_BITS];
  const int vertex_fma = (forms & F_VERTEX_FMA) != 0u;
  vec4x16_t obj;
  obj.x = convert_float16(vertex % (GRID + 1)) / (float)GRID - 0.5f;
  obj.y = convert_float16(vertex / (GRID + 1)) / (float)GRID - 0.5f;
  obj.z = (float16)0.0f;
  obj.w = (float16)1.0f;
  vertices16_t v;
  v.clip = mat_vec16(M, obj, vertex_fma, 1);
  if (!(forms & F_COMPOSE_PREMULT)) v.clip = mat_vec16(P, v.clip, vertex_fma, 0);
  const vec4x16_t c = v.clip;
#if DEPTH_FROM == 1
  {
    const float16 t = shader_log16(P[C_LOGK] * c.w + 1.0f);
    v.clip.z = depth_gl ? ((2.0f * t) / P[C_LOGL] - 1.0f) * c.w : (t / P[C_LOGL]) * c.w;
  }
#endif
  const float16 cz = v.clip.z;
  const float16 inv_w = 1.0f / c.w;
  float16 nx, ny, nz;
  if (forms & F_DIVIDE_EXACT) {
    nx = c.x / c.w;
    ny = c.y / c.w;
    nz = cz / c.w;
  } else {
    nx = c.x * inv_w;
    ny = c.y * inv_w;
    nz = cz * inv_w;
  }
  if (forms & F_VIEWPORT_FMA) {
    v.x = fma(nx, (float16)half_w, (float16)half_w);
    v.y = fma(ny, (float16)half_h, (float16)half_h);
    v.d = depth_gl ? fma(nz, (float16)0.5f, (float16)0.5f) : nz;
  } else {
    v.x = nx * half_w + half_w;
    v.y = ny * half_h + half_h;
    v.d = depth_gl ? nz * 0.5f + 0.5f : nz;
  }
  if (snap_bits > 0) { /* lane by lane: the one snapping rule, shared with the host */
    float x[16], y[16];
    vstore16(v.x, 0, x);
    vstore16(v.y, 0, y);
    for (int k = 0; k < 16; ++k) {
      x[k] = snap_window_bits(x[k], snap_bits);
      y[k] = snap_window_bits(y[k], snap_bits);
    }
    v.x = vload16(0, x);
    v.y = vload16(0, y);
  }
  v.q = inv_w;
  v.nonfinite = !isfinite(v.x) | !isfinite(v.y) | !isfinite(v.q);
#if DEPTH_FROM != 2
  v.nonfinite |= !isfinite(v.d);
#endif
  return v;
}

// The vertices (a, b, c) of triangles t of the plane grid, a lane each: quad t / 2, split along the
// diagonal from its lower-left corner a to c (flip 0: triangles (a, b, c) and (a, c, d), the
// measured planes), or from b to d (flip 1: (a, b, d) and (b, c, d), the same quad tessellated the
// other way: the coplanar overlay of depth bias, kernels/bias.cl). Vertex 0 anchors the plane
// equation.
static inline void triangle_vertices16(int16 t, int flip, int16* a, int16* b, int16* c) {
  const int16 quad = t >> 1, qi = quad % GRID, qj = quad / GRID;
  const int16 va = qj * (GRID + 1) + qi, vb = va + 1, vc = va + GRID + 2, vd = va + GRID + 1;
  const int16 odd = (t & 1) != 0;
  if (flip) { /* (a, b, d) and (b, c, d) */
    *a = select(va, vb, odd);
    *b = select(vb, vc, odd);
  } else { /* (a, b, c) and (a, c, d) */
    *a = va;
    *b = select(vb, vc, odd);
  }
  *c = flip ? vd : select(vc, vd, odd);
}

// Vertex stage, divide, window transform and triangle set-up of one plane in one frame into
// record T and flags *vflag.
static inline void setup_plane(__global const float* P, __global const float* M, float half_w,
                               float half_h, float origin_x, float origin_y, uint kernel_w,
                               uint kernel_h, uint band_rows, __global float* T,
                               __global uint* vflag, int flip) {
  float xw[NV_PAD], yw[NV_PAD], dw[NV_PAD], qw[NV_PAD];
#if CLIP_SLOTS > 1
  const int depth_gl = P[C_DEPTH_GL] != 0.0f;
  const int snap_bits = (int)P[C_SNAP_BITS];
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
      lo = fmin(lo, T[t * TRI_STRIDE + T_YMIN]);
      hi = fmax(hi, T[t * TRI_STRIDE + T_YMAX]);
      const int4 box = vload4(0, (__global const int*)T + t * TRI_STRIDE + T_BOX);
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
  __global uint* SA = (__global uint*)T + NT * TRI_STRIDE;
  for (int k = NE; k < NE_PAD; ++k)
    for (int a = 0; a <= E_BITS; ++a) SA[a * NE_PAD + k] = SA[a * NE_PAD];
}
