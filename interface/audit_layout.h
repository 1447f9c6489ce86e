/* The scene audit's host-kernel interface (kernels/audit.cl, host/audit/audit_device.cpp and
 * its host reference host/audit/audit_reference.cpp): the kernel's arguments, named once as
 * interface/mts_kernel_args.h names the MTS kernels', and the meaning of its per-pixel outputs.
 * Triangle records are the MTS layout's (interface/mts_layout.h MTS_T_*, MTS_TRI_STRIDE floats),
 * written by the host's set-up (host/audit/audit_setup.h). Valid C++ and OpenCL C. */
#ifndef DEPTHPREC_AUDIT_LAYOUT_H
#define DEPTHPREC_AUDIT_LAYOUT_H

#include "formats/df_prelude.h" /* df_u32 */

/* The image is cut into tiles of AUDIT_TILE x AUDIT_TILE pixels; each tile's bin lists the records
 * whose pixel box meets it, in draw order, and one work-item takes one row of one tile, its
 * AUDIT_TILE pixels in the lanes of a 16-wide vector. */
#define AUDIT_TILE 16

/* No triangle (winner or front of an uncovered pixel). */
#define AUDIT_NONE 0xffffffffu

/* A pixel's flags. */
#define AUDIT_COVERED 1u    /* at least one fragment survived to the depth test */
#define AUDIT_FIGHT 2u      /* a drawn winner that is not the exact front surface, nor coplanar */
#define AUDIT_COPLANAR 4u   /* another surface lies in the front surface's plane at the pixel */
#define AUDIT_DISCARDED 8u  /* a covering fragment was clipped, or not finite */
#define AUDIT_NO_MARGIN 16u /* one surface only: margin_codes means nothing */
/* covered, but no fragment passed the test against the cleared buffer (its code is the clear
 * value's, as a far plane too near or a format too coarse makes it): nothing is drawn */
#define AUDIT_UNDRAWN 32u
/* set by the host after the pass (host/audit/audit.cpp): the winner is a neighbour of the front
 * surface on its own surface (same draw, a corner in common), at their seam: no fight */
#define AUDIT_SEAM 64u

/* set by the pass: the front surface wins, but by less than the depths of the front and the next
 * surface behind it may move on another conformant implementation (the record's tolerance) plus
 * the conversion's freedom: it fights on some implementation or view */
#define AUDIT_AT_RISK 128u

/* Per record, AUDIT_TOL_WORDS floats (host/audit/depth_tolerance.h): at a covered pixel the
 * interpolated value (depth, or q = 1/w for fragment-stage depth) of any conformant
 * implementation lies within C + max(0, E0 + EX (px - x0) + EY (py - y0)) of the emulated one,
 * (x0, y0) the record's anchor (MTS_T_X0, MTS_T_Y0), and a fragment shader's depth from it within
 * SHADER more. Rounded up to binary32. */
#define AUDIT_TOL_WORDS 5
#define AUDIT_TOL_C 0
#define AUDIT_TOL_E0 1
#define AUDIT_TOL_EX 2
#define AUDIT_TOL_EY 3
#define AUDIT_TOL_SHADER 4

/* How many codes two conformant conversions of one depth may lie apart: unorm round to nearest,
 * truncation (softpipe), llvmpipe's double rounding (bounds.cl GAP_CODE_WIDTH: under 3 codes for
 * unorm32, 2 for the others); another float format's rounding direction, 1; binary32 is stored as
 * it is. */
#define AUDIT_CONVERSION_CODES(unorm, bits, binary32) \
  ((unorm) ? ((bits) >= 32 ? 3 : 2) : ((binary32) ? 0 : 1))

/* Two surfaces are one plane at a pixel when their exact eye depths there differ by at most this
 * much relative to the depth: binary64 rounding of transforms and plane equations, far below any
 * separation a depth buffer resolves (2^-53 per step, a few dozen steps). */
#define AUDIT_COPLANAR_RELATIVE 1e-9

/* The exact ray of a pixel: per scene, 4 doubles: half the viewport (hw, hh) and the projection's
 * x and y scales (sx, sy); the eye ray through window (px, py) is
 * ((px / hw - 1) / sx, (py / hh - 1) / sy, -1), and a surface with eye-space plane n.p = c meets it
 * at eye depth c / (n . ray). Per source triangle, 4 doubles: nx, ny, nz, c. */
#define AUDIT_RAY_WORDS 4
#define AUDIT_PLANE_WORDS 4

/* audit_pixels (kernels/audit.cl): every pixel of the image. source: per record the scene-wide
 * triangle it comes from (a clipped triangle's fan shares it); bins: per tile its first entry in
 * bin_records, then (tiles + 1 in all) the end. Outputs per pixel (row-major from the bottom-left,
 * width x height): the record's source triangle that won the depth test, the exact front surface,
 * the margin (codes between the front surface and the next distinct one, in the depth test's
 * direction; <= 0 where it fights; INT_MAX with no surface behind it) and the flags. */
#define AUDIT_PIXELS_BUFFERS(IN, OUT)                                                        \
  IN(float, probe)                                                                           \
  IN(float, records)                                                                         \
  IN(uint, source)                                                                           \
  IN(float, tolerance)                                                                       \
  IN(double, ray)                                                                            \
  IN(double, planes) IN(uint, bins) IN(uint, bin_records) OUT(uint, winner) OUT(uint, front) \
      OUT(int, margin) OUT(uint, flags)
typedef struct {
  df_u32 width, height, tiles_x, tiles_y;
  df_u32 clear_code; /* the cleared depth buffer's code (far: 1.0, reversed 0.0) */
} AuditPixelsArgs;

#endif
