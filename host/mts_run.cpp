#include "host/mts_run.h"

#include <fmt/format.h>

#include <chrono>
#include <set>

namespace depthprec {

MtsRun run_scene(OpenClRuntime& rt, const Scene& scene,
                 const std::function<void(const std::string&)>& log) {
  MtsRun run;
  run.info.device = rt.description();
  const auto t0 = std::chrono::steady_clock::now();
  std::set<std::string> variants;
  for (const auto& pair : scene.evaluate) {
    MtsEvaluator ev(rt, scene, pair);
    if (variants.insert(ev.variant().label).second) {
      run.info.variants.push_back(ev.variant().label);
      if (log) log(fmt::format("kernel variant {}: {} {}", ev.variant().label, ev.variant().program,
                               ev.variant().options));
    }
    auto rows = search_pair(ev, scene, pair, scene.distances);
    run.info.fragment_pairs += ev.fragment_pairs();
    run.info.launches += ev.launches();
    run.info.kernel_seconds += ev.kernel_seconds();
    if (log)
      log(fmt::format("{}: {} distances, {} fragment pairs, {} launches, {:.2f} s ({:.2f} s in kernels)",
                      pair.label(), rows.size(), ev.fragment_pairs(), ev.launches(), ev.wall_seconds(),
                      ev.kernel_seconds()));
    run.rows.insert(run.rows.end(), rows.begin(), rows.end());
  }
  run.info.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return run;
}

}  // namespace depthprec
