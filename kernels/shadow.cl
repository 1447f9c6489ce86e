// Shadow acne, emulated (docs/shadow.md "The emulation"): a receiver plane is both the caster
// rasterised into the light's depth map and the receiver looked up in it. Per plane, the caster
// triangle's vertices go through the light matrix in binary32, are snapped to the rasteriser's
// sub-texel grid, and each texel the filter reads gets the depth interpolated at its centre from
// exact fixed-point edge functions, plus the raster bias (interface/bias_formula.h), stored in the
// format and read back as binary32. Each receiver point (a grid over one texel) is moved along its
// normal, transformed by the same matrix and compared with every texel whose centre lies closer
// than the filter's reach on each axis. A texel that shadows a point of its own surface is acne.
//
// Defines: the storage format's (formats/depth_format.h DF_*), and CONTRACT 0 (every operation
// rounds on its own, as interface/bias_formula.h asks).

#pragma OPENCL FP_CONTRACT OFF
#pragma OPENCL EXTENSION cl_khr_fp64 : enable

// clang-format off
#include "formats/depth_format.h"
#include "interface/bias_formula.h"
#include "interface/shadow_layout.h"
// clang-format on

#define SHADOW_ARG_IN(type, name) __global const type *restrict name,
#define SHADOW_ARG_OUT(type, name) __global type *restrict name,

// x_ndc, y_ndc, window depth of world point p: each row as ((m0 x + m1 y) + m2 z) + m3, then
// x, y and z divided by w (a directional light's w is 1 exactly, and so is every quotient by it).
static float3 light_transform(__global const float* m, float3 p) {
  float4 r;
  r.x = ((m[0] * p.x + m[1] * p.y) + m[2] * p.z) + m[3];
  r.y = ((m[4] * p.x + m[5] * p.y) + m[6] * p.z) + m[7];
  r.z = ((m[8] * p.x + m[9] * p.y) + m[10] * p.z) + m[11];
  r.w = ((m[12] * p.x + m[13] * p.y) + m[14] * p.z) + m[15];
  return (float3)(r.x / r.w, r.y / r.w, r.z / r.w);
}

// Window x, y in texels: x_ndc res/2 + res/2.
static float2 to_window(float3 c, float half_res) {
  return (float2)(c.x * half_res + half_res, c.y * half_res + half_res);
}

// The caster's fixed-point set-up: vertices in 2^-snap texel units (exact integers), their
// binary32 depths, twice the signed area.
typedef struct {
  long x[3], y[3];
  float z[3];
  long area;
  float offset; /* the raster bias */
} Caster;

static long snapped(float w, int bits) {
  return (long)rint((double)w * (double)(1 << bits));
}

static Caster setup_caster(__global const float* m, __global const float* P, ShadowArgs a) {
  Caster c;
  for (int k = 0; k < 3; ++k) {
    const float3 v = (float3)(P[3 * k], P[3 * k + 1], P[3 * k + 2]);
    const float3 t = light_transform(m, v);
    const float2 w = to_window(t, a.half_res);
    c.x[k] = snapped(w.x, a.snap_bits);
    c.y[k] = snapped(w.y, a.snap_bits);
    c.z[k] = t.z;
  }
  c.area = (c.x[1] - c.x[0]) * (c.y[2] - c.y[0]) - (c.x[2] - c.x[0]) * (c.y[1] - c.y[0]);
  // The plane's slopes in depth per texel, in binary32 from the snapped vertices.
  const float g = (float)(1 << a.snap_bits);
  const float x1 = (float)(c.x[1] - c.x[0]) / g, y1 = (float)(c.y[1] - c.y[0]) / g;
  const float x2 = (float)(c.x[2] - c.x[0]) / g, y2 = (float)(c.y[2] - c.y[0]) / g;
  const float z1 = c.z[1] - c.z[0], z2 = c.z[2] - c.z[0];
  const float det = x1 * y2 - x2 * y1;
  const float dzdx = (z1 * y2 - z2 * y1) / det, dzdy = (z2 * x1 - z1 * x2) / det;
  c.offset = depth_bias(a.units_term, a.float_rule, a.factor, 0.0f,
                        depth_bias_slope(dzdx, dzdy, a.slope_form), c.z[0], c.z[1], c.z[2]);
  return c;
}

