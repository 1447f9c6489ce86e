// The depth-bias measurement (docs/bias.md): plane B lies in plane A, tessellated the other way
// (each quad split along its other diagonal, as a decal or a second mesh of the same surface is),
// is drawn after A with a depth bias, and must pass the depth test at every kernel pixel of every
// frame. The same emulated pipeline as kernels/mts.cl (set-up, coverage, interpolation, storage:
// its parts are included below, with the same -D defines), plus the bias: per triangle of B,
// o = depth_bias(...) from its set-up's slopes and vertex depths (interface/bias_formula.h), added
// to each fragment's interpolated window depth in binary32 and clamped to [0, 1] before storage,
// as OpenGL specifies (the offset is added to the fragment's depth, which is then clamped).
//
// Defines besides mts.cl's: none. Run-time arguments carry what a probe varies (units, factor,
// clamp in the probe constants, interface/mts_layout.h C_BIAS_*) and what a batch fixes (the r
// rule, the slope form, strict or or-equal compare).

#include "kernels/mts/defines.h" /* every define given */
#if DEPTH_FROM == 2
#error "depth bias does not apply to depth written by the fragment stage (host/bias/bias_rule.h)"
#endif

#include "kernels/mts/contract.h" /* CONTRACT: the FP_CONTRACT pragma */

// clang-format off
#include "formats/depth_format.h"
#include "interface/mts_layout.h"
#include "interface/mts_kernel_args.h" /* kernel arguments, shared with the host */
#include "interface/llvmpipe_log.h"
#include "interface/snap.h"
#include "interface/bias_formula.h"
#include "kernels/mts/common.cl"
#include "kernels/mts/plane_records.cl"
#include "kernels/mts/setup.cl"
#include "kernels/mts/coverage.cl"
#include "kernels/mts/fragment.cl"
// clang-format on

// Planes in pairs per (probe, visit): 2 k is plane A (the measured grid), 2 k + 1 plane B (the
// other diagonal, with each triangle's bias in its record at MTS_T_BIAS). Global id: the plane's
// index; its probe constants are those of id / per_probe.
__kernel void bias_setup(BIAS_SETUP_BUFFERS(MTS_ARG_IN, MTS_ARG_OUT) const BiasSetupArgs args) {
  const uint id = get_global_id(0);
  if (id >= args.count) return;
  const int float_rule = args.float_rule, slope_form = args.slope_form;
  const int is_b = (int)(id & 1u);
  __global const float* P = probes + (id / args.per_probe) * MTS_PROBE_STRIDE;
  __global float* T = tris + (size_t)id * PLANE_STRIDE;
  const MtsKernelArea a = args.area;
  setup_plane(P, mats + (id >> 1) * PLANE_MATRIX_WORDS, args.half_w, args.half_h, a.origin_x,
              a.origin_y, a.kernel_w, a.kernel_h, a.band_rows, T, vflags + id, is_b);
  for (int t = 0; t < NT; ++t) {
    __global float* R = T + t * MTS_TRI_STRIDE;
    float o = 0.0f;
    /* A record that covers no pixel (an empty slot, or a degenerate triangle of the clip stage's
     * fans: its gradients are 0/0) has no bias to apply; a plane facing the camera exactly makes
     * such fans under llvmpipe's clip stage. */
    if (is_b && (as_uint(R[MTS_T_BITS]) & MTS_BIT_VALID)) {
      /* the float rule reads the largest |depth| of the triangle's vertices (MTS_T_ZMAX) */
      o = depth_bias(P[MTS_C_BIAS_UNITS], float_rule, P[MTS_C_BIAS_FACTOR], P[MTS_C_BIAS_CLAMP],
                     depth_bias_slope(R[MTS_T_DZDX], R[MTS_T_DZDY], slope_form), R[MTS_T_ZMAX],
                     R[MTS_T_ZMAX], R[MTS_T_ZMAX]);
      if (!isfinite(o)) vflags[id] |= MTS_V_NONFINITE;
    }
    R[MTS_T_BIAS] = o;
  }
}

