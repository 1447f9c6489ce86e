// The vertex stage: clip coordinates, the divide, the window transform, snapping; and which grid
// vertices make each triangle. The host describes the clip coordinates' part once
// (host/model/vertex_stage.h: vertex_path, vertex_clip) and packs what this reads of it
// (host/model/frame_setup.h append_plane_words, the probe constants' MTS_F_* bits and view).

#if RELATIVE_TO_EYE
#pragma OPENCL EXTENSION cl_khr_fp64 : enable
#include "interface/relative_to_eye.h" /* the split and the difference, shared with the host */
// The eye-space positions of 16 grid vertices relative to eye (pipeline.transform
// relative_to_eye): world positions from the plane's binary64 world matrix W, as the application
// computes them, each coordinate split into binary32 high and low parts and subtracted from the
// eye's on the GPU (interface/relative_to_eye.h). The view has no rotation and the plane's is in
// W, so this is eye space; w is 1. Lane by lane: the binary64 part is the CPU's.
static inline vec4x16_t relative_to_eye16(__global const float* P, __global const float* M,
                                          vec4x16_t obj) {
  __global const double* W = (__global const double*)M;
  float ox[16], oy[16], e[3][16];
  vstore16(obj.x, 0, ox);
  vstore16(obj.y, 0, oy);
  for (int k = 0; k < 16; ++k)
    for (int r = 0; r < 3; ++r)
      e[r][k] = dp_rte_eye(dp_rte_world_row(W, r, (double)ox[k], (double)oy[k]),
                           P[MTS_C_EYE_HIGH_X + r], P[MTS_C_EYE_LOW_X + r]);
  vec4x16_t eye;
  eye.x = vload16(0, e[0]);
  eye.y = vload16(0, e[1]);
  eye.z = vload16(0, e[2]);
  eye.w = (float16)1.0f;
  return eye;
}
#endif

#include "interface/binary16.h" /* mediump's rounding, shared with the host */

// Row r of m times v at a reduced shader precision (MTS_F_MEDIUMP: GLSL ES mediump, binary16;
// MTS_F_ES2_HIGHP: the GLSL ES 1.00 highp minimum; interface/binary16.h dp_shader_round): the
// matrix entry held at that precision, each product and sum rounded to it, separate or fused one
// step at a time (host/model/vertex_stage.cpp mediump_row_dot, the same arithmetic).
static inline float mediump_row(__global const float* m, const float v[4], int fused, int prec) {
  float s = dp_shader_round(dp_shader_round(m[0], prec) * v[0], prec);
  for (int c = 1; c < 4; ++c)
    s = fused
            ? dp_shader_round(fma(dp_shader_round(m[c], prec), v[c], s), prec)
            : dp_shader_round(s + dp_shader_round(dp_shader_round(m[c], prec) * v[c], prec), prec);
  return s;
}

// The clip coordinates of 16 object positions, lane by lane, in mediump
// (host/model/vertex_stage.cpp vertex_clip under VertexStage::mediump, the same steps): M (or P V M
// premultiplied), the view's translation, P.
static inline vec4x16_t mediump_vertex16(__global const float* P, __global const float* M,
                                         vec4x16_t obj, uint forms, int fused, int prec) {
  float ox[16], oy[16], out[4][16];
  vstore16(obj.x, 0, ox);
  vstore16(obj.y, 0, oy);
  for (int k = 0; k < 16; ++k) {
    const float o[4] = {ox[k], oy[k], 0.0f, 1.0f};
    float e[4] = {0.0f, 0.0f, 0.0f, 1.0f}, c[4];
    if (forms & MTS_F_COMPOSE_PREMULT) {
      for (int r = 0; r < 4; ++r) c[r] = mediump_row(M + 4 * r, o, fused, prec);
    } else {
      for (int r = 0; r < 3; ++r) e[r] = mediump_row(M + 4 * r, o, fused, prec);
      if (forms & MTS_F_VIEW_TRANSLATE)
        for (int r = 0; r < 3; ++r)
          e[r] = dp_shader_round(e[r] + dp_shader_round(P[MTS_C_VIEW_X + r], prec), prec);
      for (int r = 0; r < 4; ++r) c[r] = mediump_row(P + 4 * r, e, fused, prec);
    }
    for (int r = 0; r < 4; ++r) out[r][k] = c[r];
  }
  vec4x16_t clip;
  clip.x = vload16(0, out[0]);
  clip.y = vload16(0, out[1]);
  clip.z = vload16(0, out[2]);
  clip.w = vload16(0, out[3]);
  return clip;
}

