#include "host/mts/emulator.h"

#include "host/mts/mts_evaluator.h"

namespace depthprec {

std::unique_ptr<ProbeEvaluator> emulator(OpenClRuntime& rt, const Scene& scene,
                                         const EvalPair& pair) {
  return std::make_unique<MtsEvaluator>(rt, scene, pair);
}

}  // namespace depthprec
