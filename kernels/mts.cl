// The emulated pipeline of docs/spec.md 2 for Gilg et al.'s MTS measurement: two planes (plane A
// in front, plane B behind), each a GRID x GRID grid of quads, rasterised at the pixel centres of
// the measurement kernel only, depth stored in one storage format and tested.
//
// One program variant per (technique class, storage format, pipeline options), chosen by -D
// defines (host/runtime/kernel_variant.cpp), so the per-pixel loop has no run-time
// switch; every one of them must be given (a missing define is an #error, not a silent 0):
//   GRID               quads per plane side (vertices (GRID+1)^2, triangles 2*GRID^2)
//   DEPTH_FROM         0 projection, 1 vertex-stage log (Gilg eq. 5), 2 fragment-stage depth
//   FRAG_DEPTH         with DEPTH_FROM 2: 1 linear, 2 w_buffer, 3 log
//   COMPARE_GREATER    1: GEQUAL (reversed mappings); 0: LEQUAL
//   CONTRACT           1: the compiler may fuse a*b+c; 0: every operation rounds on its own
//   CACHE_A_CODES      1: the pixel loop reads plane A's codes from the plane-A cache
//   PLANE_FORM         0: planes anchored at a vertex (below); 1: llvmpipe's, referred to the
//                      framebuffer origin and evaluated with fma; 2: softpipe's, referred to
//                      the origin and evaluated per 2x2 quad by increments, which is not
//                      monotone along a row, so the shortcuts that assume it are off
//                      (host/model/scene.h PlaneForm)
//   LLVMPIPE_LOG       1: the shaders' log is llvmpipe's (kernels/llvmpipe_log.h); 0: OpenCL's
//   CLIP_SLOTS         1: triangles as they are; MTS_CLIP_SLOTS: those crossing the viewport edge
//                      clipped into fans as llvmpipe does (mts/setup.cl clip_fan)
//   DF_*               the storage format (formats/depth_format.h)
// The vertex stage's choices are no defines: the depth range, the division, the composition of
// the matrices, the fused forms of the matrix rows and the viewport, and sub-pixel snapping are
// probe constants (C_DEPTH_GL, C_FORMS, C_SNAP_BITS in kernels/mts_layout.h), read by that stage
// alone, so pairs that differ in them alone share one program. The per-pixel loop's choices stay
// defines.
//
// Arithmetic forms (the host reference, host/mts/reference_pipeline.cpp, uses the same ones):
//   matrix * vector     r_i = ((m_i0 x + m_i1 y) + m_i2 z) + m_i3 w (unless F_VERTEX_FMA)
//   window x, y         x_w = x_ndc * (W/2) + W/2
//   edge function       E = dx * (py - ay) - dy * (px - ax), anchored at the lower vertex index
//                       of the edge so both triangles sharing it compute the same value
//   ownership (E == 0)  the triangle for which the oriented edge has s*dy < 0, or dy == 0 and
//                       s*dx < 0 (a top-left rule: exactly one of two neighbours owns the edge)
//   covering triangle   the lowest-index triangle whose three edge tests pass
//   depth (plane eq.)   d = (d0 + dzdx * (px - x0)) + dzdy * (py - y0), from vertex 0 of the
//                       triangle, dzdx = (e1d e2y - e2d e1y) / det, dzdy = (e2d e1x - e1d e2x) /
//                       det
//   1/w (perspective)   the same plane equation over q = 1/w_clip; w = 1 / q
//
// This file is the program's entry: kernels/mts/pipeline.cl checks the defines and includes the
// parts every kernel builds on, then the kernels' parts follow, each needing the ones before. The
// set-up that writes the planes' records (mts_setup) is a program of its own, kernels/mts_setup.cl,
// built with the subset of these defines it reads, so the variants that share a technique class
// share its build. The host-kernel binary layout is kernels/mts_layout.h; the kernels only the
// tests use are in kernels/mts_test.cl, also a program of its own.

#include "kernels/mts/pipeline.cl" /* the defines checked; formats, layout, coverage, fragments */

// The kernels, each part using the ones above it.
// clang-format off
#include "kernels/mts/plane_a.cl"   /* mts_a_rows: the plane-A cache's row records */
#include "kernels/mts/bounds.cl"    /* mts_a_bands, mts_frame_bounds: bands decided from code bounds */
#include "kernels/mts/raster.cl"    /* mts_raster: the per-row fight search */
// clang-format on
