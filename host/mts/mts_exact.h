// The storage-limited pipeline of MTS attribution (kernels/mts_exact.cl): the same probes and
// frames as MtsEvaluator, with everything before storage exact up to binary64 -- plane B at
// z + s itself, not fl32(z + s) -- so a search over it measures what storage alone allows.
#pragma once

#include "host/model/frame_setup.h"
#include "host/model/scene.h"
#include "host/mts/probe.h"
#include "host/runtime/opencl_runtime.h"

namespace depthprec {

class ExactEvaluator : public ProbeEvaluator {
 public:
  // orientations: the frames' sampled ones where a distance has them (worst-case sampling).
  // shortcuts: rows decided clean from their end pixels where that is certain
  // (kernels/mts_exact.cl, ROW_ENDS); off only to check that they never change a result.
  ExactEvaluator(OpenClRuntime& rt, const Scene& scene, const EvalPair& pair,
                 const Orientations& orientations = {}, bool shortcuts = true);
  std::vector<ProbeResult> run(const std::vector<Probe>& probes) override;
  // Kernel rows (of every probe and frame run) whose pixels were, some or all, decided clean
  // from end pixels.
  uint64_t rows_decided_from_ends() const { return rows_from_ends_; }

 private:
  OpenClRuntime& rt_;
  const Scene& scene_;
  EvalPair pair_;
  Orientations orientations_;
  cl::Kernel kernel_;
  uint64_t rows_from_ends_ = 0;
};

}  // namespace depthprec
