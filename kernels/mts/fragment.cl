// Fragment depth and stored codes along a row, 16 pixels at a time, and the fight test.

// A triangle's interpolation set up for one row. PLANE_FORM 0: depth (or 1/w) = (c0 + slope *
// (px - x0)) + row_term, row_term = dzdy * (py - y0). PLANE_FORM 1 (llvmpipe): fma(dy, y,
// fma(slope, px - x0, c0)), y = py - y0: x0 = y0 = 0.5 make px - x0 and y the integer pixel
// coordinates. PLANE_FORM 2 (softpipe): per 2x2 quad from its even corner (qx, qy), z0 = (c0 +
// slope qx) + row_term, row_term = dy qy, then + slope on odd columns and + dy on odd rows, in
// that order; y is the pixel's integer row, whose parity says which.
// up: the direction an envelope's adversary moves the plane's codes (MTS_T_ADVERSARY; under
// ADVERSARY_CODES only).
typedef struct {
  float c0, slope, x0, row_term, dy, y, up;
} row_plane_t;

static inline row_plane_t row_plane(__global const float* T, int t, float py) {
  __global const float* R = T + t * MTS_TRI_STRIDE;
  row_plane_t rp;
  rp.x0 = R[MTS_T_X0];
  rp.y = py - R[MTS_T_Y0];
#if ADVERSARY_CODES
  rp.up = R[MTS_T_ADVERSARY];
#else
  rp.up = 0.0f;
#endif
#if DEPTH_FROM == 2
  rp.c0 = R[MTS_T_Q0];
  rp.slope = R[MTS_T_DQDX];
  rp.dy = R[MTS_T_DQDY];
#else
  rp.c0 = R[MTS_T_D0];
  rp.slope = R[MTS_T_DZDX];
  rp.dy = R[MTS_T_DZDY];
#endif
#if PLANE_FORM == 2
  rp.row_term = rp.dy * (rp.y - (float)((int)rp.y & 1)); /* the quad's even row */
#else
  rp.row_term = rp.dy * rp.y;
#endif
  return rp;
}

// Whether each plane's depth is monotone along a row, as every rounding step of a per-pixel form
// is: the corner bounds, the gap certificate and the decisions from a piece's ends rest on it.
// Quad increments (PLANE_FORM 2) are not: a pixel's value depends on its column's parity.
#define PLANE_MONOTONE (PLANE_FORM != 2)

// Row planes of 16 lanes: one triangle broadcast, or one triangle per lane (per piece).
typedef struct {
  float16 c0, slope, x0, row_term, dy, y, up;
} row_plane16_t;

static inline row_plane16_t broadcast16(row_plane_t rp) {
  row_plane16_t r;
  r.c0 = (float16)rp.c0;
  r.slope = (float16)rp.slope;
  r.x0 = (float16)rp.x0;
  r.row_term = (float16)rp.row_term;
  r.dy = (float16)rp.dy;
  r.y = (float16)rp.y;
  r.up = (float16)rp.up;
  return r;
}

// Row planes gathered one lane at a time (a piece's or a box corner's each), then taken as
// vectors.
typedef struct {
  float c0[16], slope[16], x0[16], row_term[16], dy[16], y[16], up[16];
} row_plane_lanes_t;

static inline void set_lane(row_plane_lanes_t* l, int k, row_plane_t rp) {
  l->c0[k] = rp.c0;
  l->slope[k] = rp.slope;
  l->x0[k] = rp.x0;
  l->row_term[k] = rp.row_term;
  l->dy[k] = rp.dy;
  l->y[k] = rp.y;
  l->up[k] = rp.up;
}

static inline row_plane16_t load_lanes(const row_plane_lanes_t* l) {
  row_plane16_t r;
  r.c0 = vload16(0, l->c0);
  r.slope = vload16(0, l->slope);
  r.x0 = vload16(0, l->x0);
  r.row_term = vload16(0, l->row_term);
  r.dy = vload16(0, l->dy);
  r.y = vload16(0, l->y);
  r.up = vload16(0, l->up);
  return r;
}

