#include "host/analysis/pipelines.h"

#include "host/base/json_number.h"
#include "host/mts/mts_run.h"

namespace depthprec {

nlohmann::json pair_record(OpenClRuntime& rt, const Scene& scene, const EvalPair& pair) {
  nlohmann::json j = {{"pair", pair.label()}, {"variants", nlohmann::json::object()}};
  for (const PipelineVariant& v : kPipelineVariants) {
    Scene s = scene;
    s.evaluate = {pair};
    s.pipeline.matrix_precision = v.precision;
    s.pipeline.compose = v.compose;
    s.stiffness_probes = 0;
    nlohmann::json mts = nlohmann::json::array();
    for (const auto& r : run_scene(rt, s).rows) mts.push_back(json_number(r.mts));
    j["variants"][v.name] = mts;
  }
  return j;
}

}  // namespace depthprec
