// The emulated pipeline of docs/spec.md 2 for Gilg et al.'s MTS measurement: two planes (plane A
// in front, plane B behind), each a GRID x GRID grid of quads, rasterised at the pixel centres of
// the measurement kernel only, depth stored in one storage format and tested.
//
// One program variant per (technique class, storage format, pipeline options), chosen by -D
// defines (host/runtime/kernel_variant.cpp; each one's meaning and the check that it is given in
// kernels/mts/defines.h), so the per-pixel loop has no run-time switch.
//
// Arithmetic forms (the host reference, host/mts/reference_pipeline.cpp, uses the same ones):
//   matrix * vector     r_i = ((m_i0 x + m_i1 y) + m_i2 z) + m_i3 w (unless MTS_F_VERTEX_FMA)
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
// share its build. The host-kernel binary layout is interface/mts_layout.h; the kernels only the
// tests use are in kernels/mts_test.cl, also a program of its own.

#include "kernels/mts/pipeline.cl" /* the defines checked; formats, layout, coverage, fragments */

// The kernels, each part using the ones above it.
// clang-format off
#include "kernels/mts/plane_a.cl"   /* mts_a_rows: the plane-A cache's row records */
#include "kernels/mts/bounds.cl"    /* mts_a_bands, mts_frame_bounds: bands decided from code bounds */
#include "kernels/mts/raster.cl"    /* mts_raster: the per-row fight search */
// clang-format on
