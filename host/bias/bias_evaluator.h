// The emulated depth-bias evaluator (BiasEmulator): kernels/bias.cl decides the bias probes of
// host/bias/bias_probe.h on the device.
#pragma once

#include <map>
#include <vector>

#include "host/bias/bias_probe.h"
#include "host/bias/bias_rule.h"
#include "host/model/frame_setup.h"
#include "host/model/scene.h"
#include "host/runtime/kernel_variant.h"
#include "host/runtime/opencl_runtime.h"

namespace depthprec {

class BiasEmulator : public BiasEvaluator {
 public:
  // Throws InputError when the pair has no bias (bias_not_applicable) or the format no rule.
  // orientations: the frames' sampled ones where a distance has them (worst-case sampling).
  BiasEmulator(OpenClRuntime& rt, const Scene& scene, const EvalPair& pair,
               const BiasOptions& options, const Orientations& orientations = {});
  std::vector<ProbeResult> run(const std::vector<BiasProbe>& probes) override;
  RowSource source() const override { return RowSource::emulated; }
  const KernelVariant& variant() const { return variant_; }

 private:
  OpenClRuntime& rt_;
  const Scene& scene_;
  EvalPair pair_;
  Orientations orientations_;
  BiasOptions options_;
  BiasRule rule_;
  KernelVariant variant_;
  cl::Program program_;
  cl::Kernel setup_, rows_;
  size_t plane_floats_ = 0;
  // A probe visits the frames cyclically from the one where the last failing probe of its
  // distance failed (as MtsEvaluator does): a too-small bias fails in the same frames again.
  std::map<double, int> last_fail_frame_;
};

// The variant kernels/bias.cl is built as for a pair: mts_variant's defines, bias.cl's source.
KernelVariant bias_variant(const Scene& scene, const EvalPair& pair);

}  // namespace depthprec
