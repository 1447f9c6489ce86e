// The emulated pipeline's evaluator (MtsEvaluator, host/mts/mts_evaluator.h) behind the
// ProbeEvaluator interface, for code that decides probes without launching a kernel itself and so
// includes no OpenCL (host/analysis/; docs/architecture.md, "Layers").
#pragma once

#include <memory>

#include "host/model/scene.h"
#include "host/mts/probe.h"

namespace depthprec {

class OpenClRuntime;  // host/runtime/opencl_runtime.h

// An MtsEvaluator of the pair under the scene (which must outlive it), as MtsEvaluator's
// constructor makes it by default: every shortcut on, the production kernels.
std::unique_ptr<ProbeEvaluator> emulator(OpenClRuntime& rt, const Scene& scene,
                                         const EvalPair& pair);

}  // namespace depthprec
