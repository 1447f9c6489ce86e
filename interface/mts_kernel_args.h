/* The arguments of the MTS and bias kernels, named once for the kernels and the host: each
 * kernel takes its buffers, in the order its *_BUFFERS list gives them, then one struct of its
 * scalars by value. The kernels expand a list into their parameters (kernels/mts/common.cl
 * MTS_ARG_IN, MTS_ARG_OUT), the host into a struct of named buffers that it binds in the same
 * order (host/runtime/kernel_args.h), so neither side spells an argument's position. Valid C++ and
 * OpenCL C; every scalar is 4 bytes, so the structs' layout is the same on both sides. */
#ifndef DEPTHPREC_MTS_KERNEL_ARGS_H
#define DEPTHPREC_MTS_KERNEL_ARGS_H

#include "formats/df_prelude.h" /* df_u32, df_i32 */

/* The measurement kernel's pixels, the same for every launch of an evaluator. */
typedef struct {
  df_u32 kernel_w, kernel_h; /* its size in pixels */
  float origin_x, origin_y;  /* the window position of its first pixel's corner */
  df_u32 bands;              /* its rows in bands of band_rows (the last may be shorter) */
  df_u32 band_rows;
} MtsKernelArea;

/* IN(type, name): a buffer the kernel reads; OUT(type, name): one it writes. */

/* mts_setup (kernels/mts_setup.cl): the set-up of planes first_plane .. first_plane + count - 1
 * from their matrices (mats, from the launch's first), each plane's probe constants those of
 * plane / per_probe. */
#define MTS_SETUP_BUFFERS(IN, OUT) \
  IN(float, probes) IN(float, mats) OUT(float, tris) OUT(uint, vflags)
typedef struct {
  MtsKernelArea area;
  float half_w, half_h; /* half the viewport: the window transform's scale */
  df_u32 per_probe, first_plane, count;
} MtsSetupArgs;

/* mts_a_rows (kernels/mts/plane_a.cl): the plane-A cache's row records of planes first_plane ..,
 * `items` rows in all; from the reference distance's (ref_*) when use_ref is set. */
#define MTS_A_ROWS_BUFFERS(IN, OUT) \
  IN(float, probes)                 \
  IN(float, tris)                   \
  IN(uint, vflags) IN(float, ref_tris) IN(uint, ref_rows) OUT(uint, rows) OUT(uint, codes)
typedef struct {
  MtsKernelArea area;
  df_u32 first_plane, per_probe, items, use_ref;
  df_u32 fill_codes; /* CACHE_A_CODES: 1 to fill the codes cache, 0 to leave it (plane A
                        probed once: mts_raster then computes A's codes where it needs them) */
} MtsARowsArgs;

/* mts_a_bands (kernels/mts/bounds.cl): plane A's code bounds per band, `items` bands in all. */
#define MTS_A_BANDS_BUFFERS(IN, OUT) \
  IN(float, probes) IN(float, tris) IN(uint, vflags) OUT(uint, out)
typedef struct {
  MtsKernelArea area;
  df_u32 first_plane, per_probe, items;
} MtsABandsArgs;

/* mts_frame_bounds (kernels/mts/bounds.cl): the verdict of each band of each (probe, visit),
 * `items` bands in all; a probe's visit v is frame (first_frame + v) % frames_total. */
#define MTS_FRAME_BOUNDS_BUFFERS(IN, OUT) \
  IN(float, probes)                       \
  IN(float, tris)                         \
  IN(uint, vflags)                        \
  IN(float, a_tris) IN(uint, a_vflags) IN(uint, a_bands) IN(uint, a_slots) OUT(uint, decided)
typedef struct {
  MtsKernelArea area;
  df_u32 first_frame, frames_total, frames, items;
} MtsFrameBoundsArgs;

/* mts_raster (kernels/mts/raster.cl): the fight search of each band of each (probe, visit). */
#define MTS_RASTER_BUFFERS(IN, OUT)                                                         \
  IN(float, probes)                                                                         \
  IN(float, tris)                                                                           \
  IN(uint, vflags)                                                                          \
  IN(float, a_tris)                                                                         \
  IN(uint, a_vflags) IN(uint, a_rows) IN(uint, a_slots) IN(uint, a_codes) IN(uint, decided) \
      OUT(uint, result)
typedef struct {
  MtsKernelArea area;
  df_u32 first_frame, frames_total, frames;
  df_u32 shortcuts;      /* 0: rasterise every band, whatever mts_frame_bounds decided */
  df_u32 a_codes_filled; /* CACHE_A_CODES: whether mts_a_rows filled a_codes (fill_codes) */
} MtsRasterArgs;

/* bias_setup (kernels/bias.cl): planes in pairs per (probe, visit), A then B with its bias. */
#define BIAS_SETUP_BUFFERS(IN, OUT) \
  IN(float, probes) IN(float, mats) OUT(float, tris) OUT(uint, vflags)
typedef struct {
  MtsKernelArea area;
  float half_w, half_h;
  df_u32 per_probe, count;
  df_i32 float_rule; /* the float rule of depth bias's r (interface/bias_formula.h) */
  df_i32 slope_form; /* BIAS_SLOPE_* */
} BiasSetupArgs;

/* bias_rows (kernels/bias.cl): each kernel row of each (probe, visit). */
#define BIAS_ROWS_BUFFERS(IN, OUT) \
  IN(float, probes) IN(float, tris) IN(uint, vflags) OUT(uint, result)
typedef struct {
  MtsKernelArea area;
  df_u32 frames;
  df_i32 strict; /* LESS (GREATER) rather than LEQUAL (GEQUAL) */
} BiasRowsArgs;

#endif
