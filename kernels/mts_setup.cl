// The set-up stage of the MTS measurement, a program of its own: mts_setup runs the vertex stage,
// the divide, the window transform and the triangle set-up of every plane (kernels/mts/setup.cl)
// and reads no storage format, compare or fragment-stage choice, so one build serves every
// variant of kernels/mts.cl that shares its defines (host/runtime/kernel_variant.cpp
// setup_options): a scene of several formats compiles it once per technique class.
//   GRID, CONTRACT, PLANE_FORM, CLIP_SLOTS   as in kernels/mts.cl
//   DEPTH_FROM     0 projection, 1 vertex-stage log (Gilg eq. 5), 2 fragment-stage depth (the
//                  set-up then leaves d to the fragment stage)
//   LLVMPIPE_LOG   the vertex-stage log's form (kernels/llvmpipe_log.h); 0 unless DEPTH_FROM 1

#if !defined(GRID) || !defined(DEPTH_FROM) || !defined(CONTRACT) || !defined(PLANE_FORM) || \
    !defined(LLVMPIPE_LOG) || !defined(CLIP_SLOTS)
#error \
    "kernels/mts_setup.cl needs GRID, DEPTH_FROM, CONTRACT, PLANE_FORM, LLVMPIPE_LOG and CLIP_SLOTS (host/runtime/kernel_variant.cpp)"
#endif

#include "kernels/mts/contract.h" /* CONTRACT: the FP_CONTRACT pragma */

// clang-format off
#include "kernels/mts_layout.h"        /* buffer layout, shared with the host */
#include "kernels/llvmpipe_log.h"      /* llvmpipe's log, shared with the host */
#include "kernels/snap.h"              /* sub-pixel snapping, shared with the host */
#include "kernels/mts/common.cl"       /* layout names at this GRID, mat_vec, any16 */
#include "kernels/mts/plane_records.cl" /* the coverage certificate, a triangle's pixel box */
#include "kernels/mts/setup.cl"        /* vertex stage, triangle set-up, coverage certificate */
// clang-format on

// Global id: the plane's index in mats; it is written to tris and vflags at first_plane + id, and
// its probe constants are those of (first_plane + id) / per_probe.
__kernel void mts_setup(__global const float* restrict probes, __global const float* restrict mats,
                        const uint per_probe, const float half_w, const float half_h,
                        const float origin_x, const float origin_y, const uint kernel_w,
                        const uint kernel_h, const uint band_rows, __global float* restrict tris,
                        __global uint* restrict vflags, const uint first_plane, const uint count) {
  const uint k = get_global_id(0);
  if (k >= count) return;
  const uint id = first_plane + k;
  setup_plane(probes + (id / per_probe) * PROBE_STRIDE, mats + k * MAT_STRIDE, half_w, half_h,
              origin_x, origin_y, kernel_w, kernel_h, band_rows, tris + (size_t)id * PLANE_STRIDE,
              vflags + id, 0);
}
