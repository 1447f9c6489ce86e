// The Lapidous-Jiao average error measured on the emulated pipeline instead of the analytic
// model: for each sampled Ze, a camera-facing plane at fl32(Ze) goes through the binary32
// vertex stage, divide and storage of docs/spec.md 2 (the buffer's technique, zero_to_one); the
// error is the eye-distance width of the interval its stored code stands for (the code and the next
// one above, mapped back exactly). See docs/lapidous-jiao.md for where and why it differs.
#pragma once

#include "host/lj/lj_metric.h"
#include "host/model/scene.h"

namespace depthprec {

struct LjPipelineResult {
  double ae = 0;
  long long samples = 0;
  long long clipped = 0;   // samples whose binary32 depth left [0, 1] (left out of the average)
  long long off_code = 0;  // samples stored in another code than the exact depth rounds to
};

LjPipelineResult lj_pipeline_error(const LjConfig& c, const StorageFormat& f,
                                   const Pipeline& pipeline);

}  // namespace depthprec
