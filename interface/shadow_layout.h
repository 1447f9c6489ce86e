/* The shadow-acne kernel's interface (kernels/shadow.cl, host/shadow/shadow_emulator.cpp): its
 * buffers in order, its scalars' struct, and the layout of each receiver plane's record, named once
 * for both sides. Valid C++ and OpenCL C; every scalar is 4 bytes.
 *
 * One work-item is one receiver plane: a caster triangle of that plane rasterised into the
 * light's depth map, and a grid of receiver points on it, each looked up through the filter. */
#ifndef DEPTHPREC_SHADOW_LAYOUT_H
#define DEPTHPREC_SHADOW_LAYOUT_H

#include "formats/df_prelude.h"

/* A plane's binary32 record (planes_f), SHADOW_F_STRIDE floats: the caster triangle's three world
 * vertices, the receiver normal (unit, toward the light), the grid's first texel position. */
#define SHADOW_F_V0 0
#define SHADOW_F_V1 3
#define SHADOW_F_V2 6
#define SHADOW_F_NORMAL 9
#define SHADOW_F_BASE_U 12
#define SHADOW_F_BASE_V 13
#define SHADOW_F_STRIDE 16
/* Its binary64 record (planes_d): the receiver point at texel position (u, v) is
 * (origin + u du + v dv) / (c0 + u c1 + v c2) -- a directional light's plane is affine in the map,
 * c = (1, 0, 0); a spot light's projective -- on the plane through the binary32 vertices, then
 * rounded to binary32 as a varying is. */
#define SHADOW_D_ORIGIN 0
#define SHADOW_D_DU 3
#define SHADOW_D_DV 6
#define SHADOW_D_DENOM 9
#define SHADOW_D_STRIDE 12

/* The light matrix (light): rows x, y, z and w of four floats each; x / w and y / w are normalized
 * device coordinates, z / w the window depth (a directional light's w is 1). */
#define SHADOW_LIGHT_WORDS 16

#define SHADOW_BUFFERS(IN, OUT) \
  IN(float, light) IN(float, planes_f) IN(double, planes_d) OUT(uint, acne)
typedef struct {
  float half_res;      /* the map's side / 2 */
  float units_term;    /* the raster bias's constant as interface/bias_formula.h takes it */
  float factor;        /* its slope factor */
  float normal_offset; /* metres along the receiver's normal, toward the light */
  float reach;         /* texels: the filter reads texels whose centres lie closer on each axis */
  df_u32 count;        /* planes */
  df_u32 grid;         /* receiver points per texel side */
  df_i32 float_rule;   /* the bias's r from the primitive's largest depth (float32) */
  df_i32 slope_form;   /* BIAS_SLOPE_MAX or BIAS_SLOPE_SQRT */
  df_i32 reversed;     /* nearer the light is larger: lit where the reference is >= the texel */
  df_i32 snap_bits;    /* the rasteriser's sub-texel bits */
} ShadowArgs;

#endif
