// Vertex set-up of a plane, and the certificate that it covers the kernel.

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
                                 uint kh, uint band_rows, int* bad_row) {
  uint bad_bands = 0u;
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
  return V_COVERS | (bad_bands << V_BAND_SHIFT);
}

// Every pixel of the band (or of the whole kernel) is owned by exactly one triangle.
static inline int band_covered(uint vf, uint band) {
  return (vf & V_COVERS) && (band >= V_MAX_BANDS || !((vf >> (V_BAND_SHIFT + band)) & 1u));
}

// Every pixel of kernel row `row` of plane T (flags vf) is owned by exactly one triangle: the
// certificate of band_covered, down to the one row a vertex near a pixel centre spoils.
static inline int row_covered(__global const float* T, uint vf, int row) {
  __global const int16* bad = (__global const int16*)((__global const int*)T + V_BAD_ROW);
  int16 hit = (int16)0;
  for (int k = 0; k < NV_PAD / 16; ++k) hit |= bad[k] == (int16)row;
  return (vf & V_COVERS) && !any16(hit);
}

// The kernel pixels (column i0..i1, row j0..j1) that triangle R may own: those whose centre lies
// within its bounding box widened by one pixel (an edge test can pass only within its rounding
// error outside the exact triangle). Empty when i0 > i1 or j0 > j1.
static inline int4 kernel_pixel_box(__global const float* R, float ox, float oy, int W, int H) {
  float xmin = INFINITY, xmax = -INFINITY;
  for (int e = 0; e < 3; ++e) {
    const float ax = R[T_EDGES + 4 * e], bx = ax + R[T_EDGES + 4 * e + 2];
    xmin = fmin(xmin, fmin(ax, bx));
    xmax = fmax(xmax, fmax(ax, bx));
  }
  return (int4)(max((int)ceil(fmax(xmin - 1.0f - ox - 0.5f, -1.0f)), 0),
                min((int)floor(fmin(xmax + 1.0f - ox - 0.5f, (float)W)), W - 1),
                max((int)ceil(fmax(R[T_YMIN] - 1.0f - oy - 0.5f, -1.0f)), 0),
                min((int)floor(fmin(R[T_YMAX] + 1.0f - oy - 0.5f, (float)H)), H - 1));
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

// Vertex stage, divide, window transform and triangle set-up of one plane in one frame into
// record T and flags *vflag; the vertices' window depths are left in dw.
static inline void setup_plane(__global const float* P, __global const float* M, float half_w,
                               float half_h, float origin_x, float origin_y, uint kernel_w,
                               uint kernel_h, uint band_rows, __global float* T,
                               __global uint* vflag, int flip, float* dw) {
  float xw[NV], yw[NV], qw[NV];
  uint nonfinite = 0u;
  for (int j = 0; j <= GRID; ++j) {
    for (int i = 0; i <= GRID; ++i) {
      const int v = j * (GRID + 1) + i;
      const float4 obj =
          (float4)((float)i / (float)GRID - 0.5f, (float)j / (float)GRID - 0.5f, 0.0f, 1.0f);
#if COMPOSE_PREMULT
      float4 clip = mat_vec(M, obj);
#else
      float4 clip = mat_vec(P, mat_vec(M, obj));
#endif
#if DEPTH_FROM == 1
      {
        const float t = shader_log(P[C_LOGK] * clip.w + 1.0f);
#if RANGE_GL
        clip.z = ((2.0f * t) / P[C_LOGL] - 1.0f) * clip.w;
#else
        clip.z = (t / P[C_LOGL]) * clip.w;
#endif
      }
#endif
      const float inv_w = 1.0f / clip.w;
#if DIVIDE_EXACT
      const float3 ndc = (float3)(clip.x / clip.w, clip.y / clip.w, clip.z / clip.w);
#else
      const float3 ndc = (float3)(clip.x * inv_w, clip.y * inv_w, clip.z * inv_w);
#endif
#if VIEWPORT_FMA
      xw[v] = fma(ndc.x, half_w, half_w);
      yw[v] = fma(ndc.y, half_h, half_h);
#if RANGE_GL
      dw[v] = fma(ndc.z, 0.5f, 0.5f);
#else
      dw[v] = ndc.z;
#endif
#else
      xw[v] = ndc.x * half_w + half_w;
      yw[v] = ndc.y * half_h + half_h;
#if RANGE_GL
      dw[v] = ndc.z * 0.5f + 0.5f;
#else
      dw[v] = ndc.z;
#endif
#endif
      qw[v] = inv_w;
      if (!isfinite(xw[v]) || !isfinite(yw[v]) || !isfinite(qw[v])) nonfinite = 1u;
#if DEPTH_FROM != 2
      if (!isfinite(dw[v])) nonfinite = 1u;
#endif
    }
  }
  uint shapely = 1u; /* every triangle non-degenerate, no angle below ~6 degrees */
  for (int t = 0; t < NT; ++t) {
    const int3 tv = triangle_vertices(t, flip);
    const int i0 = tv.x, i1 = tv.y, i2 = tv.z;
    const int vi[3] = {i0, i1, i2};
    __global float* R = T + t * TRI_STRIDE;
    /* the edges stay in registers: written to the record and to the edge arrays (SA) from here,
     * never read back */
    float ex[3], ey[3], edx[3], edy[3];
    uint bits = 0u;
    for (int e = 0; e < 3; ++e) {
      const int va = vi[e], vb = vi[(e + 1) % 3];
      const int lo = min(va, vb), hi = max(va, vb);
      ex[e] = xw[lo];
      ey[e] = yw[lo];
      edx[e] = xw[hi] - xw[lo];
      edy[e] = yw[hi] - yw[lo];
      R[T_EDGES + 4 * e + 0] = ex[e];
      R[T_EDGES + 4 * e + 1] = ey[e];
      R[T_EDGES + 4 * e + 2] = edx[e];
      R[T_EDGES + 4 * e + 3] = edy[e];
      if (va > vb) bits |= 1u << e;
    }
    // orientation: edge 0 evaluated at vertex 2
    float orient = edx[0] * (yw[i2] - ey[0]) - edy[0] * (xw[i2] - ex[0]);
    if (bits & 1u) orient = -orient;
    if (orient < 0.0f) bits ^= 7u;
    const int valid = orient != 0.0f && isfinite(orient);
    for (int e = 0; e < 3; ++e) {
      const float s = (bits >> e) & 1u ? -1.0f : 1.0f;
      const float dx = s * edx[e], dy = s * edy[e];
      if (dy < 0.0f || (dy == 0.0f && dx < 0.0f)) bits |= 8u << e;
    }
    if (valid)
      bits |= 64u;
    else
      shapely = 0u;
    const float e1x = xw[i1] - xw[i0], e1y = yw[i1] - yw[i0];
    const float e2x = xw[i2] - xw[i0], e2y = yw[i2] - yw[i0];
    const float det = e1x * e2y - e2x * e1y;
    {
      const float e3x = xw[i2] - xw[i1], e3y = yw[i2] - yw[i1];
      const float longest =
          fmax(fmax(e1x * e1x + e1y * e1y, e2x * e2x + e2y * e2y), e3x * e3x + e3y * e3y);
      /* |det| = l_j l_k sin(angle) >= longest * sin(angle) */
      if (!(fabs(det) >= 0.1f * longest)) shapely = 0u;
    }
#if PLANE_FORM == 1
    {
      /* llvmpipe (lp_state_setup.c): the vertices as it passes them, (v1, v0, v2) when the area
       * is negative; gradients as differences times 1/area; the value at the framebuffer origin.
       * Evaluated at integer pixel coordinates (px - 0.5, py - 0.5): T_X0 = T_Y0 = 0.5. */
      const int j0 = det < 0.0f ? i1 : i0, j1 = det < 0.0f ? i0 : i1, j2 = i2;
      const float x0c = xw[j0] - 0.5f, y0c = yw[j0] - 0.5f;
      const float dx01 = xw[j0] - xw[j1], dy01 = yw[j0] - yw[j1];
      const float dx20 = xw[j2] - xw[j0], dy20 = yw[j2] - yw[j0];
      const float ooa = 1.0f / (dx01 * dy20 - dx20 * dy01);
      const float dy20o = dy20 * ooa, dy01o = dy01 * ooa, dx20o = dx20 * ooa, dx01o = dx01 * ooa;
      const float dz01 = dw[j0] - dw[j1], dz20 = dw[j2] - dw[j0];
      const float dzdx = dz01 * dy20o - dz20 * dy01o, dzdy = dz20 * dx01o - dz01 * dx20o;
      const float dq01 = qw[j0] - qw[j1], dq20 = qw[j2] - qw[j0];
      const float dqdx = dq01 * dy20o - dq20 * dy01o, dqdy = dq20 * dx01o - dq01 * dx20o;
      R[T_X0] = 0.5f;
      R[T_Y0] = 0.5f;
      R[T_D0] = dw[j0] - (dzdx * x0c + dzdy * y0c);
      R[T_DZDX] = dzdx;
      R[T_DZDY] = dzdy;
      R[T_Q0] = qw[j0] - (dqdx * x0c + dqdy * y0c);
      R[T_DQDX] = dqdx;
      R[T_DQDY] = dqdy;
    }
#else
    const float e1d = dw[i1] - dw[i0], e2d = dw[i2] - dw[i0];
    const float e1q = qw[i1] - qw[i0], e2q = qw[i2] - qw[i0];
    R[T_X0] = xw[i0];
    R[T_Y0] = yw[i0];
    R[T_D0] = dw[i0];
    R[T_DZDX] = (e1d * e2y - e2d * e1y) / det;
    R[T_DZDY] = (e2d * e1x - e1d * e2x) / det;
    R[T_Q0] = qw[i0];
    R[T_DQDX] = (e1q * e2y - e2q * e1y) / det;
    R[T_DQDY] = (e2q * e1x - e1q * e2x) / det;
#endif
    R[T_YMIN] = fmin(fmin(yw[i0], yw[i1]), yw[i2]);
    R[T_YMAX] = fmax(fmax(yw[i0], yw[i1]), yw[i2]);
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
          ((bits >> e) & 1u) | (((bits >> (3 + e)) & 1u) << 1);
    }
    ((__global uint*)R)[T_BITS] = bits;
    vstore4(kernel_pixel_box(R, origin_x, origin_y, (int)kernel_w, (int)kernel_h), 0,
            (__global int*)R + T_BOX);
  }
  const int certify = !nonfinite && shapely; /* covers_kernel's preconditions */
  int bad_row[NV];
  *vflag = nonfinite | (certify ? covers_kernel(xw, yw, origin_x, origin_y, kernel_w, kernel_h,
                                                band_rows, bad_row)
                                : 0u);
  for (int v = 0; v < NV_PAD; ++v)
    ((__global int*)T)[V_BAD_ROW + v] = v < NV && certify ? bad_row[v] : -1;
  for (int qj = 0; qj < GRID; ++qj) {
    float lo = INFINITY, hi = -INFINITY;
    for (int t = 2 * GRID * qj; t < 2 * GRID * (qj + 1); ++t) {
      lo = fmin(lo, T[t * TRI_STRIDE + T_YMIN]);
      hi = fmax(hi, T[t * TRI_STRIDE + T_YMAX]);
    }
    T[Q_YRANGE + 2 * qj] = lo;
    T[Q_YRANGE + 2 * qj + 1] = hi;
  }
  for (int v = 0; v < NV_PAD; ++v) {
    T[V_XW + v] = v < NV ? xw[v] : 0.0f;
    T[V_YW + v] = v < NV ? yw[v] : 0.0f;
  }
  /* the edge arrays' padding repeats triangle 0's edge 0 */
  __global uint* SA = (__global uint*)T + NT * TRI_STRIDE;
  for (int k = NE; k < NE_PAD; ++k)
    for (int a = 0; a <= E_BITS; ++a) SA[a * NE_PAD + k] = SA[a * NE_PAD];
}

// Global id: the plane's index in mats; it is written to tris and vflags at first_plane + id, and
// its probe constants are those of (first_plane + id) / per_probe.
__kernel void mts_setup(__global const float* restrict probes, __global const float* restrict mats,
                        const uint per_probe, const float half_w, const float half_h,
                        const float origin_x, const float origin_y, const uint kernel_w,
                        const uint kernel_h, const uint band_rows, __global float* restrict tris,
                        __global uint* restrict vflags, const uint first_plane, const uint count) {
  const uint k = get_global_id(0);
  if (k >= count) return;
  const uint id = first_plane + k;
  float dw[NV];
  setup_plane(probes + (id / per_probe) * PROBE_STRIDE, mats + k * MAT_STRIDE, half_w, half_h,
              origin_x, origin_y, kernel_w, kernel_h, band_rows, tris + (size_t)id * PLANE_STRIDE,
              vflags + id, 0, dw);
}
