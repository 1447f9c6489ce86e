// The emulated pipeline of docs/spec.md 2 for Gilg et al.'s MTS measurement: two planes (plane A
// in front, plane B behind), each a GRID x GRID grid of quads, rasterised at the pixel centres of
// the measurement kernel only, depth stored in one storage format and tested.
//
// One program variant per (technique class, storage format, depth range, pipeline options),
// chosen by -D defines (host/runtime/kernel_variant.cpp), so the per-pixel loop has no run-time switch:
//   GRID               quads per plane side (vertices (GRID+1)^2, triangles 2*GRID^2)
//   DEPTH_FROM         0 projection, 1 vertex-stage log (Gilg eq. 5), 2 fragment-stage depth
//   FRAG_DEPTH         with DEPTH_FROM 2: 1 linear, 2 w_buffer, 3 log
//   RANGE_GL           1: d = 0.5 * z_ndc + 0.5 (clip z in [-w, w]); 0: d = z_ndc
//   COMPARE_GREATER    1: GEQUAL (reversed mappings); 0: LEQUAL
//   DIVIDE_EXACT       1: z_clip / w_clip correctly rounded; 0: z_clip * fl(1 / w_clip)
//   COMPOSE_PREMULT    1: the host uploads P*MV, one product per vertex; 0: P * (MV * v)
//   CONTRACT           1: the compiler may fuse a*b+c; 0: every operation rounds on its own
//   CACHE_A_CODES      1: the pixel loop reads plane A's codes from the plane-A cache
//   DF_*               the storage format (formats/depth_format.h)
//
// Arithmetic forms (the host reference, host/mts/reference_pipeline.cpp, uses the same ones):
//   matrix * vector     r_i = ((m_i0 x + m_i1 y) + m_i2 z) + m_i3 w
//   window x, y         x_w = x_ndc * (W/2) + W/2
//   edge function       E = dx * (py - ay) - dy * (px - ax), anchored at the lower vertex index
//                       of the edge so both triangles sharing it compute the same value
//   ownership (E == 0)  the triangle for which the oriented edge has s*dy < 0, or dy == 0 and
//                       s*dx < 0 (a top-left rule: exactly one of two neighbours owns the edge)
//   covering triangle   the lowest-index triangle whose three edge tests pass
//   depth (plane eq.)   d = (d0 + dzdx * (px - x0)) + dzdy * (py - y0), from vertex 0 of the
//                       triangle, dzdx = (e1d e2y - e2d e1y) / det, dzdy = (e2d e1x - e1d e2x) / det
//   1/w (perspective)   the same plane equation over q = 1/w_clip; w = 1 / q
#include "formats/depth_format.h"

#if CONTRACT
#pragma OPENCL FP_CONTRACT ON
#else
#pragma OPENCL FP_CONTRACT OFF
#endif

#define NV ((GRID + 1) * (GRID + 1))
#define NT (2 * GRID * GRID)
#define TRI_STRIDE 32
/* After the triangle records, the plane's 3*NT edges as arrays (structure of arrays, padded to a
 * multiple of 16) so a row can place all edge boundaries 16 at a time. */
#define NE (3 * NT)
#define NE_PAD ((NE + 15) / 16 * 16)
#define E_AX 0
#define E_AY 1
#define E_DX 2
#define E_DY 3
#define E_DXDY 4
#define E_BITS 5 /* uint: bit 0 negate, bit 1 owns */
/* Then each row of quads' y-range (GRID pairs ymin, ymax): the triangles a kernel row can meet
 * are those of the quad rows whose range holds it, a run of indices. */
#define Q_YRANGE (NT * TRI_STRIDE + 6 * NE_PAD)
/* Then, from a multiple of 16 floats on (so they load as aligned float16, and every plane record
 * starts at one: PLANE_STRIDE), the window x and y of every vertex, padded with zeros to a
 * multiple of 16: how far plane B's vertices lie from plane A's (b_moved_from_a). */
#define NV_PAD ((NV + 15) / 16 * 16)
#define V_XW ((Q_YRANGE + 2 * GRID + 15) / 16 * 16)
#define V_YW (V_XW + NV_PAD)
/* Then per vertex the kernel row of the pixel centre it lies near (int; -1: none, or padding):
 * the rows covers_kernel's certificate does not hold for (row_covered). */
#define V_BAD_ROW (V_YW + NV_PAD)
#define PLANE_STRIDE (V_BAD_ROW + NV_PAD)
#define PROBE_STRIDE 24
/* Per band of cached plane A (mts_a_bands): code bounds lo, hi, bad, then the gap range */
#define BW_GAP_LO 3
#define BW_GAP_HI 4
#define BAND_WORDS 5
#define MAT_STRIDE 16

// Triangle record offsets
#define T_EDGES 0 /* 3 x (ax, ay, dx, dy) */
#define T_BITS 12 /* uint: bit e negate edge e, bit 3+e owns edge e, bit 6 valid */
#define T_X0 13
#define T_Y0 14
#define T_D0 15
#define T_DZDX 16
#define T_DZDY 17
#define T_Q0 18
#define T_DQDX 19
#define T_DQDY 20
#define T_YMIN 21
#define T_YMAX 22
#define T_DXDY 23 /* 3 x dx/dy per edge: a first guess of where a row crosses it */
#define T_BOX 28  /* int4: the kernel pixels the triangle may own (kernel_pixel_box) */

// Probe constants offsets (after P[16])
#define C_NEAR 16
#define C_FAR 17
#define C_RANGE 18
#define C_LOGK 19
#define C_LOGL 20

// Per-row result bits; the number of fragment pairs evaluated sits above them.
#define R_FIGHT 1u
#define R_CLIPPED 2u
#define R_NONFINITE 4u
#define R_UNCOVERED 8u
#define R_BOUNDS 16u /* the row's band was decided clean from code bounds, not rasterised */
#define R_REUSED 32u /* plane B's coverage of the row was plane A's (coverage_margin) */
#define R_COUNT_SHIFT 8

/* mts_frame_bounds' words per band of a (probe, frame), read by mts_raster: the verdict (D_*, the
 * bits D_MASK) with bit DV_ORIENTED: every triangle of plane B has plane A's orientation; and how
 * far B's vertices lie from A's (b_moved_from_a, a float). Both are per frame, found per band so
 * mts_raster reads one place. */
#define DW_VERDICT 0
#define DW_MOVED 1
#define DECIDED_WORDS 2
#define D_MASK 3u
#define DV_ORIENTED 4u
#define D_RASTER 0u /* rasterise, deciding pieces from their end codes first */
#define D_CLEAN 1u  /* clean from code bounds or the gap certificate: not rasterised */
#define D_INSIDE 2u /* rasterise straight through the pixel loop: see mts_frame_bounds */
#define D_ORDERED 3u /* D_INSIDE, and every depth of plane A at or above df_order_exact_from */

#define S_OK 0
#define S_CLIPPED 1
#define S_NONFINITE 2
#define S_UNCOVERED 3

