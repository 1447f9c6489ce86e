// llvmpipe's clip stage: triangles crossing the viewport edge cut into fans (pipeline.clip), and
// the queue that sets the fans' triangles up 16 at a time.

#if CLIP_SLOTS > 1
// Triangles waiting for their set-up, a lane each (corner c of lane k), with the record each goes
// to: the set-up takes them 16 at a time (setup_pending). With a clip stage the grid's triangles
// and the fans take records in the order they come.
typedef struct {
  float x[3][16], y[3][16], d[3][16], q[3][16];
  int id[3][16];
  int slot[16];
  int n;
  float adv_depth, adv_tolerance; /* triangles16_t's */
} pending_triangles_t;

// Sets up the pending triangles, 16 lanes of which the ones past p->n repeat the last (so no lane
// computes on undefined values), and empties the queue.
static inline void setup_pending(pending_triangles_t* p, __global float* T, float origin_x,
                                 float origin_y, uint kernel_w, uint kernel_h, uint band_rows,
                                 uint* slivers, uint* shapely) {
  if (p->n == 0) return;
  triangles16_t v;
  v.adv_depth = p->adv_depth;
  v.adv_tolerance = p->adv_tolerance;
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
  __global float* R = T + t * MTS_TRI_STRIDE;
  for (int k = 0; k < MTS_TRI_STRIDE; ++k) R[k] = 0.0f;
  R[MTS_T_YMIN] = INFINITY;
  R[MTS_T_YMAX] = -INFINITY;
  vstore4((int4)(1, 0, 1, 0), 0, (__global int*)R + MTS_T_BOX);
  __global float* SA = T + NT * MTS_TRI_STRIDE;
  for (int e = 0; e < 3; ++e)
    for (int a = 0; a <= MTS_E_BITS; ++a) SA[a * NE_PAD + 3 * t + e] = 0.0f;
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
