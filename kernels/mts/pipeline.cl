// The per-pixel pipeline of an MTS variant, without kernels: the defines checked, the storage
// formats, the layout, and the parts every per-pixel kernel builds on (coverage along a row, depth
// and codes of 16 pixels). Included by the production program (kernels/mts.cl) and by the tests'
// one (kernels/mts_test.cl), so the latter parses none of the production kernels.

#include "kernels/mts/contract.h" /* CONTRACT: the FP_CONTRACT pragma */
#include "kernels/mts/defines.h"  /* every define given */

// The order is the point: each part uses the ones above it.
// clang-format off
#include "formats/depth_format.h"   /* storage formats, shared with the host */
#include "interface/mts_layout.h"     /* buffer layout, shared with the host */
#include "interface/mts_kernel_args.h" /* kernel arguments, shared with the host */
#include "interface/llvmpipe_log.h"   /* llvmpipe's log, shared with the host */
#pragma OPENCL EXTENSION cl_khr_fp64 : enable
#include "interface/adversary.h"      /* an envelope's adversarial codes, shared with the host */
#include "interface/mediump_fragment.h" /* a mediump fragment shader, shared with the host */
#include "kernels/mts/common.cl"    /* layout names at this GRID, mat_vec, any16 */
#include "kernels/mts/plane_records.cl" /* the coverage certificate, a triangle's pixel box */
#include "kernels/mts/coverage.cl"  /* row_segments: covering triangles along a row; coverage reuse */
#include "kernels/mts/fragment.cl"  /* depth and codes of 16 pixels; the fight test */
// clang-format on