static inline float4 mat_vec(__global const float* m, float4 v) {
  float4 r;
  r.x = ((m[0] * v.x + m[1] * v.y) + m[2] * v.z) + m[3] * v.w;
  r.y = ((m[4] * v.x + m[5] * v.y) + m[6] * v.z) + m[7] * v.w;
  r.z = ((m[8] * v.x + m[9] * v.y) + m[10] * v.z) + m[11] * v.w;
  r.w = ((m[12] * v.x + m[13] * v.y) + m[14] * v.z) + m[15] * v.w;
  return r;
}

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
// vertex is > 0.0125 px from that vertex's other edges. docs/performance.md has the argument.
// A vertex near a pixel centre only spoils the certificate for the one pixel near it, so such
// bands are named in the flags (bit V_BAND_SHIFT + band, bands of band_rows rows, the first 24
// bands; a vertex in a later one clears V_COVERS) and the rest stay certified; and the pixel's
// row is written to bad_row[vertex] (-1 for a vertex near no pixel centre) for row_covered.
#define V_NONFINITE 1u
#define V_COVERS 2u
#define V_BAND_SHIFT 8
#define V_MAX_BANDS 24u
static inline uint covers_kernel(const float* xw, const float* yw, float ox, float oy, uint kw, uint kh,
                                 uint band_rows, int* bad_row) {
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
      const int va = side == 0 ? k : side == 1 ? k * (GRID + 1) + GRID : side == 2 ? GRID * (GRID + 1) + k : k * (GRID + 1);
      const int vb = side == 0 ? k + 1 : side == 1 ? (k + 1) * (GRID + 1) + GRID : side == 2 ? GRID * (GRID + 1) + k + 1 : (k + 1) * (GRID + 1);
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

// any() of a 16-lane mask by halving ORs: PoCL expands any() into a test and branch per lane pair.
static inline int any16(int16 m) {
  const int8 m8 = m.lo | m.hi;
  const int4 m4 = m8.lo | m8.hi;
  const int2 m2 = m4.lo | m4.hi;
  return (m2.x | m2.y) < 0;
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

// Vertex stage, divide, window transform and triangle set-up of one plane in one frame.
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
  __global const float* P = probes + (id / per_probe) * PROBE_STRIDE;
  __global const float* M = mats + k * MAT_STRIDE;
  float xw[NV], yw[NV], dw[NV], qw[NV];
  uint nonfinite = 0u;
  for (int j = 0; j <= GRID; ++j) {
    for (int i = 0; i <= GRID; ++i) {
      const int v = j * (GRID + 1) + i;
      const float4 obj = (float4)((float)i / (float)GRID - 0.5f, (float)j / (float)GRID - 0.5f,
                                  0.0f, 1.0f);
#if COMPOSE_PREMULT
      float4 clip = mat_vec(M, obj);
#else
      float4 clip = mat_vec(P, mat_vec(M, obj));
#endif
#if DEPTH_FROM == 1
      {
        const float t = log(P[C_LOGK] * clip.w + 1.0f);
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
      xw[v] = ndc.x * half_w + half_w;
      yw[v] = ndc.y * half_h + half_h;
#if RANGE_GL
      dw[v] = ndc.z * 0.5f + 0.5f;
#else
      dw[v] = ndc.z;
#endif
      qw[v] = inv_w;
      if (!isfinite(xw[v]) || !isfinite(yw[v]) || !isfinite(qw[v])) nonfinite = 1u;
#if DEPTH_FROM != 2
      if (!isfinite(dw[v])) nonfinite = 1u;
#endif
    }
  }
  __global float* T = tris + (size_t)id * PLANE_STRIDE;
  uint shapely = 1u; /* every triangle non-degenerate, no angle below ~6 degrees */
  for (int t = 0; t < NT; ++t) {
    const int quad = t >> 1, qi = quad % GRID, qj = quad / GRID;
    const int a = qj * (GRID + 1) + qi, b = a + 1, c = a + GRID + 2, d = a + GRID + 1;
    const int i0 = a, i1 = (t & 1) ? c : b, i2 = (t & 1) ? d : c;
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
    if (valid) bits |= 64u;
    else shapely = 0u;
    const float e1x = xw[i1] - xw[i0], e1y = yw[i1] - yw[i0];
    const float e2x = xw[i2] - xw[i0], e2y = yw[i2] - yw[i0];
    const float det = e1x * e2y - e2x * e1y;
    {
      const float e3x = xw[i2] - xw[i1], e3y = yw[i2] - yw[i1];
      const float longest = fmax(fmax(e1x * e1x + e1y * e1y, e2x * e2x + e2y * e2y), e3x * e3x + e3y * e3y);
      /* |det| = l_j l_k sin(angle) >= longest * sin(angle) */
      if (!(fabs(det) >= 0.1f * longest)) shapely = 0u;
    }
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
      ((__global uint*)SA)[E_BITS * NE_PAD + k] = ((bits >> e) & 1u) | (((bits >> (3 + e)) & 1u) << 1);
    }
    ((__global uint*)R)[T_BITS] = bits;
    vstore4(kernel_pixel_box(R, origin_x, origin_y, (int)kernel_w, (int)kernel_h), 0, (__global int*)R + T_BOX);
  }
  const int certify = !nonfinite && shapely; /* covers_kernel's preconditions */
  int bad_row[NV];
  vflags[id] = nonfinite |
               (certify ? covers_kernel(xw, yw, origin_x, origin_y, kernel_w, kernel_h, band_rows, bad_row) : 0u);
  for (int v = 0; v < NV_PAD; ++v) ((__global int*)T)[V_BAD_ROW + v] = v < NV && certify ? bad_row[v] : -1;
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

// Does the pixel centre px (row py) pass edge e of triangle R? The same float expression for every
// pixel, so span search below and the host reference agree on every pixel.
static inline int edge_passes(__global const float* R, uint bits, int e, float px, float py) {
  const float ax = R[4 * e], ay = R[4 * e + 1], dx = R[4 * e + 2], dy = R[4 * e + 3];
  float E = dx * (py - ay) - dy * (px - ax);
  if ((bits >> e) & 1u) E = -E;
  return E > 0.0f || (E == 0.0f && ((bits >> (3 + e)) & 1u));
}

// Along a row, px - ax, dy * (.) and C - (.) are all monotone in px, so each edge's test is
// monotone: the pixels passing it form a prefix or a suffix of the row, and the pixels inside the
// triangle form one interval. Found here by walking from the analytic crossing to the exact
// boundary of the very test a per-pixel rasteriser would do.
static inline void edge_range(__global const float* R, uint bits, int e, float py, float ox, int W,
                              int* lo, int* hi) {
  const float dy = R[4 * e + 3];
  const float sdy = ((bits >> e) & 1u) ? -dy : dy;
  if (sdy == 0.0f) { /* constant along the row */
    if (!edge_passes(R, bits, e, ox + 0.5f, py)) *hi = 0;
    return;
  }
  /* The test is monotone, so its value at the row's two ends says whether there is a boundary
   * to find at all; an edge far from the row (a near-horizontal one, say) passes or fails whole. */
  const int first = edge_passes(R, bits, e, ox + 0.5f, py);
  const int last = edge_passes(R, bits, e, ox + (float)(W - 1) + 0.5f, py);
  if (first && last) return;
  if (!first && !last) {
    *hi = 0;
    return;
  }
  const float cross = R[4 * e] + (py - R[4 * e + 1]) * R[T_DXDY + e] - ox - 0.5f; /* E ~ 0 here */
  int g = isfinite(cross) ? (int)clamp(ceil(cross), -1.0f, (float)W + 1.0f) : 0;
  g = clamp(g, 0, W);
  if (sdy < 0.0f) {
    /* s*E grows with px: pixels g.. pass; find the first passing index */
    while (g > 0 && edge_passes(R, bits, e, ox + (float)(g - 1) + 0.5f, py)) --g;
    while (g < W && !edge_passes(R, bits, e, ox + (float)g + 0.5f, py)) ++g;
    *lo = max(*lo, g);
  } else {
    /* s*E falls with px: pixels ..g-1 pass; find the first failing index */
    while (g < W && edge_passes(R, bits, e, ox + (float)g + 0.5f, py)) ++g;
    while (g > 0 && !edge_passes(R, bits, e, ox + (float)(g - 1) + 0.5f, py)) --g;
    *hi = min(*hi, g);
  }
}

// The row's coverage by one plane as segments [seg_x[k], seg_x[k+1]) owned by triangle seg_t[k]
// (-1: uncovered); where rounding lets two triangles claim a pixel, the lower index owns it.
// Returns the number of segments; seg_x[n] == W.
#define MAX_SEG (2 * NT + 2)
static inline int row_segments(__global const float* T, float py, float ox, int W, int* seg_x,
                               int* seg_t) {
  __global const uint* TB = (__global const uint*)T;
  /* Every edge's passing pixels [elo, ehi), 16 edges at a time: an edge passing or failing at
   * both ends of the row passes or fails all of it (the test is monotone); a crossing edge's
   * boundary is taken where the test flips between the guessed pixel and the one before it.
   * Lanes where that check fails (-2) are placed by the scalar walk below. */
  __global const float* SA = T + NT * TRI_STRIDE;
  int elo[NE_PAD], ehi[NE_PAD];
  const float px_first = ox + 0.5f, px_last = ox + (float)(W - 1) + 0.5f;
  /* only the edges of the quad rows whose y-range holds the row: a run of indices (one or two
   * rows of quads); which of their triangles meet the row is decided below */
  int t_first = NT, t_last = -1;
  for (int qj = 0; qj < GRID; ++qj) {
    if (T[Q_YRANGE + 2 * qj] <= py && py <= T[Q_YRANGE + 2 * qj + 1]) {
      t_first = min(t_first, 2 * GRID * qj);
      t_last = 2 * GRID * (qj + 1) - 1;
    }
  }
  const int g_first = (3 * t_first) / 16 * 16, g_end = 3 * (t_last + 1);
  for (int g = g_first; g < g_end; g += 16) {
    const float16 ax = vload16(0, SA + E_AX * NE_PAD + g), ay = vload16(0, SA + E_AY * NE_PAD + g);
    const float16 dx = vload16(0, SA + E_DX * NE_PAD + g), dy = vload16(0, SA + E_DY * NE_PAD + g);
    const float16 dxdy = vload16(0, SA + E_DXDY * NE_PAD + g);
    const uint16 eb = vload16(0, (__global const uint*)SA + E_BITS * NE_PAD + g);
    const int16 negate = convert_int16((eb & (uint16)1u) != (uint16)0u);
    const int16 owns = convert_int16((eb & (uint16)2u) != (uint16)0u);
    const float16 c = dx * (py - ay);
#define EDGE_PASS16(PX)                                                                      \
  ({                                                                                         \
    float16 E_ = c - dy * ((PX) - ax);                                                       \
    E_ = negate ? -E_ : E_;                                                                  \
    (E_ > 0.0f) || ((E_ == 0.0f) && owns);                                                   \
  })
    const int16 p0 = EDGE_PASS16((float16)px_first);
    const int16 p1 = EDGE_PASS16((float16)px_last);
    const float16 sdy = negate ? -dy : dy;
    const float16 cross = ax + (py - ay) * dxdy - ox - 0.5f;
    const int16 gi = clamp(convert_int16(ceil(clamp(cross, -1.0f, (float)W + 1.0f))), 1, max(W - 1, 1));
    const float16 pxg = (ox + convert_float16(gi)) + 0.5f;
    const int16 pg = EDGE_PASS16(pxg);
    const int16 pgm = EDGE_PASS16(pxg - 1.0f);
#undef EDGE_PASS16
    const int16 all = (int16)W, none = (int16)0;
    /* sdy < 0: suffix passes, lo = boundary; sdy > 0: prefix passes, hi = boundary */
    const int16 flat = sdy == 0.0f;
    const int16 up = sdy < 0.0f;
    const int16 whole = p0 && p1;
    const int16 empty = !p0 && !p1;
    const int16 found_up = up && !p0 && p1 && pg && !pgm;
    const int16 found_dn = !up && p0 && !p1 && !pg && pgm;
    int16 lo16 = none, hi16 = all;
    lo16 = found_up ? gi : lo16;
    hi16 = found_dn ? gi : hi16;
    hi16 = (flat ? !p0 : empty) ? none : hi16;
    const int16 resolved = flat || whole || empty || found_up || found_dn;
    lo16 = resolved ? lo16 : (int16)-2;
    vstore16(lo16, 0, elo + g);
    vstore16(hi16, 0, ehi + g);
  }
  int lo[NT], hi[NT], tri[NT], n = 0;
  for (int t = t_first; t <= t_last; ++t) {
    __global const float* R = T + t * TRI_STRIDE;
    const uint bits = TB[t * TRI_STRIDE + T_BITS];
    if (!(bits & 64u) || !(R[T_YMIN] <= py && py <= R[T_YMAX])) continue;
    int a = 0, b = W;
    for (int e = 0; e < 3 && a < b; ++e) {
      const int k = 3 * t + e;
      if (elo[k] == -2) {
        edge_range(R, bits, e, py, ox, W, &a, &b);
      } else {
        a = max(a, elo[k]);
        b = min(b, ehi[k]);
      }
    }
    if (a < b) {
      lo[n] = a;
      hi[n] = b;
      tri[n] = t;
      ++n;
    }
  }
  /* Usually the spans are disjoint (each pixel owned by one triangle): sorted by start they are
   * the segments, with uncovered gaps between. Otherwise fall through to the general sweep. */
  for (int i = 1; i < n; ++i) {
    const int l = lo[i], h = hi[i], t = tri[i];
    int j = i - 1;
    while (j >= 0 && lo[j] > l) {
      lo[j + 1] = lo[j];
      hi[j + 1] = hi[j];
      tri[j + 1] = tri[j];
      --j;
    }
    lo[j + 1] = l;
    hi[j + 1] = h;
    tri[j + 1] = t;
  }
  int disjoint = 1;
  for (int i = 1; i < n; ++i) disjoint &= hi[i - 1] <= lo[i];
  if (disjoint) {
    int ns = 0, cur = 0;
    for (int i = 0; i < n; ++i) {
      if (lo[i] > cur) {
        seg_x[ns] = cur;
        seg_t[ns++] = -1;
      }
      seg_x[ns] = lo[i];
      seg_t[ns++] = tri[i];
      cur = hi[i];
    }
    if (cur < W) {
      seg_x[ns] = cur;
      seg_t[ns++] = -1;
    }
    seg_x[ns] = W;
    return ns;
  }
  /* boundaries: 0, W and every span end, sorted */
  int bx[MAX_SEG];
  int nb = 0;
  bx[nb++] = 0;
  for (int i = 0; i < n; ++i) {
    bx[nb++] = lo[i];
    bx[nb++] = hi[i];
  }
  for (int i = 1; i < nb; ++i) {
    const int v = bx[i];
    int j = i - 1;
    while (j >= 0 && bx[j] > v) {
      bx[j + 1] = bx[j];
      --j;
    }
    bx[j + 1] = v;
  }
  int ns = 0;
  for (int i = 0; i < nb; ++i) {
    const int x0 = bx[i];
    const int x1 = i + 1 < nb ? bx[i + 1] : W;
    if (x1 <= x0 || x0 >= W) continue;
    int owner = -1;
    for (int k = 0; k < n; ++k)
      if (lo[k] <= x0 && x0 < hi[k] && (owner < 0 || tri[k] < owner)) owner = tri[k];
    if (ns > 0 && seg_t[ns - 1] == owner) continue; /* extend the previous segment */
    seg_x[ns] = x0;
    seg_t[ns] = owner;
    ++ns;
  }
  seg_x[ns] = W;
  return ns;
}

// Plane A does not depend on the separation, so the host sets it up once per (distance, frame)
// for every probe of the distance (host/mts/mts_evaluator.cpp, the plane-A cache): its triangles, its
// code bounds per band, and per kernel row its coverage segments and coverage margin.
#define MAXC 24 /* segments a cached row holds; a row with more is computed where it is used */
#define RW_N 0
#define RW_MARGIN 1
#define RW_X 2
#define RW_T (RW_X + MAXC + 1)
#define ROW_WORDS (RW_T + MAXC)
/* CACHE_A_CODES (host/runtime/kernel_variant.h): plane A's stored code at every pixel of a cached row, so
 * the pixel loop evaluates plane B only; rows of kernel_w + 16 codes (a 16-lane store past a
 * segment's end lands in the next segment or the padding). */

// Plane B is plane A moved along the view direction and scaled with its distance, so both project
// to the same window triangles in exact arithmetic; in binary32 B's vertices lie some delta
// (~1e-4 px) from A's. Returns a margin: for any B whose vertices all lie within less than it of
// A's (per coordinate), and which owns each kernel pixel through exactly one triangle (V_COVERS),
// B's coverage of the row is A's segments. Proof: each segment's triangle passes its three edge
// tests at the segment's first and last pixel in B too, so (each test being monotone along the
// row) at every pixel of the segment, and the one triangle that passes a pixel owns it; and the
// row stays inside each triangle's y-range, which row_segments also asks. The edge value
// E = dx (py - ay) - dy (px - ax) of a pixel moves by at most d (|dx| + |dy| + 2|py - ay| +
// 2|px - ax|) + 4 d^2 when the edge's vertices move by d, and each binary32 evaluation (fused or
// not) lies within 4.1 eps (|dx (py - ay)| + |dy (px - ax)|) of its exact value, so a pass with
// E above twice that rounding bound plus the movement survives; the margin is the d at which the
// movement would take half of what is left over, with 1 % slack for the margin's own rounding.
// 0 when A leaves a pixel uncovered or a test sits at its rounding bound.
static inline float coverage_margin(__global const float* T, float py, float ox, int n, const int* seg_x,
                                    const int* seg_t) {
  __global const float* SA = T + NT * TRI_STRIDE;
  __global const uint* SB = (__global const uint*)SA + E_BITS * NE_PAD;
  const float eps = 0x1.0p-24f;
  float margin = INFINITY;
  for (int k = 0; k < n; ++k) {
    const int t = seg_t[k];
    if (t < 0) return 0.0f;
    __global const float* R = T + t * TRI_STRIDE;
    margin = fmin(margin, fmin(py - R[T_YMIN], R[T_YMAX] - py));
    for (int e = 0; e < 3; ++e) {
      const int j = 3 * t + e;
      const float ax = SA[E_AX * NE_PAD + j], ay = SA[E_AY * NE_PAD + j];
      const float dx = SA[E_DX * NE_PAD + j], dy = SA[E_DY * NE_PAD + j];
      for (int end = 0; end < 2; ++end) {
        const float px = ox + (float)(end ? seg_x[k + 1] - 1 : seg_x[k]) + 0.5f;
        const float u = py - ay, v = px - ax;
        float E = dx * u - dy * v;
        if (SB[j] & 1u) E = -E;
        const float r = E - 16.0f * eps * (fabs(dx * u) + fabs(dy * v));
        if (!(r > 0.0f)) return 0.0f;
        const float c = 1.01f * (fabs(dx) + fabs(dy) + 2.0f * fabs(u) + 2.0f * fabs(v));
        margin = fmin(margin, fmin(r / (2.2f * c), 0.99f * sqrt(r / 8.4f)));
      }
    }
  }
  return 0.99f * margin;
}

// How far plane B's vertices lie from plane A's: the largest per-coordinate difference (rounded
// up). Both planes are finite (callers check V_NONFINITE first), so max needs no NaN handling,
// which fmax would compile into compares and blends; the loads are aligned (V_XW).
static inline float b_moved_from_a(__global const float* TA, __global const float* TB) {
  __global const float16* a = (__global const float16*)(TA + V_XW);
  __global const float16* b = (__global const float16*)(TB + V_XW);
  float16 m = (float16)0.0f;
  for (int k = 0; k < 2 * NV_PAD / 16; ++k) m = max(m, fabs(b[k] - a[k]));
  const float8 m8 = max(m.lo, m.hi);
  const float4 m4 = max(m8.lo, m8.hi);
  const float2 m2 = max(m4.lo, m4.hi);
  return 1.0001f * max(m2.x, m2.y);
}

// Whether every triangle of plane B has plane A's orientation (its edges negated alike).
static inline int b_keeps_orientation(__global const float* TA, __global const float* TB) {
  __global const uint* a = (__global const uint*)TA + T_BITS;
  __global const uint* b = (__global const uint*)TB + T_BITS;
  uint differ = 0u;
  for (int t = 0; t < NT; ++t) differ |= (a[t * TRI_STRIDE] ^ b[t * TRI_STRIDE]) & 7u;
  return differ == 0u;
}

// Whether plane B's coverage of a cached row of plane A is A's: B certified to own every pixel of
// the row through exactly one triangle (row_covered; a frame with a vertex near a pixel centre
// loses only that pixel's row), B within A's coverage margin (coverage_margin: moved is
// b_moved_from_a), and B's triangles keep A's orientation (oriented: b_keeps_orientation). The
// last two are per frame: mts_frame_bounds finds them once.
static inline int b_coverage_is_a(float moved, int oriented, __global const float* TB, uint vflags_b, int row,
                                  __global const uint* rec) {
  return oriented && moved < ((__global const float*)rec)[RW_MARGIN] && row_covered(TB, vflags_b, row);
}

// A triangle's interpolation set up for one row: depth (or 1/w) = (c0 + slope * (px - x0)) + row_term
typedef struct {
  float c0, slope, x0, row_term;
} row_plane_t;

static inline row_plane_t row_plane(__global const float* T, int t, float py) {
  __global const float* R = T + t * TRI_STRIDE;
  row_plane_t rp;
  rp.x0 = R[T_X0];
#if DEPTH_FROM == 2
  rp.c0 = R[T_Q0];
  rp.slope = R[T_DQDX];
  rp.row_term = R[T_DQDY] * (py - R[T_Y0]);
#else
  rp.c0 = R[T_D0];
  rp.slope = R[T_DZDX];
  rp.row_term = R[T_DZDY] * (py - R[T_Y0]);
#endif
  return rp;
}

// Row planes of 16 lanes: one triangle broadcast, or one triangle per lane (per piece).
typedef struct {
  float16 c0, slope, x0, row_term;
} row_plane16_t;

static inline row_plane16_t broadcast16(row_plane_t rp) {
  row_plane16_t r;
  r.c0 = (float16)rp.c0;
  r.slope = (float16)rp.slope;
  r.x0 = (float16)rp.x0;
  r.row_term = (float16)rp.row_term;
  return r;
}

// Depth and status of 16 fragments: depth (or 1/w) = (c0 + slope * (px - x0)) + row_term, every
// lane rounding on its own, as a scalar pipeline would. Masks are -1 / 0 per lane.
typedef struct {
  float16 d;
  int16 nonfinite, clipped;
} depth16_t;

static inline depth16_t depth16(row_plane16_t rp, __global const float* P, float16 px) {
  depth16_t r;
#if DEPTH_FROM == 2
  const float16 q = (rp.c0 + rp.slope * (px - rp.x0)) + rp.row_term;
  const float16 w = 1.0f / q;
  const int16 nf_w = !isfinite(w);
  r.clipped = (w < P[C_NEAR]) || (w > P[C_FAR]);
#if FRAG_DEPTH == 1
  float16 d = (w - P[C_NEAR]) / P[C_RANGE];
#elif FRAG_DEPTH == 2
  float16 d = w / P[C_FAR];
#else
  float16 d = log(P[C_LOGK] * w + 1.0f) / P[C_LOGL];
#endif
  r.nonfinite = nf_w || isnan(d);
  r.d = fmin(fmax(d, 0.0f), 1.0f); /* gl_FragDepth is clamped */
#else
  r.d = (rp.c0 + rp.slope * (px - rp.x0)) + rp.row_term;
  r.nonfinite = !isfinite(r.d);
  r.clipped = !((r.d >= 0.0f) && (r.d <= 1.0f));
#endif
  return r;
}

// Stored code and status of 16 fragments.
typedef struct {
  uint16 code;
  int16 nonfinite, clipped;
} frag16_t;

static inline frag16_t fragment16(row_plane16_t rp, __global const float* P, float16 px) {
  const depth16_t z = depth16(rp, P, px);
  frag16_t r;
  r.code = df_encode16(z.d, DF_FORMAT_FROM_DEFINES());
  r.nonfinite = z.nonfinite;
  r.clipped = z.clipped;
  return r;
}

// The stored code of 16 fragments known to be finite and unclipped (inside a piece whose ends
// are, or a band whose bounds say so): their depth lies in [-0, 1], the clamped one too, so the
// encoder needs no checks for values outside it. The same codes fragment16 gives there.
static inline uint16 inside_code16(row_plane16_t rp, __global const float* P, float16 px) {
  return df_encode16_unit(depth16(rp, P, px).d, DF_FORMAT_FROM_DEFINES());
}

static inline int16 fights16(uint16 code_a, uint16 code_b) {
#if COMPARE_GREATER
  return convert_int16(code_b >= code_a);
#else
  return convert_int16(code_b <= code_a);
#endif
}

// fights16 from the depths themselves, for fragments of which at least one has a depth at or
// above df_order_exact_from (in a D_ORDERED band every fragment of plane A has): there the codes
// compare as the depths do, so neither needs encoding.
static inline int16 ordered_fights16(float16 da, float16 db) {
#if COMPARE_GREATER
  return db >= da;
#else
  return db <= da;
#endif
}

// Codes a piece or band decided from bounds must clear: the library log's error (mts_variant).
#if DEPTH_FROM == 2 && FRAG_DEPTH == 3
#define LOG_SLACK_OR_0 LOG_CODE_SLACK
#else
#define LOG_SLACK_OR_0 0UL
#endif

#define LANES ((int16)(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15))


// Walks the row in pieces where both planes' covering triangles stay the same.
#define FOR_EACH_PIECE(...)                                                            \
  {                                                                                    \
    int ka = 0, kb = 0, x = 0;                                                         \
    while (x < W) {                                                                    \
      while (seg_xa[ka + 1] <= x) ++ka;                                                \
      while (seg_xb[kb + 1] <= x) ++kb;                                                \
      const int x_end = min(seg_xa[ka + 1], seg_xb[kb + 1]);                           \
      const int ta = seg_ta[ka], tb = seg_tb[kb];                                      \
      __VA_ARGS__                                                                      \
      x = x_end;                                                                       \
    }                                                                                  \
  }

#define MAX_PIECES (2 * MAX_SEG)

// Row records of cached plane A. Global id: plane * kernel_h + row, planes from first_plane.
__kernel void mts_a_rows(__global const float* restrict probes, __global const float* restrict tris,
                         __global const uint* restrict vflags, const uint first_plane, const uint per_probe,
                         const uint kernel_w, const uint kernel_h, const float origin_x,
                         const float origin_y, __global uint* restrict rows, __global uint* restrict codes,
                         const uint items) {
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
  __global uint* c = codes + ((size_t)plane * kernel_h + row) * (kernel_w + 16u);
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

// The smallest and largest stored code of one plane over the kernel pixels of rows [r0, r1) that
// any of its triangles may own (each triangle's bounding box, one pixel wider, clipped to the
// band), and whether any of them is clipped or non-finite. Depth is monotone in px along a row
// and, through the row term, in py (every rounding step is monotone), so its extremes over a box
// of pixel centres lie at the box's corners; the corners are evaluated with the very expressions
// of the per-pixel loop, 16 at a time (4 triangles x 4 corners).
typedef struct {
  ulong lo, hi;
  int bad;
} code_bounds_t;

// The kernel pixels (column i0..i1, row j0..j1) of rows [r0, r1) that triangle R may own
// (kernel_pixel_box, stored by mts_setup). Empty when i0 > i1 or j0 > j1.
static inline int4 pixel_box(__global const float* R, int r0, int r1) {
  const int4 box = vload4(0, (__global const int*)R + T_BOX);
  return (int4)(box.s0, box.s1, max(box.s2, r0), min(box.s3, r1 - 1));
}

static inline code_bounds_t plane_code_bounds(__global const float* T, __global const float* P, float ox,
                                              float oy, int W, int r0, int r1) {
  code_bounds_t b;
  b.lo = 0xffffffffUL;
  b.hi = 0UL;
  b.bad = 0;
  float c0[16], sl[16], x0[16], rt[16], px[16];
  int n = 0;
  for (int t = 0; t <= NT; ++t) {
    if (t < NT) {
      const int4 box = pixel_box(T + t * TRI_STRIDE, r0, r1);
      const int i0 = box.s0, i1 = box.s1, j0 = box.s2, j1 = box.s3;
      if (i0 > i1 || j0 > j1) continue;
      for (int q = 0; q < 4; ++q) {
        const float py = oy + (float)((q & 2) ? j1 : j0) + 0.5f;
        const row_plane_t rp = row_plane(T, t, py);
        c0[n] = rp.c0;
        sl[n] = rp.slope;
        x0[n] = rp.x0;
        rt[n] = rp.row_term;
        px[n] = ox + (float)((q & 1) ? i1 : i0) + 0.5f;
        ++n;
      }
    }
    if (n == 16 || (t == NT && n > 0)) {
      for (int k = n; k < 16; ++k) { /* pad with the first corner */
        c0[k] = c0[0]; sl[k] = sl[0]; x0[k] = x0[0]; rt[k] = rt[0]; px[k] = px[0];
      }
      row_plane16_t rp;
      rp.c0 = vload16(0, c0);
      rp.slope = vload16(0, sl);
      rp.x0 = vload16(0, x0);
      rp.row_term = vload16(0, rt);
      const frag16_t f = fragment16(rp, P, vload16(0, px));
      b.bad |= any(f.nonfinite | f.clipped);
      /* halving reductions: 16 -> 8 -> 4 -> 2 -> 1 lanes */
      const uint8 lo8 = min(f.code.lo, f.code.hi), hi8 = max(f.code.lo, f.code.hi);
      const uint4 lo4 = min(lo8.lo, lo8.hi), hi4 = max(hi8.lo, hi8.hi);
      const uint2 lo2 = min(lo4.lo, lo4.hi), hi2 = max(hi4.lo, hi4.hi);
      b.lo = min(b.lo, (ulong)min(lo2.x, lo2.y));
      b.hi = max(b.hi, (ulong)max(hi2.x, hi2.y));
      n = 0;
    }
  }
  return b;
}

// The gap certificate: a band is clean when, at every pixel, plane B's stored code lies beyond
// plane A's, judged from the distance between the two planes rather than from their code ranges.
// Code bounds (above) compare B's smallest code over the band with A's largest, which fails
// whenever the band's own depth range exceeds the separation, as it does near the MTS at small
// distances where depth changes by many codes per pixel. B is A scaled about the eye, so in window
// space the two depth planes are nearly parallel and their distance hardly changes over the band.
// Each triangle's depth is d = fl(fl(c0 + fl(s fl(px - x0))) + fl(t fl(py - y0))) (row_plane,
// fragment16), which lies within E = 4.01 u (|c0| + |s (px - x0)| + |t (py - y0)|) + 2^-140 of the
// exact L = c0 + s (px - x0) + t (py - y0), u = 2^-24: each of the six roundings contributes at
// most u times its result, which the three terms bound; the 0.01 covers evaluating L and E in
// binary64, 2^-140 the absolute error of subnormal results; fused operations only remove roundings.
// Measured against one reference plane R (the exact L of plane A's triangle 0): every pixel a
// triangle may own lies in its pixel_box, over which L - R is linear and E convex, so
// L - E - R is smallest and L + E - R largest at the box's corners. With lo/hi the smallest
// L - E - R and largest L + E - R over a plane's triangles in the band, d_B - d_A >= lo_B - hi_A at
// every pixel, whichever triangles own it. B's code exceeds A's (LEQUAL) when that is above
// GAP_STEP: one code step for unorm (round(d N) of values more than 1/N apart differ; no saturation
// in an unclipped band), any positive amount for float32 (codes are the bit patterns, monotone in
// d). GEQUAL mirrors it (hi_B below lo_A). Other formats, and fragment-stage depth (not an
// interpolated plane), are not certified this way.
//
// Fragment-stage depth (DEPTH_FROM 2) interpolates q = 1/w the same way, so lo/hi bound q against
// a reference plane R of q; d = h(q) is then a decreasing, convex function of q (frag_gap_clear),
// and only LEQUAL set-ups use it.
#if DF_KIND == 0
#define GAP_STEP (1.0 / (double)DF_FORMAT_FROM_DEFINES().max_code)
#elif DF_KIND == 1 && DF_E == 8 && DF_M == 23 && DF_IEEE && !DF_FLUSH
#define GAP_STEP 0.0
#endif
#if defined(GAP_STEP) && (DEPTH_FROM != 2 || !COMPARE_GREATER)
#define GAP_CERT 1
#else
#define GAP_CERT 0
#endif
#if DEPTH_FROM == 2 /* the interpolated plane: q = 1/w_clip, or depth itself */
#define G_C0 T_Q0
#define G_DX T_DQDX
#define G_DY T_DQDY
#else
#define G_C0 T_D0
#define G_DX T_DZDX
#define G_DY T_DZDY
#endif

#if GAP_CERT
#pragma OPENCL EXTENSION cl_khr_fp64 : enable
// The reference plane's exact value R at (px, py), binary64 scalars or vectors alike.
#define REF_PLANE_AT(ref, px, py)                                                     \
  (((double)(ref)[G_C0] + (double)(ref)[G_DX] * ((px) - (double)(ref)[T_X0])) +        \
   (double)(ref)[G_DY] * ((py) - (double)(ref)[T_Y0]))

// L - R, and E, of 16 corners: triangle planes in lanes (c0, s, x0, t, y0 of each) against the
// reference plane ref (same fields).
static inline void plane_minus_ref16(const float* f, __global const float* ref, double16 px, double16 py,
                                     double16* l, double16* e) {
  const double16 sx = convert_double16(vload16(0, f + 16)) * (px - convert_double16(vload16(0, f + 32)));
  const double16 ty = convert_double16(vload16(0, f + 48)) * (py - convert_double16(vload16(0, f + 64)));
  const double16 c0 = convert_double16(vload16(0, f));
  *l = ((c0 + sx) + ty) - REF_PLANE_AT(ref, px, py);
  *e = (4.01 * 0x1.0p-24) * ((fabs(c0) + fabs(sx)) + fabs(ty)) + 0x1.0p-140;
}

// lo (smallest L - E - R) and hi (largest L + E - R) of plane T over rows [r0, r1); NaN when any
// corner is not finite.
static inline double2 plane_gap_range(__global const float* T, __global const float* ref, float ox, float oy,
                                      int W, int r0, int r1) {
  double lo = INFINITY, hi = -INFINITY;
  int bad = 0;
  float f[80], px[16], py[16];
  int n = 0;
  for (int t = 0; t <= NT; ++t) {
    if (t < NT) {
      __global const float* R = T + t * TRI_STRIDE;
      const int4 box = pixel_box(R, r0, r1);
      if (box.s0 > box.s1 || box.s2 > box.s3) continue;
      for (int q = 0; q < 4; ++q) {
        f[n] = R[G_C0];
        f[16 + n] = R[G_DX];
        f[32 + n] = R[T_X0];
        f[48 + n] = R[G_DY];
        f[64 + n] = R[T_Y0];
        px[n] = ox + (float)((q & 1) ? box.s1 : box.s0) + 0.5f;
        py[n] = oy + (float)((q & 2) ? box.s3 : box.s2) + 0.5f;
        ++n;
      }
    }
    if (n == 16 || (t == NT && n > 0)) {
      for (int k = n; k < 16; ++k) { /* pad with the first corner */
        for (int j = 0; j < 80; j += 16) f[j + k] = f[j];
        px[k] = px[0];
        py[k] = py[0];
      }
      double16 l, e;
      plane_minus_ref16(f, ref, convert_double16(vload16(0, px)), convert_double16(vload16(0, py)), &l, &e);
      bad |= !all(isfinite(l) && isfinite(e));
      const double16 a = l - e, b = l + e;
      const double8 a8 = fmin(a.lo, a.hi), b8 = fmax(b.lo, b.hi);
      const double4 a4 = fmin(a8.lo, a8.hi), b4 = fmax(b8.lo, b8.hi);
      const double2 a2 = fmin(a4.lo, a4.hi), b2 = fmax(b4.lo, b4.hi);
      lo = fmin(lo, fmin(a2.x, a2.y));
      hi = fmax(hi, fmax(b2.x, b2.y));
      n = 0;
    }
  }
  return bad ? (double2)(NAN, NAN) : (double2)(lo, hi);
}

#if DEPTH_FROM == 2
// The exact depth h(q) of fragment-stage depth, and the most the binary32 computation of d from a
// computed q can differ from it where h(q) <= h_max and w = 1/q <= w_max: w = fl(1/q) is within u
// relative (correctly rounded division), then
//   linear   d = fl(fl(w - n) / range): 2.001 u h + 1.001 u w / range
//   w_buffer d = fl(w / far):           2.001 u h
//   log      d = fl(log(fl(fl(k w) + 1)) / L): x = k w + 1 within 3.0001 u of ln x after the log,
//            the log itself within 3 ulp (the bound LOG_CODE_SLACK assumes), so 7.02 u h + 3.001 u / L
static inline double frag_h(__global const float* P, double q) {
#if FRAG_DEPTH == 1
  return (1.0 / q - (double)P[C_NEAR]) / (double)P[C_RANGE];
#elif FRAG_DEPTH == 2
  return 1.0 / (q * (double)P[C_FAR]);
#else
  return log((double)P[C_LOGK] / q + 1.0) / (double)P[C_LOGL];
#endif
}

static inline double frag_err(__global const float* P, double h_max, double w_max) {
  const double u = 0x1.0p-24;
#if FRAG_DEPTH == 1
  return 2.001 * u * h_max + 1.001 * u * w_max / (double)P[C_RANGE];
#elif FRAG_DEPTH == 2
  return 2.001 * u * h_max;
#else
  return 7.02 * u * h_max + 3.001 * u / (double)P[C_LOGL];
#endif
}

// LEQUAL: whether B's code exceeds A's at every pixel of rows [r0, r1), given a = (lo, hi) of A's
// q and b = (lo, hi) of B's q against the reference plane ref (plane_gap_range). At a pixel with
// R = r: q_A >= r + lo_A, q_B <= r + hi_B, so (h decreasing) d_B - d_A >= h(r + hi_B) - h(r + lo_A)
// - 2 err, and for hi_B < lo_A that difference of a convex h falls with r: its least is at the
// band's largest R. Clamping d to [0, 1] keeps B's code above A's while A's d stays below 1 - step.
static inline int frag_gap_clear(__global const float* P, __global const float* ref, double2 a, double2 b,
                                 float ox, float oy, int W, int r0, int r1) {
  double r_min = INFINITY, r_max = -INFINITY;
  for (int q = 0; q < 4; ++q) {
    const double px = (double)(ox + (float)((q & 1) ? W - 1 : 0) + 0.5f);
    const double py = (double)(oy + (float)((q & 2) ? r1 - 1 : r0) + 0.5f);
    const double r = REF_PLANE_AT(ref, px, py);
    r_min = fmin(r_min, r);
    r_max = fmax(r_max, r);
  }
  const double q_min = r_min + fmin(a.x, b.x);
  if (!(q_min > 0.0) || !(b.y < a.x) || !isfinite(r_max)) return 0;
  const double err = frag_err(P, frag_h(P, q_min), 1.0 / q_min) + 1e-12;
  return frag_h(P, r_max + b.y) - frag_h(P, r_max + a.x) - 2.0 * err > GAP_STEP &&
         1.0 - (frag_h(P, r_min + a.x) + err) > GAP_STEP;
}
#endif
#endif

// Per band of cached plane A: its code bounds lo, hi, bad, and the range of its gap certificate
// (plane_gap_range against its own triangle 0; NaN where not computed). Global id:
// plane * bands + band, planes from first_plane; the probe constants of plane p are those of p / per_probe.
__kernel void mts_a_bands(__global const float* restrict probes, __global const float* restrict tris,
                          __global const uint* restrict vflags, const uint first_plane, const uint per_probe,
                          const uint kernel_w, const uint kernel_h, const float origin_x, const float origin_y,
                          const uint bands, const uint band_rows, __global uint* restrict out, const uint items) {
  const uint id = get_global_id(0);
  if (id >= items) return;
  const uint plane = first_plane + id / bands, band = id % bands;
  __global uint* o = out + ((size_t)plane * bands + band) * BAND_WORDS;
  o[2] = 1u;
  ((__global float*)o)[BW_GAP_LO] = NAN;
  ((__global float*)o)[BW_GAP_HI] = NAN;
  if (!band_covered(vflags[plane], band)) return;
  const int r0 = (int)(band * band_rows), r1 = min((int)kernel_h, r0 + (int)band_rows);
  __global const float* T = tris + (size_t)plane * PLANE_STRIDE;
  const code_bounds_t a = plane_code_bounds(T, probes + (plane / per_probe) * PROBE_STRIDE, origin_x, origin_y,
                                            (int)kernel_w, r0, r1);
  o[0] = (uint)a.lo;
  o[1] = (uint)a.hi;
  o[2] = (uint)a.bad;
#if GAP_CERT
  /* rounded outwards: the band's gap range is only ever widened */
  const double2 g = plane_gap_range(T, T, origin_x, origin_y, (int)kernel_w, r0, r1);
  ((__global float*)o)[BW_GAP_LO] = convert_float_rtn(g.x);
  ((__global float*)o)[BW_GAP_HI] = convert_float_rtp(g.y);
#endif
}

// Where plane A of (probe, visit) sits in the plane-A cache: a_slots holds per probe its slot and
// the frame its visit starts at (host/mts/mts_evaluator.h, frame order); each slot holds all
// frames_total frames of its distance; the launch covers visits first_frame.. of each probe. The
// start frame and first_frame + visit both lie below frames_total, so one subtraction wraps their
// sum (no division: mts_raster runs this per kernel row).
static inline uint a_plane(__global const uint* a_slots, uint probe, uint visit, uint first_frame,
                           uint frames_total) {
  const uint f = a_slots[2u * probe + 1u] + first_frame + visit;
  return a_slots[2u * probe] * frames_total + (f >= frames_total ? f - frames_total : f);
}
#define A_PLANE(pf) a_plane(a_slots, (pf) / frames, (pf) % frames, first_frame, frames_total)

// Decides bands of kernel rows of a (probe, frame) clean without rasterising them, when both
// planes certainly own every pixel of the band (band_covered) and their code bounds over it
// exclude a fight: LEQUAL: B's smallest code above A's largest (log depth: by LOG_CODE_SLACK more,
// as for pieces), or, where that fails, the gap certificate (plane_gap_range, frag_gap_clear).
// Most probes of a search's descent from s = z are decided here. A band that is not decided goes
// through mts_raster row by row, so the answer never depends on this pass, only the work does.
// Global id: (probe * frames + frame) * bands + band.
__kernel void mts_frame_bounds(__global const float* restrict probes, __global const float* restrict tris,
                               __global const uint* restrict vflags, __global const float* restrict a_tris,
                               __global const uint* restrict a_vflags,
                               __global const uint* restrict a_bands, __global const uint* restrict a_slots,
                               const uint first_frame, const uint frames_total, const uint kernel_w,
                               const uint kernel_h, const float origin_x, const float origin_y,
                               const uint frames, const uint bands, const uint band_rows,
                               __global uint* restrict decided, const uint items) {
  const uint id = get_global_id(0);
  if (id >= items) return;
  const uint pf = id / bands, band = id - pf * bands;
  const uint ap = A_PLANE(pf);
  __global const float* P = probes + (pf / frames) * PROBE_STRIDE;
  __global uint* out = decided + (size_t)id * DECIDED_WORDS;
  __global const float* TB = tris + (size_t)pf * PLANE_STRIDE;
  __global const float* ref = a_tris + (size_t)ap * PLANE_STRIDE;
  const int finite = !((a_vflags[ap] | vflags[pf]) & V_NONFINITE);
  const uint oriented = finite && b_keeps_orientation(ref, TB) ? DV_ORIENTED : 0u;
  ((__global float*)out)[DW_MOVED] = finite ? b_moved_from_a(ref, TB) : INFINITY;
  out[DW_VERDICT] = D_RASTER | oriented;
  __global const uint* a = a_bands + ((size_t)ap * bands + band) * BAND_WORDS;
  if (!band_covered(a_vflags[ap], band) || !band_covered(vflags[pf], band) || a[2]) return;
  const int r0 = (int)(band * band_rows), r1 = min((int)kernel_h, r0 + (int)band_rows);
  const code_bounds_t b = plane_code_bounds(TB, P, origin_x, origin_y, (int)kernel_w, r0, r1);
  if (b.bad) return;
#if COMPARE_GREATER
  uint clean = b.hi + LOG_SLACK_OR_0 < (ulong)a[0];
#else
  uint clean = b.lo > (ulong)a[1] + LOG_SLACK_OR_0;
#endif
#if GAP_CERT
  if (!clean) {
    const double2 g = plane_gap_range(TB, ref, origin_x, origin_y, (int)kernel_w, r0, r1);
    __global const float* ga = (__global const float*)a;
#if DEPTH_FROM == 2
    clean = frag_gap_clear(P, ref, (double2)(ga[BW_GAP_LO], ga[BW_GAP_HI]), g, origin_x, origin_y,
                           (int)kernel_w, r0, r1);
#elif COMPARE_GREATER
    clean = (double)ga[BW_GAP_LO] - g.y > GAP_STEP;
#else
    clean = g.x - (double)ga[BW_GAP_HI] > GAP_STEP;
#endif
  }
#endif
  /* Not clean, but both planes are finite and unclipped at every pixel of the band (their bounds
   * are not bad), so the status of every piece's ends is known. What the end-code pass could still
   * do is exclude a piece whose B codes all clear A's, which near the MTS, where rows are
   * rasterised, rarely happens: mts_raster goes straight to the pixel loop. Both paths give the
   * same row verdict and count; only the work differs. If A's lowest code is at or above code(T)
   * (T = df_order_exact_from), every depth of A is at or above T, and the pixel loop can compare
   * depths instead of codes. */
  const uint from = df_order_exact_from(DF_FORMAT_FROM_DEFINES());
  const int ordered = from <= 0x3f800000u && a[0] >= df_encode(as_float(from), DF_FORMAT_FROM_DEFINES());
  out[DW_VERDICT] = (clean ? D_CLEAN : ordered ? D_ORDERED : D_INSIDE) | oriented;
}

// The fight mask of a piece [x, x_end) whose fragments are all covered and inside (finite,
// unclipped): codes compared, or depths where the band is D_ORDERED, or plane A's cached codes
// (ca, CACHE_A_CODES) against B's. A piece of 16 pixels or more is taken in chunks of 16 from x,
// the last one ending at x_end: it overlaps the one before, and evaluating pixels of the same
// piece twice leaves the OR as it is, so no lane needs masking. A shorter piece is one chunk with
// the lanes past its end off.
// always_inline: with two call sites PoCL's compiler kept it out of line (its own symbol in perf),
// and log_fragment's at_mts went from 1.8 to 2.2 ns/pair; inlined, 1.4.
__attribute__((always_inline)) static inline int16 inside_piece16(row_plane16_t ra, row_plane16_t rb,
                                                                  __global const float* P, float ox, int x,
                                                                  int x_end, int ordered,
                                                                  __global const uint* ca) {
  /* pixel centres step by exactly 16: ox is an integer and coordinates stay below 2^15
   * (host/model/scene.cpp kMaxKernelSide), so (ox + idx) + 0.5f is exact for every idx */
#define PX16(I0) ((ox + convert_float16((I0) + LANES)) + 0.5f)
#define PIECE_FIGHTS(FIGHT16)                                                                  \
  {                                                                                            \
    if (x_end - x < 16) return ((x + LANES) < x_end) & FIGHT16(PX16(x), x);                    \
    int16 fight_ = (int16)0;                                                                   \
    const float16 px0_ = PX16(x);                                                              \
    float16 px_ = px0_;                                                                        \
    for (int i0_ = x; i0_ < x_end - 16; i0_ += 16, px_ += 16.0f) fight_ |= FIGHT16(px_, i0_); \
    return fight_ | FIGHT16(px0_ + (float)(x_end - 16 - x), x_end - 16); /* exact, as above */ \
  }
#define CACHED_FIGHTS16(PX, I0) fights16(vload16(0, ca + (I0)), inside_code16(rb, P, (PX)))
#define ORDERED_FIGHTS16(PX, I0) ordered_fights16(depth16(ra, P, (PX)).d, depth16(rb, P, (PX)).d)
#define CODE_FIGHTS16(PX, I0) fights16(inside_code16(ra, P, (PX)), inside_code16(rb, P, (PX)))
#if CACHE_A_CODES
  if (ca) PIECE_FIGHTS(CACHED_FIGHTS16)
#endif
  if (ordered) PIECE_FIGHTS(ORDERED_FIGHTS16) /* a loop of its own: a select inside one would
                                                  compute both sides */
  PIECE_FIGHTS(CODE_FIGHTS16)
#undef CODE_FIGHTS16
#undef ORDERED_FIGHTS16
#undef CACHED_FIGHTS16
#undef PIECE_FIGHTS
#undef PX16
}

// One kernel row of one (probe, frame). The row splits into pieces where both planes' covering
// triangles stay the same; within a piece each plane's depth is one plane equation, monotone in
// px (every rounding step of it is monotone), and so is its stored code. The ends of all pieces
// are evaluated together, 16 pieces per vector: a piece whose end codes already exclude a fight
// (LEQUAL: B's smaller end code above A's larger) is decided without touching its inside, and a
// piece of one or two pixels is decided by its ends outright. Only the rest is evaluated pixel by
// pixel, 16 at a time. Log depth is monotone only up to the library log's error (OpenCL 1.2
// allows 3 ulp): its end codes must clear the bound by LOG_CODE_SLACK (host/runtime/kernel_variant.cpp),
// the most codes that error can move a code either way at both ends of both planes.
// Pieces are then taken left to right and the row stops after the first that fights. In a band
// mts_frame_bounds certified inside (D_INSIDE, D_ORDERED) there is no end pass, and the whole row
// is evaluated first with one reduction; only a row that fights is then taken piece by piece.
// Global id: (row, visit, probe); results at (probe * frames + visit) * kernel_h + row.
__kernel void mts_raster(__global const float* restrict probes, __global const float* restrict tris,
                         __global const uint* restrict vflags, __global const float* restrict a_tris,
                         __global const uint* restrict a_vflags, __global const uint* restrict a_rows,
                         __global const uint* restrict a_slots, const uint first_frame,
                         __global const uint* restrict a_codes, const uint frames_total, const uint kernel_w,
                         const uint kernel_h, const float origin_x, const float origin_y, const uint frames,
                         __global const uint* restrict decided, const uint bands, const uint band_rows,
                         const uint shortcuts, __global uint* restrict result) {
  /* a 3-D range (row, visit, probe), so no work-item divides to find them */
  const uint row = get_global_id(0), visit = get_global_id(1), probe = get_global_id(2);
  if (row >= kernel_h) return;
  const uint pf = probe * frames + visit;
  const uint id = pf * kernel_h + row;
  __global const float* P = probes + probe * PROBE_STRIDE;
  const uint ap = a_plane(a_slots, probe, visit, first_frame, frames_total);
  if ((a_vflags[ap] | vflags[pf]) & V_NONFINITE) {
    result[id] = R_NONFINITE;
    return;
  }
  __global const uint* dec = decided + (size_t)(pf * bands + row / band_rows) * DECIDED_WORDS;
  const uint band_verdict = dec[DW_VERDICT] & D_MASK;
  if (band_verdict == D_CLEAN) { /* clean from code bounds: mts_frame_bounds */
    result[id] = R_BOUNDS | (kernel_w << R_COUNT_SHIFT);
    return;
  }
  __global const float* TA = a_tris + (size_t)ap * PLANE_STRIDE;
  __global const float* TBp = tris + (size_t)pf * PLANE_STRIDE;
  const int W = (int)kernel_w;
  const float py = origin_y + (float)row + 0.5f;
  __global const uint* rec = a_rows + ((size_t)ap * kernel_h + row) * ROW_WORDS;
  const int cached = rec[RW_N] > 0u;
  const int b_is_a = shortcuts && cached &&
                     b_coverage_is_a(((__global const float*)dec)[DW_MOVED], dec[DW_VERDICT] & DV_ORIENTED,
                                     TBp, vflags[pf], (int)row, rec);
  const int inside = band_verdict == D_INSIDE || band_verdict == D_ORDERED;
  const int ordered = band_verdict == D_ORDERED;
#if CACHE_A_CODES
  __global const uint* ca = cached ? a_codes + ((size_t)ap * kernel_h + row) * (kernel_w + 16u) : 0;
#else
  __global const uint* ca = 0;
#endif
  if (inside && b_is_a) {
    /* The common row near the MTS: every piece covered and inside, and the pieces are plane A's
     * cached segments, taken straight from the record, one reduction for the whole row. A row
     * that fights goes on below, which finds its first fighting piece (and so its count). */
    const int n = (int)rec[RW_N];
    int16 fight = (int16)0;
    for (int k = 0; k < n; ++k) {
      const int t = (int)rec[RW_T + k];
      fight |= inside_piece16(broadcast16(row_plane(TA, t, py)), broadcast16(row_plane(TBp, t, py)), P,
                              origin_x, (int)rec[RW_X + k], (int)rec[RW_X + k + 1], ordered, ca);
    }
    if (!any16(fight)) {
      result[id] = R_REUSED | ((rec[RW_X + n] - rec[RW_X]) << R_COUNT_SHIFT);
      return;
    }
  }
  int seg_xa[MAX_SEG + 1], seg_ta[MAX_SEG], seg_xb[MAX_SEG + 1], seg_tb[MAX_SEG];
  int na = (int)rec[RW_N];
  if (cached) {
    for (int k = 0; k <= na; ++k) seg_xa[k] = (int)rec[RW_X + k];
    for (int k = 0; k < na; ++k) seg_ta[k] = (int)rec[RW_T + k];
  } else {
    na = row_segments(TA, py, origin_x, W, seg_xa, seg_ta);
  }

  /* the pieces, and the end-point verdict of each: R_* bits, or ~0u for "look inside" */
  int px_start[MAX_PIECES], px_end[MAX_PIECES], p_ta[MAX_PIECES], p_tb[MAX_PIECES];
  uint verdict[MAX_PIECES];
  int ends_ok[MAX_PIECES]; /* both planes finite and unclipped at both ends, so inside too */
  int np = 0;
  if (b_is_a) { /* B's segments are A's: the pieces are A's segments, no merge needed */
    for (int k = 0; k < na; ++k)
      if (seg_xa[k + 1] > seg_xa[k]) {
        px_start[np] = seg_xa[k];
        px_end[np] = seg_xa[k + 1];
        p_ta[np] = p_tb[np] = seg_ta[k];
        ++np;
      }
  } else {
    row_segments(TBp, py, origin_x, W, seg_xb, seg_tb);
    FOR_EACH_PIECE({
      px_start[np] = x;
      px_end[np] = x_end;
      p_ta[np] = ta;
      p_tb[np] = tb;
      ++np;
    })
  }
  if (inside) {
    if (!b_is_a) { /* as above, over the merged pieces (b_is_a rows here are known to fight) */
      int16 fight = (int16)0;
      uint all = 0u;
      for (int i = 0; i < np; ++i) {
        fight |= inside_piece16(broadcast16(row_plane(TA, p_ta[i], py)),
                                broadcast16(row_plane(TBp, p_tb[i], py)), P, origin_x, px_start[i], px_end[i],
                                ordered, ca);
        all += (uint)(px_end[i] - px_start[i]);
      }
      if (!any16(fight)) {
        result[id] = all << R_COUNT_SHIFT;
        return;
      }
    }
    for (int i = 0; i < np; ++i) { /* a row that fights: its pieces one by one, below */
      verdict[i] = ~0u;
      ends_ok[i] = 1;
    }
  } else
  for (int g = 0; g < np; g += 16) {
    float c0a[16], sla[16], x0a[16], rta[16], c0b[16], slb[16], x0b[16], rtb[16], e0[16], e1[16];
    for (int k = 0; k < 16; ++k) {
      const int i = min(g + k, np - 1);
      const row_plane_t ra = row_plane(TA, max(p_ta[i], 0), py), rb = row_plane(TBp, max(p_tb[i], 0), py);
      c0a[k] = ra.c0; sla[k] = ra.slope; x0a[k] = ra.x0; rta[k] = ra.row_term;
      c0b[k] = rb.c0; slb[k] = rb.slope; x0b[k] = rb.x0; rtb[k] = rb.row_term;
      e0[k] = origin_x + (float)px_start[i] + 0.5f;
      e1[k] = origin_x + (float)(px_end[i] - 1) + 0.5f;
    }
    row_plane16_t ra, rb;
    ra.c0 = vload16(0, c0a); ra.slope = vload16(0, sla); ra.x0 = vload16(0, x0a); ra.row_term = vload16(0, rta);
    rb.c0 = vload16(0, c0b); rb.slope = vload16(0, slb); rb.x0 = vload16(0, x0b); rb.row_term = vload16(0, rtb);
    const float16 p0 = vload16(0, e0), p1 = vload16(0, e1);
    const frag16_t a0 = fragment16(ra, P, p0), a1 = fragment16(ra, P, p1);
    const frag16_t b0 = fragment16(rb, P, p0), b1 = fragment16(rb, P, p1);
    const int16 nf = a0.nonfinite | a1.nonfinite | b0.nonfinite | b1.nonfinite;
    const int16 cl = a0.clipped | a1.clipped | b0.clipped | b1.clipped;
    const int16 fight_ends = fights16(a0.code, b0.code) | fights16(a1.code, b1.code);
    const ulong16 slack = (ulong16)LOG_SLACK_OR_0;
#if COMPARE_GREATER
    const int16 excluded =
        convert_int16(convert_ulong16(max(b0.code, b1.code)) + slack < convert_ulong16(min(a0.code, a1.code)));
#else
    const int16 excluded =
        convert_int16(convert_ulong16(min(b0.code, b1.code)) > convert_ulong16(max(a0.code, a1.code)) + slack);
#endif
    int nfk[16], clk[16], fek[16], exk[16];
    vstore16(nf, 0, nfk);
    vstore16(cl, 0, clk);
    vstore16(fight_ends, 0, fek);
    vstore16(excluded, 0, exk);
    for (int k = 0; k < 16 && g + k < np; ++k) {
      const int i = g + k;
      const int len = px_end[i] - px_start[i];
      uint v = ~0u;
      if (len <= 2) { /* the ends are the whole piece */
        v = nfk[k] ? R_NONFINITE : clk[k] ? R_CLIPPED : fek[k] ? R_FIGHT : 0u;
      }
      else if (!nfk[k] && !clk[k] && exk[k]) {
        v = 0u;
      }
      verdict[i] = v;
      ends_ok[i] = !nfk[k] && !clk[k];
    }
  }

  uint flags = 0u, count = 0u;
  for (int i = 0; i < np; ++i) {
    const int x = px_start[i], x_end = px_end[i];
    count += (uint)(x_end - x);
    if (p_ta[i] < 0 || p_tb[i] < 0) {
      flags |= R_UNCOVERED;
      continue;
    }
    uint piece = verdict[i];
    if (piece == ~0u) {
      piece = 0u;
      const row_plane16_t ra = broadcast16(row_plane(TA, p_ta[i], py));
      const row_plane16_t rb = broadcast16(row_plane(TBp, p_tb[i], py));
      if (ends_ok[i]) { /* only the codes matter: one reduction per piece */
        piece = any16(inside_piece16(ra, rb, P, origin_x, x, x_end, ordered, ca)) ? R_FIGHT : 0u;
      } else
      for (int i0 = x; i0 < x_end; i0 += 16) {
        const int16 idx = i0 + LANES;
        const int16 active = idx < x_end;
        const float16 px = (origin_x + convert_float16(idx)) + 0.5f;
        const frag16_t fa = fragment16(ra, P, px), fb = fragment16(rb, P, px);
        const int16 nf = active & (fa.nonfinite | fb.nonfinite);
        const int16 cl = active & ~nf & (fa.clipped | fb.clipped);
        const int16 ok = active & ~(fa.nonfinite | fb.nonfinite | fa.clipped | fb.clipped);
        piece |= (any16(nf) ? R_NONFINITE : 0u) | (any16(cl) ? R_CLIPPED : 0u) |
                 (any16(ok & fights16(fa.code, fb.code)) ? R_FIGHT : 0u);
      }
    }
    flags |= piece;
    if (piece & R_FIGHT) break;
  }
  result[id] = flags | (b_is_a ? R_REUSED : 0u) | (count << R_COUNT_SHIFT);
}

// Audit of the coverage shortcut, for the tests: per (probe, frame, row) of a launch laid out as
// mts_raster's, bit 0: plane B's own coverage (row_segments) differs from plane A's cached one;
// bit 1: b_coverage_is_a says they are the same; bit 2: both (the shortcut would be wrong);
// bit 3: the row is cached.
__kernel void mts_coverage_audit(__global const float* restrict tris, __global const uint* restrict vflags,
                                 __global const float* restrict a_tris, __global const uint* restrict a_vflags,
                                 __global const uint* restrict a_rows, __global const uint* restrict a_slots,
                                 const uint first_frame, const uint frames_total, const uint kernel_w,
                                 const uint kernel_h, const float origin_x, const float origin_y,
                                 const uint frames, __global uint* restrict out, const uint items) {
  const uint id = get_global_id(0);
  if (id >= items) return;
  const uint pf = id / kernel_h, row = id - pf * kernel_h;
  const uint ap = A_PLANE(pf);
  __global const float* TA = a_tris + (size_t)ap * PLANE_STRIDE;
  __global const float* TB = tris + (size_t)pf * PLANE_STRIDE;
  __global const uint* rec = a_rows + ((size_t)ap * kernel_h + row) * ROW_WORDS;
  out[id] = 0u;
  const int n = (int)rec[RW_N];
  if (n == 0 || ((a_vflags[ap] | vflags[pf]) & V_NONFINITE)) return;
  int seg_x[MAX_SEG + 1], seg_t[MAX_SEG];
  const int nb = row_segments(TB, origin_y + (float)row + 0.5f, origin_x, (int)kernel_w, seg_x, seg_t);
  int differs = nb != n;
  for (int k = 0; k < n && !differs; ++k)
    differs = seg_x[k] != (int)rec[RW_X + k] || seg_t[k] != (int)rec[RW_T + k];
  const int same =
      b_coverage_is_a(b_moved_from_a(TA, TB), b_keeps_orientation(TA, TB), TB, vflags[pf], (int)row, rec);
  out[id] = 8u | (differs ? 1u : 0u) | (same ? 2u : 0u) | (differs && same ? 4u : 0u);
}

// The buffer layout the host allocates by: floats per plane record, words per cached row of plane A,
// words per band of plane A, words per band of mts_frame_bounds' verdicts.
__kernel void mts_layout(__global uint* restrict out) {
  out[0] = PLANE_STRIDE;
  out[1] = ROW_WORDS;
  out[2] = BAND_WORDS;
  out[3] = DECIDED_WORDS;
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
        const int sa = ta < 0 ? S_UNCOVERED : na[k] ? S_NONFINITE : la[k] ? S_CLIPPED : S_OK;
        const int sb = tb < 0 ? S_UNCOVERED : nb[k] ? S_NONFINITE : lb[k] ? S_CLIPPED : S_OK;
        __global uint* o = out + 4u * (row * kernel_w + (uint)(i0 + k));
        o[0] = sa == S_OK ? ca[k] : 0u;
        o[1] = sb == S_OK ? cb[k] : 0u;
        o[2] = (uint)sa;
        o[3] = (uint)sb;
      }
    }
  })
}
