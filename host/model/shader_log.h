// The logs the emulated shaders call, as the host reference and the real-rasterizer checks compute
// them: ln and log2 in the scene's form (pipeline.log: the C library's, or llvmpipe's from
// interface/llvmpipe_log.h), and the vertex stage's log depth, the one formula
// kernels/mts/setup/vertex.cl evaluates (docs/spec.md 3).
#pragma once

#include "host/model/frame_setup.h"
#include "host/model/scene.h"

namespace depthprec {

float shader_log(LogForm form, float x);
float shader_log2(LogForm form, float x);

// z_clip that vertex-stage log depth (DEPTH_FROM 1) writes for a vertex of clip w, in the depth
// range's form (gl: [-1, 1] NDC, else [0, 1]) and the probe's formula (pc.vertex_log): Gilg's
// (ln(k w + 1) / L) or three.js's (log2(max(1e-6, w + 1)) * FC), binary32, in the shader's order.
float vertex_log_clip_z(const ProbeConstants& pc, LogForm form, bool gl, float w);

}  // namespace depthprec
