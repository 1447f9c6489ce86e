#include "host/mts_run.h"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <map>
#include <set>

#include "host/row_json.h"

namespace depthprec {

std::vector<std::string> scene_variants(const Scene& scene) {
  std::vector<std::string> out;
  std::set<std::string> seen;
  for (const auto& pair : scene.evaluate) {
    const std::string label = mts_variant(scene, pair).label;
    if (seen.insert(label).second) out.push_back(label);
  }
  return out;
}

void sort_rows(const Scene& scene, std::vector<MtsRow>& rows) {
  std::map<std::string, size_t> order;
  size_t k = 0;
  for (const auto& pair : scene.evaluate)
    for (double z : scene.distances) order.emplace(row_key(pair, z), k++);
  std::stable_sort(rows.begin(), rows.end(), [&order](const MtsRow& a, const MtsRow& b) {
    return order[row_key(a.pair, a.z)] < order[row_key(b.pair, b.z)];
  });
}

MtsRun run_scene(OpenClRuntime& rt, const Scene& scene,
                 const std::function<void(const std::string&)>& log, const RunControl& control) {
  MtsRun run;
  run.info.device = rt.description();
  run.info.variants = scene_variants(scene);
  const auto t0 = std::chrono::steady_clock::now();
  std::set<std::string> built;
  const size_t nd = scene.distances.size();
  for (size_t p = 0; p < scene.evaluate.size(); ++p) {
    const EvalPair& pair = scene.evaluate[p];
    std::vector<double> todo;
    for (size_t d = 0; d < nd; ++d) {
      const size_t k = p * nd + d;
      if (static_cast<int>(k % static_cast<size_t>(control.shard_count)) != control.shard_index) continue;
      if (control.done.count(row_key(pair, scene.distances[d]))) continue;
      todo.push_back(scene.distances[d]);
    }
    if (todo.empty()) continue;
    MtsEvaluator ev(rt, scene, pair);
    if (built.insert(ev.variant().label).second && log)
      log(fmt::format("kernel variant {}: {} {}", ev.variant().label, ev.variant().program,
                      ev.variant().options));
    auto rows = search_pair(ev, scene, pair, todo, control.on_row, control.stop);
    run.info.launches += ev.launches();
    run.info.kernel_seconds += ev.kernel_seconds();
    if (log)
      log(fmt::format("{}: {} distances, {} fragment pairs, {} launches, {:.2f} s ({:.2f} s in kernels)",
                      pair.label(), rows.size(), ev.fragment_pairs(), ev.launches(), ev.wall_seconds(),
                      ev.kernel_seconds()));
    run.rows.insert(run.rows.end(), rows.begin(), rows.end());
  }
  for (const auto& r : run.rows) run.info.fragment_pairs += r.fragment_pairs;
  run.info.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return run;
}

}  // namespace depthprec
