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
// A vertex near a pixel centre only spoils the certificate for the one pixel near it, so such
// bands are named in the flags (bit V_BAND_SHIFT + band, bands of band_rows rows, the first 24
// bands; a vertex in a later one clears V_COVERS) and the rest stay certified; and the pixel's
// row is written to bad_row[vertex] (-1 for a vertex near no pixel centre) for row_covered.
static inline uint covers_kernel(const float* xw, const float* yw, float ox, float oy, uint kw,
                                 uint kh, uint band_rows, uint sliver_bands, int* bad_row) {
  uint bad_bands = sliver_bands;
  const float x0 = ox, x1 = ox + (float)kw, y0 = oy, y1 = oy + (float)kh; /* pixel area */
  for (int v = 0; v < NV; ++v) bad_row[v] = -1;
  for (int v = 0; v < NV; ++v) {
    if (!(fabs(xw[v]) <= 8192.0f && fabs(yw[v]) <= 8192.0f)) return 0u;
    if (xw[v] < x0 - 1.0f || xw[v] > x1 + 1.0f || yw[v] < y0 - 1.0f || yw[v] > y1 + 1.0f) continue;
    const float fx = xw[v] - ox - 0.5f, fy = yw[v] - oy - 0.5f;
    if (fabs(fx - rint(fx)) < 0.125f && fabs(fy - rint(fy)) < 0.125f) {
      bad_row[v] = clamp((int)rint(fy), 0, (int)kh - 1);
      const uint band = (uint)bad_row[v] / band_rows;
      if (band >= V_MAX_BANDS) return 0u;
      bad_bands |= 1u << band;
    }
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
  return V_COVERS | (sliver_bands ? V_SLIVERS : 0u) | (bad_bands << V_BAND_SHIFT);
}

// The vertices of triangle t of the plane grid: quad t / 2, split along the diagonal from its
// lower-left corner a to c (flip 0: triangles (a, b, c) and (a, c, d), the measured planes), or
// from b to d (flip 1: (a, b, d) and (b, c, d), the same quad tessellated the other way: the
// coplanar overlay of depth bias, kernels/bias.cl). Vertex 0 anchors the plane equation.
static inline int3 triangle_vertices(int t, int flip) {
  const int quad = t >> 1, qi = quad % GRID, qj = quad / GRID;
  const int a = qj * (GRID + 1) + qi, b = a + 1, c = a + GRID + 2, d = a + GRID + 1;
  if (flip) return (t & 1) ? (int3)(b, c, d) : (int3)(a, b, d);
  return (t & 1) ? (int3)(a, c, d) : (int3)(a, b, c);
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

#if PLANE_FORM != 0
// The depth and 1/w planes of a record referred to the framebuffer origin, as llvmpipe and softpipe
// refer them: the anchor vertex's value minus the gradients times its offset (xc, yc) from the
// origin pixel's centre; evaluated at integer pixel coordinates, so x0 = y0 = 1/2.
static inline void store_origin_planes(__global float* R, float xc, float yc, float d0, float dzdx,
                                       float dzdy, float q0, float dqdx, float dqdy) {
  R[T_X0] = 0.5f;
  R[T_Y0] = 0.5f;
  R[T_D0] = d0 - (dzdx * xc + dzdy * yc);
  R[T_DZDX] = dzdx;
  R[T_DZDY] = dzdy;
  R[T_Q0] = q0 - (dqdx * xc + dqdy * yc);
  R[T_DQDX] = dqdx;
  R[T_DQDY] = dqdy;
}
#endif

// One triangle record (slot t of plane T) from its vertices: ids (an edge is evaluated from its
// lower-id vertex, so two triangles sharing it compute the same value), window x, y, depth and
// 1/w. Edges, orientation and ownership bits, the depth and 1/w planes in the set-up's form, the
// y-range, the largest |depth|, the edge arrays and the pixel box. A degenerate triangle, or one
// with an angle below ~6 degrees, is a sliver (mark_sliver).
#if MTS_NV(GRID) + 8 * NT0 > (1 << 15) /* the grid's vertices, then 8 per clipped triangle */
#error "vertex ids need more than the 15 bits the edge arrays keep for each (E_ID_SHIFT)"
#endif
static inline void setup_triangle(__global float* T, int t, const int* id, const float* x,
                                  const float* y, const float* d, const float* q, float origin_x,
                                  float origin_y, uint kernel_w, uint kernel_h, uint band_rows,
                                  uint* slivers, uint* shapely) {
  __global float* R = T + t * TRI_STRIDE;
  /* the edges stay in registers: written to the record and to the edge arrays (SA) from here,
   * never read back */
  float ex[3], ey[3], edx[3], edy[3];
  uint bits = 0u;
  for (int e = 0; e < 3; ++e) {
    const int a = e, b = (e + 1) % 3;
    const int lo = id[a] < id[b] ? a : b, hi = id[a] < id[b] ? b : a;
    ex[e] = x[lo];
    ey[e] = y[lo];
    edx[e] = x[hi] - x[lo];
    edy[e] = y[hi] - y[lo];
    R[T_EDGES + 4 * e + 0] = ex[e];
    R[T_EDGES + 4 * e + 1] = ey[e];
    R[T_EDGES + 4 * e + 2] = edx[e];
    R[T_EDGES + 4 * e + 3] = edy[e];
    if (id[a] > id[b]) bits |= 1u << e;
  }
  // orientation: edge 0 evaluated at vertex 2
  float orient = edx[0] * (y[2] - ey[0]) - edy[0] * (x[2] - ex[0]);
  if (bits & 1u) orient = -orient;
  if (orient < 0.0f) bits ^= 7u;
  const int valid = orient != 0.0f && isfinite(orient);
  for (int e = 0; e < 3; ++e) {
    const float s = (bits >> e) & 1u ? -1.0f : 1.0f;
    const float dx = s * edx[e], dy = s * edy[e];
    if (dy < 0.0f || (dy == 0.0f && dx < 0.0f)) bits |= 8u << e;
  }
  if (valid) bits |= 64u;
  const float e1x = x[1] - x[0], e1y = y[1] - y[0];
  const float e2x = x[2] - x[0], e2y = y[2] - y[0];
  const float det = e1x * e2y - e2x * e1y;
  {
    const float e3x = x[2] - x[1], e3y = y[2] - y[1];
    const float longest =
        fmax(fmax(e1x * e1x + e1y * e1y, e2x * e2x + e2y * e2y), e3x * e3x + e3y * e3y);
    /* |det| = l_j l_k sin(angle) >= longest * sin(angle) */
    if (!valid || !(fabs(det) >= 0.1f * longest))
      mark_sliver(x, y, det, origin_x, origin_y, kernel_w, kernel_h, band_rows, slivers, shapely);
  }
#if PLANE_FORM == 1
  {
    /* llvmpipe (lp_state_setup.c): the vertices as it passes them, (v1, v0, v2) when the area
     * is negative; gradients as differences times 1/area; the value at the framebuffer origin.
     * Evaluated at integer pixel coordinates (px - 0.5, py - 0.5): T_X0 = T_Y0 = 0.5. */
    const int j0 = det < 0.0f ? 1 : 0, j1 = det < 0.0f ? 0 : 1, j2 = 2;
    const float x0c = x[j0] - 0.5f, y0c = y[j0] - 0.5f;
    const float dx01 = x[j0] - x[j1], dy01 = y[j0] - y[j1];
    const float dx20 = x[j2] - x[j0], dy20 = y[j2] - y[j0];
    const float ooa = 1.0f / (dx01 * dy20 - dx20 * dy01);
    const float dy20o = dy20 * ooa, dy01o = dy01 * ooa, dx20o = dx20 * ooa, dx01o = dx01 * ooa;
    const float dz01 = d[j0] - d[j1], dz20 = d[j2] - d[j0];
    const float dzdx = dz01 * dy20o - dz20 * dy01o, dzdy = dz20 * dx01o - dz01 * dx20o;
    const float dq01 = q[j0] - q[j1], dq20 = q[j2] - q[j0];
    const float dqdx = dq01 * dy20o - dq20 * dy01o, dqdy = dq20 * dx01o - dq01 * dx20o;
    store_origin_planes(R, x0c, y0c, d[j0], dzdx, dzdy, q[j0], dqdx, dqdy);
  }
#elif PLANE_FORM == 2
  {
    /* softpipe (sp_setup.c): vertices sorted by y as setup_sort_vertices does (ties keep its
     * order), ebot = vmid - vmin, emaj = vmax - vmin, gradients times 1/area, the value at the
     * framebuffer origin from vmin (tri_linear_coeff). Evaluated per 2x2 quad (row_plane). */
    int lo, mid, hi;
    if (y[0] <= y[1]) {
      if (y[1] <= y[2]) {
        lo = 0, mid = 1, hi = 2;
      } else if (y[2] <= y[0]) {
        lo = 2, mid = 0, hi = 1;
      } else {
        lo = 0, mid = 2, hi = 1;
      }
    } else {
      if (y[0] <= y[2]) {
        lo = 1, mid = 0, hi = 2;
      } else if (y[2] <= y[1]) {
        lo = 2, mid = 1, hi = 0;
      } else {
        lo = 1, mid = 2, hi = 0;
      }
    }
    const float bot_dx = x[mid] - x[lo], bot_dy = y[mid] - y[lo];
    const float maj_dx = x[hi] - x[lo], maj_dy = y[hi] - y[lo];
    const float ooa = 1.0f / (maj_dx * bot_dy - bot_dx * maj_dy);
    const float xc = x[lo] - 0.5f, yc = y[lo] - 0.5f;
    const float botdz = d[mid] - d[lo], majdz = d[hi] - d[lo];
    const float dzdx = (bot_dy * majdz - botdz * maj_dy) * ooa;
    const float dzdy = (maj_dx * botdz - majdz * bot_dx) * ooa;
    const float botdq = q[mid] - q[lo], majdq = q[hi] - q[lo];
    const float dqdx = (bot_dy * majdq - botdq * maj_dy) * ooa;
    const float dqdy = (maj_dx * botdq - majdq * bot_dx) * ooa;
    store_origin_planes(R, xc, yc, d[lo], dzdx, dzdy, q[lo], dqdx, dqdy);
  }
#else
  const float e1d = d[1] - d[0], e2d = d[2] - d[0];
  const float e1q = q[1] - q[0], e2q = q[2] - q[0];
  R[T_X0] = x[0];
  R[T_Y0] = y[0];
  R[T_D0] = d[0];
  R[T_DZDX] = (e1d * e2y - e2d * e1y) / det;
  R[T_DZDY] = (e2d * e1x - e1d * e2x) / det;
  R[T_Q0] = q[0];
  R[T_DQDX] = (e1q * e2y - e2q * e1y) / det;
  R[T_DQDY] = (e2q * e1x - e1q * e2x) / det;
#endif
  R[T_YMIN] = fmin(fmin(y[0], y[1]), y[2]);
  R[T_YMAX] = fmax(fmax(y[0], y[1]), y[2]);
  R[T_ZMAX] = fmax(fmax(fabs(d[0]), fabs(d[1])), fabs(d[2]));
  __global float* SA = T + NT * TRI_STRIDE;
  for (int e = 0; e < 3; ++e) {
    const int k = 3 * t + e;
    const float dxdy = edx[e] / edy[e];
    R[T_DXDY + e] = dxdy;
    SA[E_AX * NE_PAD + k] = ex[e];
    SA[E_AY * NE_PAD + k] = ey[e];
    SA[E_DX * NE_PAD + k] = edx[e];
    SA[E_DY * NE_PAD + k] = edy[e];
    SA[E_DXDY * NE_PAD + k] = dxdy;
    ((__global uint*)SA)[E_BITS * NE_PAD + k] =
        ((bits >> e) & 1u) | (((bits >> (3 + e)) & 1u) << 1) | ((uint)id[e] << E_ID_SHIFT) |
        ((uint)id[(e + 1) % 3] << (E_ID_SHIFT + 15));
  }
  ((__global uint*)R)[T_BITS] = bits;
  vstore4(kernel_pixel_box(R, origin_x, origin_y, (int)kernel_w, (int)kernel_h), 0,
          (__global int*)R + T_BOX);
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

#if CLIP_SLOTS > 1
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
// sets up its fan in records first, first + 1, ...; returns how many it filled.
static inline int clip_fan(__global float* T, int t0, int first, const clip_vertex_t* tri,
                           uint mask, float half_w, float half_h, float origin_x, float origin_y,
                           uint kernel_w, uint kernel_h, uint band_rows, int depth_gl,
                           int snap_bits, uint* slivers, uint* shapely) {
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
    setup_triangle(T, first + i - 2, id, x, y, d, q, origin_x, origin_y, kernel_w, kernel_h,
                   band_rows, slivers, shapely);
  }
  return n - 2;
}
#endif

// Vertex stage, divide, window transform and triangle set-up of one plane in one frame into
// record T and flags *vflag.
static inline void setup_plane(__global const float* P, __global const float* M, float half_w,
                               float half_h, float origin_x, float origin_y, uint kernel_w,
                               uint kernel_h, uint band_rows, __global float* T,
                               __global uint* vflag, int flip) {
  float xw[NV], yw[NV], dw[NV], qw[NV];
  /* the probe constants this stage alone reads (kernels/mts_layout.h) */
  const int depth_gl = P[C_DEPTH_GL] != 0.0f;
  const uint forms = (uint)P[C_FORMS];
  const int snap_bits = (int)P[C_SNAP_BITS];
  const int divide_exact = (forms & F_DIVIDE_EXACT) != 0u;
  const int premultiplied = (forms & F_COMPOSE_PREMULT) != 0u;
  const int viewport_fma = (forms & F_VIEWPORT_FMA) != 0u;
  const int vertex_fma = (forms & F_VERTEX_FMA) != 0u;
#if CLIP_SLOTS > 1
  float4 cv[NV]; /* clip coordinates, for the clip stage */
#endif
  uint nonfinite = 0u;
  for (int j = 0; j <= GRID; ++j) {
    for (int i = 0; i <= GRID; ++i) {
      const int v = j * (GRID + 1) + i;
      const float4 obj =
          (float4)((float)i / (float)GRID - 0.5f, (float)j / (float)GRID - 0.5f, 0.0f, 1.0f);
      float4 clip = premultiplied ? obj_vec(M, obj, vertex_fma)
                                  : mat_vec(P, obj_vec(M, obj, vertex_fma), vertex_fma);
#if DEPTH_FROM == 1
      {
        const float t = shader_log(P[C_LOGK] * clip.w + 1.0f);
        clip.z = depth_gl ? ((2.0f * t) / P[C_LOGL] - 1.0f) * clip.w : (t / P[C_LOGL]) * clip.w;
      }
#endif
      const float inv_w = 1.0f / clip.w;
      const float3 ndc = divide_exact ? (float3)(clip.x / clip.w, clip.y / clip.w, clip.z / clip.w)
                                      : (float3)(clip.x * inv_w, clip.y * inv_w, clip.z * inv_w);
      if (viewport_fma) {
        xw[v] = fma(ndc.x, half_w, half_w);
        yw[v] = fma(ndc.y, half_h, half_h);
        dw[v] = depth_gl ? fma(ndc.z, 0.5f, 0.5f) : ndc.z;
      } else {
        xw[v] = ndc.x * half_w + half_w;
        yw[v] = ndc.y * half_h + half_h;
        dw[v] = depth_gl ? ndc.z * 0.5f + 0.5f : ndc.z;
      }
      xw[v] = snap_window_bits(xw[v], snap_bits);
      yw[v] = snap_window_bits(yw[v], snap_bits);
      qw[v] = inv_w;
#if CLIP_SLOTS > 1
      cv[v] = clip;
#endif
      if (!isfinite(xw[v]) || !isfinite(yw[v]) || !isfinite(qw[v])) nonfinite = 1u;
#if DEPTH_FROM != 2
      if (!isfinite(dw[v])) nonfinite = 1u;
#endif
    }
  }
  uint shapely = 1u; /* covers_kernel's argument holds at least outside the sliver bands */
  uint slivers = 0u; /* bands of kernel rows near a sliver triangle */
  int next = 0;      /* the next free record of the current quad row */
  for (int t0 = 0; t0 < NT0; ++t0) {
    const int qj = t0 / (2 * GRID);
    if (t0 % (2 * GRID) == 0) next = Q_SLOTS * qj;
    const int3 tv = triangle_vertices(t0, flip);
    const int vi[3] = {tv.x, tv.y, tv.z};
#if CLIP_SLOTS > 1
    const uint m0 = clip_mask(cv[vi[0]]), m1 = clip_mask(cv[vi[1]]), m2 = clip_mask(cv[vi[2]]);
    if (!(m0 | m1 | m2)) {
#endif
      const float x[3] = {xw[vi[0]], xw[vi[1]], xw[vi[2]]};
      const float y[3] = {yw[vi[0]], yw[vi[1]], yw[vi[2]]};
      const float d[3] = {dw[vi[0]], dw[vi[1]], dw[vi[2]]};
      const float q[3] = {qw[vi[0]], qw[vi[1]], qw[vi[2]]};
      setup_triangle(T, next++, vi, x, y, d, q, origin_x, origin_y, kernel_w, kernel_h, band_rows,
                     &slivers, &shapely);
#if CLIP_SLOTS > 1
    } else if (!(m0 & m1 & m2)) { /* all outside one plane: culled */
      clip_vertex_t poly[3];
      for (int k = 0; k < 3; ++k) {
        const int v = vi[k];
        poly[k] = (clip_vertex_t){cv[v], xw[v], yw[v], dw[v], qw[v], v};
      }
      next += clip_fan(T, t0, next, poly, m0 | m1 | m2, half_w, half_h, origin_x, origin_y,
                       kernel_w, kernel_h, band_rows, depth_gl, snap_bits, &slivers, &shapely);
    }
#endif
    if (t0 % (2 * GRID) == 2 * GRID - 1) {
      ((__global int*)T)[Q_USED + qj] = next - Q_SLOTS * qj;
      for (int k = next; k < Q_SLOTS * (qj + 1); ++k) empty_slot(T, k);
    }
  }
  const int certify = !nonfinite && shapely; /* covers_kernel's preconditions */
  int bad_row[NV];
  *vflag = nonfinite | (certify ? covers_kernel(xw, yw, origin_x, origin_y, kernel_w, kernel_h,
                                                band_rows, slivers, bad_row)
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
