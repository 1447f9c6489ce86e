#include "host/model/shader_log.h"

#include <cmath>

#include "formats/df_prelude.h"
#include "interface/llvmpipe_log.h"

namespace depthprec {

namespace {

DP_LLVMPIPE_LOG_DEFINE(llvmpipe_log2, llvmpipe_log, float, df_float_bits, df_bits_float,
                       static_cast<float>, std::fma)

}  // namespace

float shader_log(LogForm form, float x) {
  return form == LogForm::llvmpipe ? llvmpipe_log(x) : std::log(x);
}

float shader_log2(LogForm form, float x) {
  return form == LogForm::llvmpipe ? llvmpipe_log2(x) : std::log2(x);
}

float vertex_log_clip_z(const ProbeConstants& pc, LogForm form, bool gl, float w) {
  if (pc.vertex_log == MTS_VERTEX_LOG_THREEJS) {
    // logdepthbuf_vertex.glsl.js (<= r162): z = log2(max(EPSILON, w + 1.0)) * logDepthBufFC - 1.0;
    // z *= w. WebGL has no [0, 1] clip space; there the FC / 2 of its fragment form, so both
    // ranges store the same depth.
    const float t = shader_log2(form, std::fmax(1e-6f, w + 1.0f));
    return gl ? (t * pc.threejs_fc - 1.0f) * w : (t * (0.5f * pc.threejs_fc)) * w;
  }
  const float t = shader_log(form, pc.log_k * w + 1.0f);
  return gl ? ((2.0f * t) / pc.log_L - 1.0f) * w : (t / pc.log_L) * w;
}

}  // namespace depthprec
