#include "host/analysis/cost.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "host/base/json_number.h"
#include "host/lj/lj_metric.h"
#include "host/mts/mts_run.h"
#include "host/mts/mts_timing.h"

namespace depthprec {

std::string structural_cost(const Scene& s, Technique t) {
  if (t != Technique::layered) return info(t).gpu_cost;
  return fmt::format("{} passes, depth cleared per layer; {} mapping per layer", s.params.layers,
                     info(s.params.layer_mapping).name);
}

nlohmann::json cost_record(OpenClRuntime& rt, const Scene& scene, const EvalPair& pair,
                           bool timing) {
  Scene one = scene;
  one.evaluate = {pair};
  const MtsRun mts = run_scene(rt, one);
  std::vector<double> ratio;
  std::vector<Probe> at_mts;  // clean probes where every pixel is evaluated: equal work per pair
  int unresolved = 0;
  for (const auto& r : mts.rows) {
    if (r.unresolvable) {
      ++unresolved;
    } else {
      ratio.push_back(r.mts / r.vertex_bound);
      if (r.verdict() == Verdict::resolved) at_mts.push_back({r.z, r.mts * kAtMtsFactor});
    }
  }
  std::sort(ratio.begin(), ratio.end());
  const double median = ratio.empty() ? INFINITY : ratio[ratio.size() / 2];
  nlohmann::json j = pair.fields();
  j.update({{"median_mts_over_vertex_bound", json_number(median)},
            {"unresolvable_distances", unresolved},
            {"structural_cost", structural_cost(scene, pair.technique)}});
  if (const auto c = lj_config_for(pair.technique, scene.near, scene.far))
    j["lj_ae"] = json_number(lj_average_error_device(rt, *c, scene.storage_format(pair)).ae);
  // A pair with no resolved distance has no clean probe to time: no figure, not 0.
  if (timing && !at_mts.empty())
    j["ns_per_fragment_pair"] = time_probes(rt, scene, pair, at_mts).ns_per_pair();
  return j;
}

}  // namespace depthprec