// The interpolated plane at 16 pixel centres, every lane rounding on its own.
static inline float16 plane_at16(row_plane16_t rp, float16 px) {
#if PLANE_FORM == 1
  return fma(rp.dy, rp.y, fma(rp.slope, px - rp.x0, rp.c0));
#elif PLANE_FORM == 2
  const float16 x = px - rp.x0;
  const int16 odd_x = (convert_int16(x) & 1) != 0, odd_y = (convert_int16(rp.y) & 1) != 0;
  const float16 z0 =
      (rp.c0 + rp.slope * (x - select((float16)0.0f, (float16)1.0f, odd_x))) + rp.row_term;
  const float16 z1 = select(z0, z0 + rp.slope, odd_x);
  return select(z1, z1 + rp.dy, odd_y);
#else
  return (rp.c0 + rp.slope * (px - rp.x0)) + rp.row_term;
#endif
}

// Depth and status of 16 fragments: depth (or 1/w) = (c0 + slope * (px - x0)) + row_term, every
// lane rounding on its own, as a scalar pipeline would. Masks are -1 / 0 per lane.
typedef struct {
  float16 d;
  int16 nonfinite, clipped;
} depth16_t;

#if FRAG_MEDIUMP
// The fragment shader below binary32 (interface/mediump_fragment.h; FRAG_MEDIUMP is its
// precision), lane by lane.
DP_MEDIUMP_FRAGMENT_DEFINE(mediump_depth, shader_log, shader_log2)
static inline float16 mediump_depth16(float16 q, __global const float* P) {
  float a[16];
  vstore16(q, 0, a);
  for (int k = 0; k < 16; ++k)
    a[k] =
        mediump_depth(FRAG_DEPTH, a[k], P[MTS_C_NEAR], P[MTS_C_RANGE], P[MTS_C_FAR], P[MTS_C_LOGK],
                      P[MTS_C_LOGL], P[MTS_C_THREEJS_FC], P[MTS_C_CESIUM_INV_LOG2], FRAG_MEDIUMP);
  return vload16(0, a);
}
#endif

// Depth and status of 16 fragments whose interpolated value (depth, or q = 1/w) is v.
static inline depth16_t depth_of_value16(float16 v, __global const float* P) {
  depth16_t r;
#if DEPTH_FROM == 2
  const float16 q = v;
  const float16 w = 1.0f / q;
  const int16 nf_w = !isfinite(w);
#if FRAG_DEPTH == 5
  /* Cesium (writeLogDepth): the varying (w - near) + 1.0, whose discard stands in for the clip
   * volume's near and far (its vertex stage clamps z_ndc into [-1, 1]) */
  const float16 from_near_plus_one = (w - P[MTS_C_NEAR]) + 1.0f;
  r.clipped = (from_near_plus_one <= 0.9999999f) || (from_near_plus_one > P[MTS_C_CESIUM_FAR1]);
#else
  r.clipped = (w < P[MTS_C_NEAR]) || (w > P[MTS_C_FAR]);
#endif
#if FRAG_MEDIUMP
  float16 d = mediump_depth16(q, P);
#elif FRAG_DEPTH == 1
  float16 d = (w - P[MTS_C_NEAR]) / P[MTS_C_RANGE];
#elif FRAG_DEPTH == 2
  float16 d = w / P[MTS_C_FAR];
#elif FRAG_DEPTH == 4 /* three.js: log2(vFragDepth) * logDepthBufFC * 0.5, vFragDepth = 1.0 + w */
  float16 d = (shader_log2_16(1.0f + w) * P[MTS_C_THREEJS_FC]) * 0.5f;
#elif FRAG_DEPTH == 5 /* log2(depth) * czm_oneOverLog2FarDepthFromNearPlusOne */
  float16 d = shader_log2_16(from_near_plus_one) * P[MTS_C_CESIUM_INV_LOG2];
#else
  float16 d = shader_log16(P[MTS_C_LOGK] * w + 1.0f) / P[MTS_C_LOGL];
#endif
  r.nonfinite = nf_w || isnan(d);
  r.d = fmin(fmax(d, 0.0f), 1.0f); /* gl_FragDepth is clamped */
#else
  r.d = v;
  r.nonfinite = !isfinite(r.d);
  r.clipped = !((r.d >= 0.0f) && (r.d <= 1.0f));
#endif
  return r;
}

