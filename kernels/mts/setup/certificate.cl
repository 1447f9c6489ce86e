// The coverage certificate of a plane's set-up: which kernel pixels its triangles provably own
// (covers_kernel), and the bands a sliver triangle leaves out of it (mark_sliver).

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
// known, are named in the flags (bit MTS_V_BAND_SHIFT + band, bands of band_rows rows).
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
        float E = MTS_EDGE_FUNCTION(ax, ay, dx, dy, px, py);
        if (inner < 0.0f) E = -E;
        if (!(E > margin)) return 0u;
      }
    }
  }
  return MTS_V_COVERS | (sliver_bands ? MTS_V_SLIVERS : 0u) | (sliver_bands << MTS_V_BAND_SHIFT);
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
// number) marks every row of its box. A band past MTS_V_MAX_BANDS clears *shapely.
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
      if ((uint)j / band_rows >= MTS_V_MAX_BANDS) {
        *shapely = 0u;
        return;
      }
      *slivers |= 1u << ((uint)j / band_rows);
    }
  }
}