// Does plane B fail to show (the depth test keeps A) at 16 pixels? Strict compare: LESS
// (GREATER); otherwise LEQUAL (GEQUAL).
static inline int16 b_hidden16(uint16 code_a, uint16 code_b, int strict) {
#if COMPARE_GREATER
  return strict ? convert_int16(code_b <= code_a) : convert_int16(code_b < code_a);
#else
  return strict ? convert_int16(code_b >= code_a) : convert_int16(code_b > code_a);
#endif
}

// One kernel row of one (probe, visit): the result word of interface/mts_layout.h, MTS_R_FIGHT
// meaning that plane A showed through the overlay somewhere in the row. Global id: (row, visit,
// probe); results at (probe * frames + visit) * kernel_h + row.
__kernel void bias_rows(BIAS_ROWS_BUFFERS(MTS_ARG_IN, MTS_ARG_OUT) const BiasRowsArgs args) {
  const uint frames = args.frames;
  const int strict = args.strict;
  const uint kernel_w = args.area.kernel_w, kernel_h = args.area.kernel_h;
  const float origin_x = args.area.origin_x, origin_y = args.area.origin_y;
  const uint row = get_global_id(0), visit = get_global_id(1), probe = get_global_id(2);
  if (row >= kernel_h) return;
  const uint pf = probe * frames + visit;
  const uint id = pf * kernel_h + row;
  __global const float* P = probes + probe * MTS_PROBE_STRIDE;
  if ((vflags[2 * pf] | vflags[2 * pf + 1]) & MTS_V_NONFINITE) {
    result[id] = MTS_R_NONFINITE;
    return;
  }
  __global const float* TA = tris + (size_t)(2 * pf) * PLANE_STRIDE;
  __global const float* TB = tris + (size_t)(2 * pf + 1) * PLANE_STRIDE;
  const int W = (int)kernel_w;
  const float py = origin_y + (float)row + 0.5f;
  int seg_xa[MAX_SEG + 1], seg_ta[MAX_SEG], seg_xb[MAX_SEG + 1], seg_tb[MAX_SEG];
  row_segments(TA, py, origin_x, W, seg_xa, seg_ta);
  row_segments(TB, py, origin_x, W, seg_xb, seg_tb);
  /* Under a strict compare plane A itself fails against the cleared buffer where its code is
   * the clear value's (LESS against 1, GREATER against 0): it is not drawn there, so nothing is
   * measured at that pixel, as where no plane covers it. */
  const uint clear_code = df_encode(COMPARE_GREATER ? 0.0f : 1.0f, DF_FORMAT_FROM_DEFINES());
  uint flags = 0u;
  FOR_EACH_PIECE({
    if (ta < 0 || tb < 0) {
      flags |= MTS_R_UNCOVERED;
    } else {
      const row_plane16_t ra = broadcast16(row_plane(TA, ta, py));
      const row_plane16_t rb = broadcast16(row_plane(TB, tb, py));
      const float o = TB[tb * MTS_TRI_STRIDE + MTS_T_BIAS];
      for (int i0 = x; i0 < x_end; i0 += 16) {
        const int16 active = (i0 + LANES) < x_end;
        const float16 px = (origin_x + convert_float16(i0 + LANES)) + 0.5f;
        const frag16_t fa = fragment16(ra, P, px);
        const depth16_t db = depth16(rb, P, px);
        const uint16 code_b =
            df_encode16(fmin(fmax(db.d + o, 0.0f), 1.0f), DF_FORMAT_FROM_DEFINES());
        const int16 nf = active & (fa.nonfinite | db.nonfinite);
        const int16 cl = active & ~nf & (fa.clipped | db.clipped);
        const int16 a_absent = strict ? convert_int16(fa.code == (uint16)clear_code) : (int16)0;
        const int16 ok = active & ~(nf | cl);
        flags |= (any16(nf) ? MTS_R_NONFINITE : 0u) | (any16(cl) ? MTS_R_CLIPPED : 0u) |
                 (any16(ok & a_absent) ? MTS_R_UNCOVERED : 0u) |
                 (any16(ok & ~a_absent & b_hidden16(fa.code, code_b, strict)) ? MTS_R_FIGHT : 0u);
      }
    }
  })
  result[id] = flags | ((uint)W << MTS_R_COUNT_SHIFT);
}
