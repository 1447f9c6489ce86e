#include "host/lj/lj_pipeline.h"

#include <cmath>

#include "host/model/frame_setup.h"
#include "host/model/resolve.h"

namespace depthprec {

LjPipelineResult lj_pipeline_error(const LjConfig& c, const StorageFormat& f,
                                   const Pipeline& pipeline) {
  validate(c);
  const Technique t = lj_technique(c.buffer);
  const bool fragment = info(t).from == DepthFrom::fragment;
  // P for the buffer's technique, built as the scene pipeline builds it.
  Scene scene = load_scene("", {});
  scene.near = c.near;
  scene.far = c.far;
  scene.pipeline = pipeline;
  const EvalPair pair{t, f.name(), DepthRange::zero_to_one};
  const ProbeConstants pc = probe_constants(scene, pair, c.near);
  const ResolveSetup rs{t, c.near, c.far, scene.params};
  const lj_config shared = c.shared();

  double num = 0, num_c = 0, den = 0, den_c = 0;
  LjPipelineResult r;
  r.samples = c.samples;
  for (long long i = 0; i < c.samples; ++i) {
    const double Ze = lj_distance(shared, i);
    // The vertex at the kernel centre: eye = (0, 0, -fl32(Ze), 1); clip = P * eye in binary32.
    const float eye[4] = {0.0f, 0.0f, -static_cast<float>(Ze), 1.0f};
    float clip[4];
    for (int row = 0; row < 4; ++row) clip[row] = mat_row_dot(pc.P, row, eye, pipeline.vertex);
    const float inv_w = 1.0f / clip[3];
    float d;
    if (fragment) {  // w_buffer: d = w / f from the perspective-correct w
      const float w = 1.0f / inv_w;
      d = std::fmin(std::fmax(w / pc.far, 0.0f), 1.0f);
    } else {
      d = pipeline.divide == Divide::exact ? clip[2] / clip[3] : clip[2] * inv_w;
    }
    if (!(d >= 0.0f && d <= 1.0f)) {
      ++r.clipped;
      continue;
    }
    const uint32_t code = f.encode(d);
    const double exact = lj_depth(shared, i);
    uint32_t ideal = f.code_floor(exact);
    if (f.rounding() == Rounding::nearest_even && ideal < f.max_code() &&
        exact - f.decode(ideal) > f.decode(ideal + 1) - exact)
      ++ideal;
    if (ideal != code) ++r.off_code;
    const uint32_t lo = code < f.max_code() ? code : code - 1;
    const double err = distance_gap(rs, f.decode(lo), f.decode(lo + 1));
    const double wgt = lj_weight(shared, i);
    lj_add(&num, &num_c, err * wgt);
    lj_add(&den, &den_c, wgt);
  }
  r.ae = (num + num_c) / ((c.far - c.near) * (den + den_c));
  return r;
}

}  // namespace depthprec
