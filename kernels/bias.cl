// The depth-bias measurement (docs/bias.md): plane B lies in plane A, tessellated the other way
// (each quad split along its other diagonal, as a decal or a second mesh of the same surface is),
// is drawn after A with a depth bias, and must pass the depth test at every kernel pixel of every
// frame. The same emulated pipeline as kernels/mts.cl (set-up, coverage, interpolation, storage:
// its parts are included below, with the same -D defines), plus the bias: per triangle of B,
// o = depth_bias(...) from its set-up's slopes and vertex depths (kernels/bias_formula.h), added
// to each fragment's interpolated window depth in binary32 and clamped to [0, 1] before storage,
// as OpenGL specifies (the offset is added to the fragment's depth, which is then clamped).
//
// Defines besides mts.cl's: none. Run-time arguments carry what a probe varies (units, factor,
// clamp in the probe constants, kernels/mts_layout.h C_BIAS_*) and what a batch fixes (the r
// rule, the slope form, strict or or-equal compare).

#if !defined(GRID) || !defined(DEPTH_FROM) || !defined(FRAG_DEPTH) || !defined(COMPARE_GREATER) || \
    !defined(CONTRACT) || !defined(PLANE_FORM) || !defined(LLVMPIPE_LOG) ||                        \
    !defined(CLIP_SLOTS) || !defined(DF_KIND)
#error "kernels/bias.cl needs the defines of kernels/mts.cl (host/runtime/kernel_variant.cpp)"
#endif
#if DEPTH_FROM == 2
#error "depth bias does not apply to depth written by the fragment stage (host/bias/bias_rule.h)"
#endif

#include "kernels/mts/contract.h" /* CONTRACT: the FP_CONTRACT pragma */

// clang-format off
#include "formats/depth_format.h"
#include "kernels/mts_layout.h"
#include "kernels/llvmpipe_log.h"
#include "kernels/snap.h"
#include "kernels/bias_formula.h"
#include "kernels/mts/common.cl"
#include "kernels/mts/plane_records.cl"
#include "kernels/mts/setup.cl"
#include "kernels/mts/coverage.cl"
#include "kernels/mts/fragment.cl"
// clang-format on

// Planes in pairs per (probe, visit): 2 k is plane A (the measured grid), 2 k + 1 plane B (the
// other diagonal, with each triangle's bias in its record at T_BIAS). Global id: the plane's
// index; its probe constants are those of id / per_probe.
__kernel void bias_setup(__global const float* restrict probes, __global const float* restrict mats,
                         const uint per_probe, const float half_w, const float half_h,
                         const float origin_x, const float origin_y, const uint kernel_w,
                         const uint kernel_h, const int float_rule, const int slope_form,
                         __global float* restrict tris, __global uint* restrict vflags,
                         const uint count) {
  const uint id = get_global_id(0);
  if (id >= count) return;
  const int is_b = (int)(id & 1u);
  __global const float* P = probes + (id / per_probe) * PROBE_STRIDE;
  __global float* T = tris + (size_t)id * PLANE_STRIDE;
  setup_plane(P, mats + (id >> 1) * MAT_STRIDE, half_w, half_h, origin_x, origin_y, kernel_w,
              kernel_h, kernel_h, T, vflags + id, is_b);
  for (int t = 0; t < NT; ++t) {
    __global float* R = T + t * TRI_STRIDE;
    float o = 0.0f;
    if (is_b) {
      /* the float rule reads the largest |depth| of the triangle's vertices (T_ZMAX) */
      o = depth_bias(P[C_BIAS_UNITS], float_rule, P[C_BIAS_FACTOR], P[C_BIAS_CLAMP],
                     depth_bias_slope(R[T_DZDX], R[T_DZDY], slope_form), R[T_ZMAX], R[T_ZMAX],
                     R[T_ZMAX]);
      if (!isfinite(o)) vflags[id] |= V_NONFINITE;
    }
    R[T_BIAS] = o;
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

// One kernel row of one (probe, visit): the result word of kernels/mts_layout.h, R_FIGHT meaning
// that plane A showed through the overlay somewhere in the row. Global id: (row, visit, probe);
// results at (probe * frames + visit) * kernel_h + row.
__kernel void bias_rows(__global const float* restrict probes, __global const float* restrict tris,
                        __global const uint* restrict vflags, const uint kernel_w,
                        const uint kernel_h, const float origin_x, const float origin_y,
                        const uint frames, const int strict, __global uint* restrict result) {
  const uint row = get_global_id(0), visit = get_global_id(1), probe = get_global_id(2);
  if (row >= kernel_h) return;
  const uint pf = probe * frames + visit;
  const uint id = pf * kernel_h + row;
  __global const float* P = probes + probe * PROBE_STRIDE;
  if ((vflags[2 * pf] | vflags[2 * pf + 1]) & V_NONFINITE) {
    result[id] = R_NONFINITE;
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
      flags |= R_UNCOVERED;
    } else {
      const row_plane16_t ra = broadcast16(row_plane(TA, ta, py));
      const row_plane16_t rb = broadcast16(row_plane(TB, tb, py));
      const float o = TB[tb * TRI_STRIDE + T_BIAS];
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
        flags |= (any16(nf) ? R_NONFINITE : 0u) | (any16(cl) ? R_CLIPPED : 0u) |
                 (any16(ok & a_absent) ? R_UNCOVERED : 0u) |
                 (any16(ok & ~a_absent & b_hidden16(fa.code, code_b, strict)) ? R_FIGHT : 0u);
      }
    }
  })
  result[id] = flags | ((uint)W << R_COUNT_SHIFT);
}
