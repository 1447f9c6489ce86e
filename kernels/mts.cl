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
// This file is the program's entry: it checks the defines and includes the parts in the order
// each needs the one before. The set-up that writes the planes' records (mts_setup) is a program
// of its own, kernels/mts_setup.cl, built with the subset of these defines it reads, so the
// variants that share a technique class share its build. The host-kernel binary layout is
// kernels/mts_layout.h; the kernels only the tests use are in kernels/mts_test.cl, also a program
// of its own.

#if !defined(GRID) || !defined(DEPTH_FROM) || !defined(FRAG_DEPTH) || !defined(COMPARE_GREATER) || \
    !defined(CONTRACT) || !defined(LOG_CODE_SLACK) || !defined(CACHE_A_CODES) ||                   \
    !defined(PLANE_FORM) || !defined(LLVMPIPE_LOG) || !defined(CLIP_SLOTS) || !defined(DF_KIND)
#error \
    "kernels/mts.cl needs GRID, DEPTH_FROM, FRAG_DEPTH, COMPARE_GREATER, CONTRACT, LOG_CODE_SLACK, CACHE_A_CODES, PLANE_FORM, LLVMPIPE_LOG, CLIP_SLOTS and the DF_* format defines (host/runtime/kernel_variant.cpp)"
#endif

#include "kernels/mts/contract.h" /* CONTRACT: the FP_CONTRACT pragma */

// The order is the point: each part uses the ones above it.
// clang-format off
#include "formats/depth_format.h"   /* storage formats, shared with the host */
#include "kernels/mts_layout.h"     /* buffer layout, shared with the host */
#include "kernels/llvmpipe_log.h"   /* llvmpipe's log, shared with the host */
#include "kernels/mts/common.cl"    /* layout names at this GRID, mat_vec, any16 */
#include "kernels/mts/plane_records.cl" /* the coverage certificate, a triangle's pixel box */
#include "kernels/mts/coverage.cl"  /* row_segments: covering triangles along a row; coverage reuse */
#include "kernels/mts/fragment.cl"  /* depth and codes of 16 pixels; the fight test */
#include "kernels/mts/plane_a.cl"   /* mts_a_rows: the plane-A cache's row records */
#include "kernels/mts/bounds.cl"    /* mts_a_bands, mts_frame_bounds: bands decided from code bounds */
#include "kernels/mts/raster.cl"    /* mts_raster: the per-row fight search */
// clang-format on
