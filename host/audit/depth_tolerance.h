// How far the depth a conformant implementation stores for a fragment can lie from the emulated
// one (docs/audit.md "At risk"): a bound, per set-up triangle, on |d_impl - d_exact| where d_exact
// is exact arithmetic on the same binary32 inputs (object positions, uploaded matrices) and d_impl
// any implementation whose every binary32 operation is correctly rounded, in any order, fused or
// not: the vertex stage's products, the divide, the viewport transform, a vertex-anchored or
// origin-anchored depth plane, evaluated or stepped, positions snapped to 8 sub-pixel bits or not,
// a library or approximate log. The emulated depth is one such implementation, so two
// implementations' depths lie within twice the bound. Each term is written beside the arithmetic it
// bounds in depth_tolerance.cpp. The audit marks a pixel at risk where the front surface's lead
// over the next surface behind it is within the two surfaces' bounds (and the conversion's width).
#pragma once

#include <array>

#include "host/model/frame_setup.h"
#include "host/model/scene.h"
#include "host/model/storage_format.h"
#include "host/mts/triangle_setup.h"

namespace depthprec {

// A vertex's errors, in two parts: [0..3] the clip coordinates' (x, y, z, w) own roundings, each
// bounded on its own; [4..6] how far the vertex's eye position (x, y, z) may lie from the exact
// one. An eye displacement moves every clip coordinate together (P times it): z_clip and w move as
// one, so it reaches the window through the projection's exact derivative (window_error), not as
// independent clip errors, which far from the near plane would count the depth's error w / n
// times over.
using ClipError = std::array<double, 7>;
constexpr int kEyeError = 4;

// The vertex stage of object position p under the draw's description (VertexStage,
// host/model/vertex_stage.h), step by step as vertex_clip computes it: each product of a row with a
// vector, in any association, fused or not, within gamma(4) of the sum of its terms' magnitudes,
// plus the inputs' own errors through the row.
ClipError vertex_clip_error(const ProbeConstants& pc, const VertexStage& stage,
                            const std::array<float, 3>& p);

// A vertex c the clip stage made, crossing `planes` planes, of a triangle whose largest clip
// coordinates are `largest` and whose vertices' errors are at most `carried`.
ClipError clipped_vertex_error(const std::array<float, 4>& largest, const ClipError& carried,
                               int planes, const std::array<float, 4>& c);

// The bound for one set-up triangle, v[0..2] (window vertices after clipping, clip errors
// e[0..2]) at a pixel (px, py) it covers: its interpolated value (window depth, or q = 1/w for
// fragment-stage depth) within constant + max(0, e0 + ex (px - ax) + ey (py - ay)) of the exact
// one; the depth a fragment shader computes from q within `shader` more. Infinite constant where no
// finite bound holds (a vertex whose w error reaches half its w, a degenerate triangle).
struct RecordTolerance {
  double constant = 0, e0 = 0, ex = 0, ey = 0, shader = 0;
};
RecordTolerance record_tolerance(const Scene& scene, const EvalPair& pair, const ProbeConstants& pc,
                                 const SetupVertex* const v[3], const ClipError* const e[3],
                                 float ax, float ay);

// The storage conversion's freedom, in codes: how far two conformant conversions of one depth may
// lie apart (unorm: rounding, truncation, llvmpipe's double rounding, up to 3 codes for unorm32;
// another float format's rounding, 1 code; binary32, none).
int conversion_codes(const StorageFormat& format);

}  // namespace depthprec
