// What the MtsEvaluator's files share (mts_evaluator.cpp, mts_launches.cpp, mts_test_kernels.cpp):
// the result bits and constants of the host-kernel layout under the names the host uses, the
// band height, the plane-A cache's budget and record sizes. Internal to host/mts/.
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>

#include "host/model/scene.h"
#include "host/runtime/opencl_runtime.h"
#include "interface/mts_layout.h"

namespace depthprec::mts_parts {

constexpr int kProbeStride = MTS_PROBE_STRIDE;
constexpr uint32_t kFight = MTS_R_FIGHT, kClipped = MTS_R_CLIPPED, kNonFinite = MTS_R_NONFINITE,
                   kUncovered = MTS_R_UNCOVERED, kBounds = MTS_R_BOUNDS, kReused = MTS_R_REUSED;
constexpr int kCountShift = MTS_R_COUNT_SHIFT;
constexpr uint32_t kVertexNonFinite = MTS_V_NONFINITE;

// Kernel rows per band that mts_frame_bounds decides at once from code bounds: a band's depth
// range grows with its height, so smaller bands are decided closer to the MTS but cost more
// bounds work per row.
constexpr cl_uint kBandRows = 32;
static_assert(kBandRows <= 32,
              "a band's rows left out of its verdict are bits of one word (MTS_DW_BAD_ROWS)");

// The plane-A cache grows to the distances of the largest run so far, up to as many as fit in
// its share of this (all frames of each; the pairs a run evaluates side by side share it) and at
// most kMaxSlots. The search keeps no more distances in flight than that (distances_at_once), so
// none is evicted while it is still probed: memory stays within the budget whatever the frames
// or distances (a buffer an earlier evaluator handed on may be up to half as large again as its
// share: MtsEvaluator::reuse_or_make). A small window costs no speed: the default table took 12.0 s
// with one job at 64 MiB and at 192 MiB, 11.1 s with two jobs at 64 MiB each (docs/performance.md).
constexpr size_t kPlaneACacheBytes = size_t{128} << 20;
constexpr size_t kMaxSlots = 64;

constexpr size_t kLocal = kWorkGroup;  // host/runtime/opencl_runtime.h
inline cl::NDRange padded(size_t n) {
  return cl::NDRange(padded_size(n));
}

inline cl_uint band_count(const Scene& scene) {
  return (static_cast<cl_uint>(scene.kernel_h) + kBandRows - 1) / kBandRows;
}

// mts_a_rows' work-items per plane: its kernel rows in groups of MTS_A_ROWS_PER_ITEM.
inline cl_uint a_row_groups(const Scene& scene) {
  return MTS_A_ROW_GROUPS(static_cast<cl_uint>(scene.kernel_h));
}

// Floats per plane record (interface/mts_layout.h, the buffer layout the kernels include too).
inline size_t plane_record_floats(const Scene& scene) {
  return MTS_PLANE_STRIDE(static_cast<size_t>(scene.plane_subdivisions),
                          static_cast<size_t>(scene.pipeline.clip_slots()));
}

// Words per kernel row of plane A's cached codes (0: not cached).
inline size_t code_row_words(const Scene& scene, bool cache_codes) {
  return cache_codes ? static_cast<size_t>(scene.kernel_w) + MTS_CODE_ROW_PAD : 0;
}

// Bytes of each of the plane-A cache's buffers for `slots` distances, every frame of each, in
// MtsEvaluator::PlaneABuffers' order: probe constants, plane records, vertex flags, row records,
// band records, codes (0 when not cached), then the reference's plane and row records, which
// are one distance's whatever the slots.
inline std::array<size_t, 8> plane_a_buffer_bytes(const Scene& scene, bool cache_codes,
                                                  size_t slots) {
  const size_t f = static_cast<size_t>(scene.frames), kh = static_cast<size_t>(scene.kernel_h);
  const size_t planes = slots * f;
  return {sizeof(float) * kProbeStride * slots,
          sizeof(float) * planes * plane_record_floats(scene),
          sizeof(uint32_t) * planes,
          sizeof(uint32_t) * planes * kh * MTS_ROW_WORDS,
          sizeof(uint32_t) * planes * band_count(scene) * MTS_BAND_WORDS,
          sizeof(uint32_t) * planes * kh * code_row_words(scene, cache_codes),
          sizeof(float) * f * plane_record_floats(scene),
          sizeof(uint32_t) * f * kh * MTS_ROW_WORDS};
}

// Bytes of one plane-A cache slot: one distance, every frame (the buffers but the reference's).
inline size_t plane_a_slot_bytes(const Scene& scene, bool cache_codes) {
  const std::array<size_t, 8> b = plane_a_buffer_bytes(scene, cache_codes, 1);
  return b[0] + b[1] + b[2] + b[3] + b[4] + b[5];
}

// Distances the plane-A cache holds at once with its budget shared by `evaluators`.
inline size_t plane_a_slots(const Scene& scene, bool cache_codes, int evaluators) {
  const size_t share = kPlaneACacheBytes / static_cast<size_t>(std::max(1, evaluators));
  return std::clamp<size_t>(share / std::max<size_t>(plane_a_slot_bytes(scene, cache_codes), 1), 1,
                            kMaxSlots);
}

}  // namespace depthprec::mts_parts
