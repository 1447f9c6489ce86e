// Decides depth-bias probes: does a coplanar overlay (plane B in plane A, tessellated along the
// other diagonal, drawn after A with the bias) pass the depth test at every kernel pixel of every
// frame? Emulated by kernels/bias.cl (BiasEmulator) or rendered through OpenGL with
// glPolygonOffset (BiasRenderer, host/render/), so one search drives both.
#pragma once

#include <map>
#include <vector>

#include "host/bias/bias_rule.h"
#include "host/model/scene.h"
#include "host/mts/probe.h"
#include "host/runtime/kernel_variant.h"
#include "host/runtime/opencl_runtime.h"

namespace depthprec {

// units and factor as the application sets them (signed: negative toward the camera under
// LESS); clamp from the options.
struct BiasProbe {
  double z = 0;
  double units = 0, factor = 0;
};

// Outcome::fight: plane A showed through the overlay at some kernel pixel of some frame (the
// bias was too small); clean: the overlay won everywhere.
class BiasEvaluator {
 public:
  virtual ~BiasEvaluator() = default;
  virtual std::vector<ProbeResult> run(const std::vector<BiasProbe>& probes) = 0;
  virtual RowSource source() const = 0;
};

class BiasEmulator : public BiasEvaluator {
 public:
  // Throws InputError when the pair has no bias (bias_not_applicable) or the format no rule.
  BiasEmulator(OpenClRuntime& rt, const Scene& scene, const EvalPair& pair,
               const BiasOptions& options);
  std::vector<ProbeResult> run(const std::vector<BiasProbe>& probes) override;
  RowSource source() const override { return RowSource::emulated; }
  const KernelVariant& variant() const { return variant_; }

 private:
  OpenClRuntime& rt_;
  const Scene& scene_;
  EvalPair pair_;
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
