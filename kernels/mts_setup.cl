// The set-up stage of the MTS measurement, a program of its own: mts_setup runs the vertex stage,
// the divide, the window transform and the triangle set-up of every plane (kernels/mts/setup.cl)
// and reads no storage format, compare or fragment-stage choice, so one build serves every
// variant of kernels/mts.cl that shares its defines (host/runtime/kernel_variant.cpp
// setup_options): a scene of several formats compiles it once per technique class.
// Its defines are the set-up's subset of kernels/mts/defines.h.

#define MTS_SETUP_STAGE 1         /* the set-up's defines only */
#include "kernels/mts/contract.h" /* CONTRACT: the FP_CONTRACT pragma */
#include "kernels/mts/defines.h"

// clang-format off
#include "interface/mts_layout.h"        /* buffer layout, shared with the host */
#include "interface/mts_kernel_args.h" /* kernel arguments, shared with the host */
#include "interface/llvmpipe_log.h"      /* llvmpipe's log, shared with the host */
#include "interface/snap.h"              /* sub-pixel snapping, shared with the host */
#include "kernels/mts/common.cl"       /* layout names at this GRID, mat_vec, any16 */
#include "kernels/mts/plane_records.cl" /* the coverage certificate, a triangle's pixel box */
#include "kernels/mts/setup.cl"        /* vertex stage, triangle set-up, coverage certificate */
// clang-format on

// Global id: the plane's index in mats; it is written to tris and vflags at first_plane + id, and
// its probe constants are those of (first_plane + id) / per_probe.
__kernel void mts_setup(MTS_SETUP_BUFFERS(MTS_ARG_IN, MTS_ARG_OUT) const MtsSetupArgs args) {
  const uint k = get_global_id(0);
  if (k >= args.count) return;
  const uint id = args.first_plane + k;
  const MtsKernelArea a = args.area;
  setup_plane(probes + (id / args.per_probe) * MTS_PROBE_STRIDE, mats + k * PLANE_MATRIX_WORDS,
              args.half_w, args.half_h, a.origin_x, a.origin_y, a.kernel_w, a.kernel_h, a.band_rows,
              tris + (size_t)id * PLANE_STRIDE, vflags + id, 0);
}