// Window x and y as the rasterizer stores them (pipeline.snap, interface/snap.h).
DP_SNAP_WINDOW_DEFINE(snap_window_bits, fabs, rint)

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
  /* the probe constants this stage alone reads (interface/mts_layout.h) */
  const int depth_gl = P[MTS_C_DEPTH_GL] != 0.0f;
  const uint forms = (uint)P[MTS_C_FORMS];
  const int snap_bits = (int)P[MTS_C_SNAP_BITS];
  const int vertex_fma = (forms & MTS_F_VERTEX_FMA) != 0u;
  vec4x16_t obj;
  obj.x = convert_float16(vertex % (GRID + 1)) / (float)GRID - 0.5f;
  obj.y = convert_float16(vertex / (GRID + 1)) / (float)GRID - 0.5f;
  obj.z = (float16)0.0f;
  obj.w = (float16)1.0f;
  vertices16_t v;
#if RELATIVE_TO_EYE
  v.clip = mat_vec16(P, relative_to_eye16(P, M, obj), vertex_fma, 0);
#else
  const int prec = (forms & MTS_F_MEDIUMP)     ? DP_SHADER_MEDIUMP
                   : (forms & MTS_F_ES2_HIGHP) ? DP_SHADER_ES2_HIGHP
                                               : DP_SHADER_HIGHP;
  if (prec != DP_SHADER_HIGHP) {
    v.clip = mediump_vertex16(P, M, obj, forms, vertex_fma, prec);
  } else {
    v.clip = mat_vec16(M, obj, vertex_fma, 1);
    if (forms & MTS_F_VIEW_TRANSLATE) { /* the view matrix: no rotation, the camera's translation */
      v.clip.x = v.clip.x + P[MTS_C_VIEW_X];
      v.clip.y = v.clip.y + P[MTS_C_VIEW_X + 1];
      v.clip.z = v.clip.z + P[MTS_C_VIEW_X + 2];
    }
    if (!(forms & MTS_F_COMPOSE_PREMULT)) v.clip = mat_vec16(P, v.clip, vertex_fma, 0);
  }
#endif
  const vec4x16_t c = v.clip;
#if DEPTH_FROM == 1 /* host/model/shader_log.cpp vertex_log_clip_z, the same arithmetic */
  if (P[MTS_C_VERTEX_LOG] == (float)MTS_VERTEX_LOG_THREEJS) {
    /* three.js's fallback: log2(max(EPSILON, w + 1.0)) * logDepthBufFC - 1.0, then times w; FC / 2
     * in the [0, 1] range WebGL lacks, so both ranges store the same depth */
    const float fc = P[MTS_C_THREEJS_FC];
    const float16 t = shader_log2_16(fmax((float16)1e-6f, c.w + 1.0f));
    v.clip.z = depth_gl ? (t * fc - 1.0f) * c.w : (t * (0.5f * fc)) * c.w;
  } else {
    const float16 t = shader_log16(P[MTS_C_LOGK] * c.w + 1.0f);
    v.clip.z = depth_gl ? ((2.0f * t) / P[MTS_C_LOGL] - 1.0f) * c.w : (t / P[MTS_C_LOGL]) * c.w;
  }
#endif
  const float16 cz = v.clip.z;
  float16 inv_w = 1.0f / c.w;
  const float adv_depth = P[MTS_C_ADV_DEPTH];
  if (adv_depth != 0.0f && P[MTS_C_ADV_RECIPROCAL] != 0.0f) {
    /* an envelope's reciprocal within 1 ulp, rounded the way that moves the window depth in the
     * adversary's direction: through z/w where the depth is projected (up with z > 0 when the
     * depth moves up), through w itself where the fragment stage computes it (1/w down when the
     * depth moves up) */
    float r[16], w[16], z[16];
    vstore16(inv_w, 0, r);
    vstore16(c.w, 0, w);
    vstore16(cz, 0, z);
    for (int k = 0; k < 16; ++k)
      r[k] = adv_reciprocal(w[k], r[k], dp_adv_reciprocal_up(DEPTH_FROM == 2, z[k], adv_depth));
    inv_w = vload16(0, r);
  }
  float16 nx, ny, nz;
  if (forms & MTS_F_DIVIDE_EXACT) {
    nx = c.x / c.w;
    ny = c.y / c.w;
    nz = cz / c.w;
  } else {
    nx = c.x * inv_w;
    ny = c.y * inv_w;
    nz = cz * inv_w;
  }
  if (forms & MTS_F_VIEWPORT_FMA) {
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
