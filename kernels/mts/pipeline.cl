// The per-pixel pipeline of an MTS variant, without kernels: the defines checked, the storage
// formats, the layout, and the parts every per-pixel kernel builds on (coverage along a row, depth
// and codes of 16 pixels). Included by the production program (kernels/mts.cl) and by the tests'
// one (kernels/mts_test.cl), so the latter parses none of the production kernels.

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
// clang-format on