// The binary32 value the comparison reads for texel (i, j): the interpolated depth at its centre
// plus the bias, clamped to [0, 1], stored, and read back.
static float stored_depth(const Caster* c, int i, int j, int bits, df_format fmt) {
  const long centre = 1L << (bits - 1);
  const long px = ((long)i << bits) + centre, py = ((long)j << bits) + centre;
  long e[3];
  for (int k = 0; k < 3; ++k) {
    const int k1 = (k + 1) % 3, k2 = (k + 2) % 3;
    e[k] = (c->x[k2] - c->x[k1]) * (py - c->y[k1]) - (c->y[k2] - c->y[k1]) * (px - c->x[k1]);
  }
  const float area = (float)c->area;
  float d = 0.0f;
  for (int k = 0; k < 3; ++k) d = d + ((float)e[k] / area) * c->z[k];
  d = d + c->offset;
  d = clamp(d, 0.0f, 1.0f);
  const uint code = df_encode(d, fmt);
#if DF_KIND == 0
  return (float)code / (float)fmt.max_code;
#else
  return as_float(code);
#endif
}

__kernel void shadow_acne(SHADOW_BUFFERS(SHADOW_ARG_IN, SHADOW_ARG_OUT) const ShadowArgs a) {
  const uint id = get_global_id(0);
  if (id >= a.count) return;
  const df_format fmt = DF_FORMAT_FROM_DEFINES();
  __global const float* P = planes_f + (size_t)id * SHADOW_F_STRIDE;
  __global const double* D = planes_d + (size_t)id * SHADOW_D_STRIDE;
  const Caster c = setup_caster(light, P, a);
  const float3 n = (float3)(P[SHADOW_F_NORMAL], P[SHADOW_F_NORMAL + 1], P[SHADOW_F_NORMAL + 2]);
  const float3 offset = a.normal_offset * n;
  uint count = 0;
  for (uint gy = 0; gy < a.grid; ++gy)
    for (uint gx = 0; gx < a.grid; ++gx) {
      const double u = (double)P[SHADOW_F_BASE_U] + (double)gx / (double)a.grid;
      const double v = (double)P[SHADOW_F_BASE_V] + (double)gy / (double)a.grid;
      const double3 pd =
          ((double3)(D[0], D[1], D[2]) + u * (double3)(D[3], D[4], D[5]) +
           v * (double3)(D[6], D[7], D[8])) /
          (D[SHADOW_D_DENOM] + u * D[SHADOW_D_DENOM + 1] + v * D[SHADOW_D_DENOM + 2]);
      const float3 p = convert_float3(pd) + offset;  // the varying, moved along the normal
      const float3 t = light_transform(light, p);
      const float2 w = to_window(t, a.half_res);
      const int i0 = (int)ceil(w.x - a.reach - 0.5f), i1 = (int)floor(w.x + a.reach - 0.5f);
      const int j0 = (int)ceil(w.y - a.reach - 0.5f), j1 = (int)floor(w.y + a.reach - 0.5f);
      bool shadowed = false;
      for (int j = j0; j <= j1 && !shadowed; ++j) {
        if (!(fabs((float)j + 0.5f - w.y) < a.reach)) continue;
        for (int i = i0; i <= i1 && !shadowed; ++i) {
          if (!(fabs((float)i + 0.5f - w.x) < a.reach)) continue;
          const float s = stored_depth(&c, i, j, a.snap_bits, fmt);
          shadowed = a.reversed ? t.z < s : t.z > s;
        }
      }
      count += shadowed ? 1u : 0u;
    }
  acne[id] = count;
}
