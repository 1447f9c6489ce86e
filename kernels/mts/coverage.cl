// Which triangle covers which kernel pixels of a row, and when plane B's coverage is plane A's.

// Does the pixel centre px (row py) pass edge e of triangle R? The same float expression for every
// pixel, so span search below and the host reference agree on every pixel.
static inline int edge_passes(__global const float* R, uint bits, int e, float px, float py) {
  const float ax = R[4 * e], ay = R[4 * e + 1], dx = R[4 * e + 2], dy = R[4 * e + 3];
  float E = MTS_EDGE_FUNCTION(ax, ay, dx, dy, px, py);
  if (bits & MTS_BIT_NEGATE(e)) E = -E;
  return MTS_EDGE_PASSES(E, (bits & MTS_BIT_OWNS(e)) != 0u);
}

// Along a row, px - ax, dy * (.) and C - (.) are all monotone in px, so each edge's test is
// monotone: the pixels passing it form a prefix or a suffix of the row, and the pixels inside the
// triangle form one interval. Found here by walking from the analytic crossing to the exact
// boundary of the very test a per-pixel rasteriser would do.
static inline void edge_range(__global const float* R, uint bits, int e, float py, float ox, int W,
                              int* lo, int* hi) {
  const float dy = R[4 * e + 3];
  const float sdy = (bits & MTS_BIT_NEGATE(e)) ? -dy : dy;
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
  const float cross =
      R[4 * e] + (py - R[4 * e + 1]) * R[MTS_T_DXDY + e] - ox - 0.5f; /* E ~ 0 here */
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
// Sorts key[0..n) ascending, stable, by insertion (n is small: the spans or boundaries of one
// row), moving the payloads p1 and p2 along with the keys; either may be 0 (none), which the
// compiler folds away where the call passes a constant.
static inline void insertion_sort(int* key, int* p1, int* p2, int n) {
  for (int i = 1; i < n; ++i) {
    const int k = key[i], a = p1 ? p1[i] : 0, b = p2 ? p2[i] : 0;
    int j = i - 1;
    while (j >= 0 && key[j] > k) {
      key[j + 1] = key[j];
      if (p1) p1[j + 1] = p1[j];
      if (p2) p2[j + 1] = p2[j];
      --j;
    }
    key[j + 1] = k;
    if (p1) p1[j + 1] = a;
    if (p2) p2[j + 1] = b;
  }
}

// The triangle records kernel rows with pixel centres py0..py1 can meet in plane T: those of the
// quad rows whose y-range holds one of them, a run of records from *first to before *end (one or
// two quad rows for one row; which of their triangles meet it, row_segments decides).
static inline void records_meeting(__global const float* T, float py0, float py1, int* first,
                                   int* end) {
  uint quad_rows = 0u;
  for (int qj = 0; qj < GRID; ++qj)
    if (T[Q_YRANGE + 2 * qj] <= py1 && py0 <= T[Q_YRANGE + 2 * qj + 1]) quad_rows |= 1u << qj;
  quad_row_records(T, quad_rows, first, end);
}

#define MAX_SEG (2 * NT + 2)
static inline int row_segments(__global const float* T, float py, float ox, int W, int* seg_x,
                               int* seg_t) {
  __global const uint* TB = (__global const uint*)T;
  /* Every edge's passing pixels [elo, ehi), 16 edges at a time: an edge passing or failing at
   * both ends of the row passes or fails all of it (the test is monotone); a crossing edge's
   * boundary is taken where the test flips between the guessed pixel and the one before it.
   * Lanes where that check fails (-2) are placed by the scalar walk below. */
  __global const float* SA = T + NT * MTS_TRI_STRIDE;
  int elo[NE_PAD], ehi[NE_PAD];
  const float px_first = ox + 0.5f, px_last = ox + (float)(W - 1) + 0.5f;
  /* only the edges of the records the row can meet */
  int t_first, t_end;
  records_meeting(T, py, py, &t_first, &t_end);
  for (int g = 3 * t_first / 16 * 16; g < 3 * t_end; g += 16) {
    const float16 ax = vload16(0, SA + MTS_E_AX * NE_PAD + g),
                  ay = vload16(0, SA + MTS_E_AY * NE_PAD + g);
    const float16 dx = vload16(0, SA + MTS_E_DX * NE_PAD + g),
                  dy = vload16(0, SA + MTS_E_DY * NE_PAD + g);
    const float16 dxdy = vload16(0, SA + MTS_E_DXDY * NE_PAD + g);
    const uint16 eb = vload16(0, (__global const uint*)SA + MTS_E_BITS * NE_PAD + g);
    const int16 negate = convert_int16((eb & (uint16)1u) != (uint16)0u);
    const int16 owns = convert_int16((eb & (uint16)2u) != (uint16)0u);
    const float16 c = dx * (py - ay);
#define EDGE_PASS16(PX)              \
  ({                                 \
    float16 E_ = c - dy * ((PX)-ax); \
    E_ = negate ? -E_ : E_;          \
    MTS_EDGE_PASSES(E_, owns);       \
  })
    const int16 p0 = EDGE_PASS16((float16)px_first);
    const int16 p1 = EDGE_PASS16((float16)px_last);
    const float16 sdy = negate ? -dy : dy;
    const float16 cross = ax + (py - ay) * dxdy - ox - 0.5f;
    const int16 gi =
        clamp(convert_int16(ceil(clamp(cross, -1.0f, (float)W + 1.0f))), 1, max(W - 1, 1));
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
  for (int t = t_first; t < t_end; ++t) {
    __global const float* R = T + t * MTS_TRI_STRIDE;
    const uint bits = TB[t * MTS_TRI_STRIDE + MTS_T_BITS];
    if (!(bits & MTS_BIT_VALID) || !(R[MTS_T_YMIN] <= py && py <= R[MTS_T_YMAX])) continue;
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
  insertion_sort(lo, hi, tri, n);
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
  insertion_sort(bx, 0, 0, nb);
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

// The segments of a cached row record (mts_a_rows) into seg_x, seg_t; returns their number.
static inline int record_segments(__global const uint* rec, int* seg_x, int* seg_t) {
  const int n = (int)rec[MTS_RW_N];
  for (int k = 0; k <= n; ++k) seg_x[k] = (int)rec[MTS_RW_X + k];
  for (int k = 0; k < n; ++k) seg_t[k] = (int)rec[MTS_RW_T + k];
  return n;
}

// Plane B is plane A moved along the view direction and scaled with its distance, so both project
// to the same window triangles in exact arithmetic; in binary32 B's vertices lie some delta
// (~1e-4 px) from A's. Returns a margin: for any B whose edges join A's vertices and lie within
// less than it of A's (per coordinate, as b_moved_from_a measures), and which owns each kernel
// pixel through exactly one triangle (MTS_V_COVERS), B's coverage of the row is A's segments.
// Proof: each segment's triangle passes its three edge tests at the segment's first and last pixel
// in B too, so (each test being monotone along the row) at every pixel of the segment, and the one
// triangle that passes a pixel owns it; and the row stays inside each triangle's y-range, which
// row_segments also asks. The edge value E = dx (py - ay) - dy (px - ax) of a pixel moves by at
// most d (|dx| + |dy| + 2|py - ay| + 2|px - ax|) + 4 d^2 when the edge's anchor (ax, ay) moves by d
// and its direction (dx, dy) by 2 d per coordinate (as when its vertices move by d;
// b_moved_from_a), and each binary32 evaluation (fused or not) lies within 4.1 eps (|dx (py - ay)|
// + |dy (px - ax)|) of its exact value, so a pass with E above twice that rounding bound plus the
// movement survives; the margin is the d at which the movement would take half of what is left
// over, with 1 % slack for the margin's own rounding. 0 when A leaves a pixel uncovered or a test
// sits at its rounding bound. The argument reads only the triangle records, so it holds for the
// clip stage's fans as for the grid's triangles.
static inline float coverage_margin(__global const float* T, float py, float ox, int n,
                                    const int* seg_x, const int* seg_t) {
  __global const float* SA = T + NT * MTS_TRI_STRIDE;
  __global const uint* SB = (__global const uint*)SA + MTS_E_BITS * NE_PAD;
  const float eps = 0x1.0p-24f;
  float margin = INFINITY;
  /* Per segment its triangle's three edges (contiguous in the edge records) at both ends, in
   * lanes 0-5 of a float8 (lanes 6, 7 repeat lanes 0, 1). The square-root term is monotone in r,
   * so one square root of the smallest r serves every test. */
  float8 q = (float8)INFINITY, r_min = (float8)INFINITY;
  int8 at_bound = (int8)0; /* tests at their rounding bound: checked once, after the loop */
  for (int k = 0; k < n; ++k) {
    const int t = seg_t[k];
    if (t < 0) return 0.0f;
    __global const float* R = T + t * MTS_TRI_STRIDE;
    margin = fmin(margin, fmin(py - R[MTS_T_YMIN], R[MTS_T_YMAX] - py));
    const float px0 = ox + (float)seg_x[k] + 0.5f, px1 = ox + (float)(seg_x[k + 1] - 1) + 0.5f;
#define EDGES8(F, FIELD)                         \
  ({                                             \
    const F##3 v3_ = vload3(0, (FIELD) + 3 * t); \
    (F##8)(v3_, v3_, v3_.s01);                   \
  })
    const float8 ax = EDGES8(float, SA + MTS_E_AX * NE_PAD),
                 ay = EDGES8(float, SA + MTS_E_AY * NE_PAD);
    const float8 dx = EDGES8(float, SA + MTS_E_DX * NE_PAD),
                 dy = EDGES8(float, SA + MTS_E_DY * NE_PAD);
    const uint8 bits = EDGES8(uint, SB);
#undef EDGES8
    const float8 px = (float8)(px0, px0, px0, px1, px1, px1, px0, px0);
    const float8 u = py - ay, v = px - ax;
    float8 E = dx * u - dy * v;
    E = (bits & 1u) != 0u ? -E : E;
    const float8 r = E - 16.0f * eps * (fabs(dx * u) + fabs(dy * v));
    at_bound |= !(r > 0.0f);
    const float8 c = 1.01f * (fabs(dx) + fabs(dy) + 2.0f * fabs(u) + 2.0f * fabs(v));
    q = fmin(q, r / (2.2f * c));
    r_min = fmin(r_min, r);
  }
  if (any(at_bound)) return 0.0f;
  const float4 q4 = fmin(q.lo, q.hi), r4 = fmin(r_min.lo, r_min.hi);
  const float2 q2 = fmin(q4.lo, q4.hi), r2 = fmin(r4.lo, r4.hi);
  margin = fmin(margin, fmin(fmin(q2.x, q2.y), 0.99f * sqrt(fmin(r2.x, r2.y) / 8.4f)));
  return 0.99f * margin;
}

// How far plane B's triangle records lie from plane A's, as the d of coverage_margin, over
// records first..end - 1 (those A's rows of a band can meet, records_meeting): the largest
// difference of an edge's anchor (ax, ay), of half its direction (dx, dy) and of a triangle's
// y-range, rounded up. For edges between the same vertices (b_keeps_a_edges) this is at most how
// far B's vertices lie from A's, plus the rounding of dx and dy; it reads what the edge tests read,
// so it covers the clip stage's new vertices too. A difference between unequal infinities or with a
// NaN is infinite.
static inline float16 moved16(float16 a, float16 b) {
  const float16 d = fabs(b - a);
  return a == b ? (float16)0.0f : d <= INFINITY ? d : (float16)INFINITY;
}

static inline float b_moved_from_a(__global const float* TA, __global const float* TB, int first,
                                   int end) {
  __global const float* EA = TA + NT * MTS_TRI_STRIDE;
  __global const float* EB = TB + NT * MTS_TRI_STRIDE;
  float16 m = (float16)0.0f;
  for (int g = 3 * first / 16 * 16; g < 3 * end; g += 16) {
    m = fmax(
        m, moved16(vload16(0, EA + MTS_E_AX * NE_PAD + g), vload16(0, EB + MTS_E_AX * NE_PAD + g)));
    m = fmax(
        m, moved16(vload16(0, EA + MTS_E_AY * NE_PAD + g), vload16(0, EB + MTS_E_AY * NE_PAD + g)));
    m = fmax(m, 0.5f * moved16(vload16(0, EA + MTS_E_DX * NE_PAD + g),
                               vload16(0, EB + MTS_E_DX * NE_PAD + g)));
    m = fmax(m, 0.5f * moved16(vload16(0, EA + MTS_E_DY * NE_PAD + g),
                               vload16(0, EB + MTS_E_DY * NE_PAD + g)));
  }
  const float8 m8 = fmax(m.lo, m.hi);
  const float4 m4 = fmax(m8.lo, m8.hi);
  const float2 m2 = fmax(m4.lo, m4.hi);
  /* the y-ranges, four triangles a vector (a scalar maximum was one long dependency chain, a
   * quarter of mts_a_rows' time); a triangle past end repeats the last one */
  float8 y = (float8)0.0f;
  for (int t = first; t < end; t += 4) {
    const int t1 = min(t + 1, end - 1), t2 = min(t + 2, end - 1), t3 = min(t + 3, end - 1);
#define YRANGES8(T)                                           \
  (float8)(vload2(0, (T) + t * MTS_TRI_STRIDE + MTS_T_YMIN),  \
           vload2(0, (T) + t1 * MTS_TRI_STRIDE + MTS_T_YMIN), \
           vload2(0, (T) + t2 * MTS_TRI_STRIDE + MTS_T_YMIN), \
           vload2(0, (T) + t3 * MTS_TRI_STRIDE + MTS_T_YMIN))
    const float8 ya = YRANGES8(TA), yb = YRANGES8(TB);
#undef YRANGES8
    const float8 d = fabs(yb - ya);
    y = fmax(y, ya == yb ? (float8)0.0f : d <= INFINITY ? d : (float8)INFINITY);
  }
  const float4 y4 = fmax(y.lo, y.hi);
  const float2 y2 = fmax(y4.lo, y4.hi);
  return 1.0001f * fmax(fmax(m2.x, m2.y), fmax(y2.x, y2.y));
}

// Whether every edge of plane B among records first..end - 1 joins the same two vertices as A's
// (the clip stage's fans alike, however they fill the records) with A's orientation: its edge
// test negated alike.
static inline int b_keeps_a_edges(__global const float* TA, __global const float* TB, int first,
                                  int end) {
  __global const uint* a = (__global const uint*)(TA + NT * MTS_TRI_STRIDE) + MTS_E_BITS * NE_PAD;
  __global const uint* b = (__global const uint*)(TB + NT * MTS_TRI_STRIDE) + MTS_E_BITS * NE_PAD;
  uint16 differ = (uint16)0u;
  for (int g = 3 * first / 16 * 16; g < 3 * end; g += 16)
    differ |= (vload16(0, a + g) ^ vload16(0, b + g)) & ~2u;
  return !any(differ != (uint16)0u);
}

// For the rows [r0, r1) of a band, over the records they can meet in plane A (records_meeting):
// whether plane B's edges are A's (b_keeps_a_edges, returned as MTS_DV_ORIENTED or 0) and how far
// they moved (b_moved_from_a, *moved), as b_coverage_is_a asks for every row of the band.
static inline uint band_b_against_a(__global const float* TA, __global const float* TB,
                                    float origin_y, int r0, int r1, float* moved) {
  int first, end;
  records_meeting(TA, origin_y + (float)r0 + 0.5f, origin_y + (float)(r1 - 1) + 0.5f, &first, &end);
  *moved = b_moved_from_a(TA, TB, first, end);
  return b_keeps_a_edges(TA, TB, first, end) ? MTS_DV_ORIENTED : 0u;
}

// Whether plane B's coverage of a cached row of plane A is A's: B certified to own every pixel of
// the row through exactly one triangle (row_covered; a frame with a vertex near a pixel centre
// loses only that pixel's row), B within A's coverage margin (coverage_margin: moved is
// b_moved_from_a), and B's edges are A's (oriented: b_keeps_a_edges). The
// last two are per frame: mts_frame_bounds finds them once.
static inline int b_coverage_is_a(float moved, int oriented, __global const float* TB,
                                  uint vflags_b, int row, uint band_rows,
                                  __global const uint* rec) {
  return oriented && moved < ((__global const float*)rec)[MTS_RW_MARGIN] &&
         row_covered(TB, vflags_b, row, band_rows);
}