static inline depth16_t depth16(row_plane16_t rp, __global const float* P, float16 px) {
  return depth_of_value16(plane_at16(rp, px), P);
}

// Stored code and status of 16 fragments.
typedef struct {
  uint16 code;
  int16 nonfinite, clipped;
} frag16_t;

#if ADVERSARY_CODES
// An envelope's adversarial unorm conversion (interface/adversary.h dp_adv_unorm_code), lane by
// lane: codes up where the plane's adversary moves them up, else down.
static inline uint16 adversary_codes16(float16 d, float16 up) {
  float a[16], u[16];
  uint c[16];
  vstore16(d, 0, a);
  vstore16(up, 0, u);
  for (int k = 0; k < 16; ++k)
    c[k] = dp_adv_unorm_code(a[k], DF_FORMAT_FROM_DEFINES(), u[k] > 0.0f, ADVERSARY_CODE_SLACK);
  return vload16(0, c);
}
#define STORED_CODES16(D, RP) adversary_codes16((D), (RP).up)
#define INSIDE_CODES16(D, RP) adversary_codes16((D), (RP).up)
#else
#define STORED_CODES16(D, RP) df_encode16((D), DF_FORMAT_FROM_DEFINES())
#define INSIDE_CODES16(D, RP) df_encode16_unit((D), DF_FORMAT_FROM_DEFINES())
#endif

static inline frag16_t fragment16(row_plane16_t rp, __global const float* P, float16 px) {
  const depth16_t z = depth16(rp, P, px);
  frag16_t r;
  r.code = STORED_CODES16(z.d, rp);
  r.nonfinite = z.nonfinite;
  r.clipped = z.clipped;
  return r;
}

// The stored code of 16 fragments known to be finite and unclipped (inside a piece whose ends
// are, or a band whose bounds say so): their depth lies in [-0, 1], the clamped one too, so the
// encoder needs no checks for values outside it. The same codes fragment16 gives there.
static inline uint16 inside_code16(row_plane16_t rp, __global const float* P, float16 px) {
  return INSIDE_CODES16(depth16(rp, P, px).d, rp);
}

static inline int16 fights16(uint16 code_a, uint16 code_b) {
#if COMPARE_GREATER
  return convert_int16(code_b >= code_a);
#else
  return convert_int16(code_b <= code_a);
#endif
}

// fights16 from the depths themselves, for fragments of which at least one has a depth at or
// above df_order_exact_from (in a MTS_D_ORDERED band every fragment of plane A has): there the
// codes compare as the depths do, so neither needs encoding.
static inline int16 ordered_fights16(float16 da, float16 db) {
#if COMPARE_GREATER
  return db >= da;
#else
  return db <= da;
#endif
}

// Codes a piece or band decided from bounds must clear: the library log's error (mts_variant).
#if DEPTH_FROM == 2 && FRAG_DEPTH >= 3
#define LOG_SLACK_OR_0 LOG_CODE_SLACK
#else
#define LOG_SLACK_OR_0 0UL
#endif

// Walks the row in pieces where both planes' covering triangles stay the same.
#define FOR_EACH_PIECE(...)                                  \
  {                                                          \
    int ka = 0, kb = 0, x = 0;                               \
    while (x < W) {                                          \
      while (seg_xa[ka + 1] <= x) ++ka;                      \
      while (seg_xb[kb + 1] <= x) ++kb;                      \
      const int x_end = min(seg_xa[ka + 1], seg_xb[kb + 1]); \
      const int ta = seg_ta[ka], tb = seg_tb[kb];            \
      __VA_ARGS__                                            \
      x = x_end;                                             \
    }                                                        \
  }

#define MAX_PIECES (2 * MAX_SEG)
