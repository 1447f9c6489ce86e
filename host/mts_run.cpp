#include "host/mts_run.h"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <set>

#include "host/mts_exact.h"
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

namespace {

// The attribution factors of a pair's rows: the storage-limited MTS from the binary64 pipeline
// (kernels/mts_exact.cl) and the arithmetic-limited MTS from the same binary32 pipeline storing
// in float32, which holds every binary32 depth exactly (a float32 pair is its own). The factor
// searches skip the stiffness probes: they report a number, not a stability check.
void attribute_rows(OpenClRuntime& rt, const Scene& scene, const EvalPair& pair, std::vector<MtsRow>& rows,
                    std::map<std::string, double>& arithmetic_cache, const std::function<bool()>& stop) {
  Scene plain = scene;
  plain.stiffness_probes = 0;
  std::vector<double> zs;
  for (const auto& r : rows) zs.push_back(r.z);
  ExactEvaluator exact(rt, plain, pair);
  const auto storage = search_pair(exact, plain, pair, zs, {}, stop);
  EvalPair raw = pair;
  raw.format = "float32";
  const bool is_raw = pair.format == "float32";
  if (is_raw)
    for (const auto& r : rows) arithmetic_cache[row_key(raw, r.z)] = r.mts;
  std::vector<double> missing;
  for (double z : zs)
    if (!arithmetic_cache.count(row_key(raw, z))) missing.push_back(z);
  if (!missing.empty()) {
    MtsEvaluator ev(rt, plain, raw);
    for (const auto& r : search_pair(ev, plain, raw, missing, {}, stop)) arithmetic_cache[row_key(raw, r.z)] = r.mts;
  }
  for (size_t i = 0; i < rows.size(); ++i) {
    rows[i].storage_mts = storage[i].beyond_far ? INFINITY : storage[i].mts;
    rows[i].arithmetic_mts = arithmetic_cache[row_key(raw, rows[i].z)];
  }
}

}  // namespace

MtsRun run_scene(OpenClRuntime& rt, const Scene& scene,
                 const std::function<void(const std::string&)>& log, const RunControl& control) {
  MtsRun run;
  run.info.device = rt.description();
  run.info.variants = scene_variants(scene);
  const auto t0 = std::chrono::steady_clock::now();
  std::set<std::string> built;
  std::map<std::string, double> arithmetic_cache;  // row key of a float32 pair -> its MTS
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
    auto rows = search_pair(ev, scene, pair, todo, control.attribute ? nullptr : control.on_row, control.stop);
    if (control.attribute) {
      attribute_rows(rt, scene, pair, rows, arithmetic_cache, control.stop);
      if (control.on_row)
        for (const auto& r : rows) control.on_row(r);
    }
    run.info.launches += ev.launches();
    run.info.kernel_seconds += ev.kernel_seconds();
    if (log) {
      const auto& w = ev.pairs_by_outcome();
      const double all = std::max<double>(1.0, static_cast<double>(ev.fragment_pairs()));
      log(fmt::format("{}: {} distances, {} fragment pairs, {} launches, {:.2f} s ({:.2f} s in kernels); "
                      "pairs on clean probes {:.0f} %, fighting {:.0f} % (of which past the deciding frame "
                      "{:.0f} %), clipped or non-finite {:.0f} %",
                      pair.label(), rows.size(), ev.fragment_pairs(), ev.launches(), ev.wall_seconds(),
                      ev.kernel_seconds(), 100 * w[0] / all, 100 * w[1] / all, 100 * ev.pairs_after_decision() / all,
                      100 * (w[2] + w[3]) / all));
    }
    run.rows.insert(run.rows.end(), rows.begin(), rows.end());
  }
  for (const auto& r : run.rows) run.info.fragment_pairs += r.fragment_pairs;
  run.info.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return run;
}

}  // namespace depthprec
