#include "host/mts_run.h"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <set>

#include "host/frame_setup.h"
#include "host/kernel_variant.h"
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
    rows[i].set_dominant(scene.rel_precision);
  }
}

// What decides a row's computation, byte for byte: the kernel program and its build options, the
// binary32 constants the set-up reads at this z (and the binary64 P a premultiplied binary64
// compose rounds from), and with attribution the technique (its exact mapping). Two pairs with
// the same key run the same instructions on the same data -- with binary32 matrices and
// n = 1, f = 1e9, standard and infinite do, as do reversed and reversed_infinite -- so the later
// one takes the earlier one's rows.
std::string computation_key(const Scene& scene, const EvalPair& pair, double z, bool attribute) {
  const KernelVariant v = mts_variant(scene, pair);
  const ProbeConstants pc = probe_constants(scene, pair, z);
  const auto packed = pc.packed();
  std::string key = v.program + "|" + v.options + "|" + (attribute ? info(pair.technique).name : "") + "|";
  key.append(reinterpret_cast<const char*>(packed.data()), sizeof(float) * packed.size());
  key.append(reinterpret_cast<const char*>(pc.P_full.data()), sizeof(double) * pc.P_full.size());
  key.append(reinterpret_cast<const char*>(&z), sizeof z);
  return key;
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
  std::map<std::string, MtsRow> computed;          // computation_key -> the row it gave
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
    // rows an identical computation already gave: taken over, with no work of their own
    std::vector<MtsRow> shared;
    std::vector<double> fresh;
    for (double z : todo) {
      const auto it = computed.find(computation_key(scene, pair, z, control.attribute));
      if (it == computed.end()) {
        fresh.push_back(z);
        continue;
      }
      // The row is the computation's, work included, so it reads the same whichever pair (or
      // shard) ran it; only its measured time is this run's: none.
      MtsRow r = it->second;
      r.pair = pair;
      r.seconds = r.kernel_seconds = 0;
      shared.push_back(r);
      if (control.on_row) control.on_row(r);
    }
    if (!shared.empty() && log)
      log(fmt::format("{}: {} distances computed exactly as by an earlier pair, rows taken over", pair.label(),
                      shared.size()));
    run.rows.insert(run.rows.end(), shared.begin(), shared.end());
    todo = fresh;
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
    run.info.evaluated_pairs += ev.fragment_pairs();
    run.info.kernel_seconds += ev.kernel_seconds();
    if (log) {
      const auto& w = ev.pairs_by_outcome();
      const double all = std::max<double>(1.0, static_cast<double>(ev.fragment_pairs()));
      log(fmt::format("{}: {} distances, {} fragment pairs, {} launches, {:.2f} s ({:.2f} s in kernels); "
                      "pairs on clean probes {:.0f} %, fighting {:.0f} % (of which past the deciding frame "
                      "{:.0f} %), clipped or non-finite {:.0f} %; decided from code bounds without rasterising {:.0f} %; "
                      "rasterised rows with plane B's coverage taken from A's {:.0f} %",
                      pair.label(), rows.size(), ev.fragment_pairs(), ev.launches(), ev.wall_seconds(),
                      ev.kernel_seconds(), 100 * w[0] / all, 100 * w[1] / all, 100 * ev.pairs_after_decision() / all,
                      100 * (w[2] + w[3]) / all, 100 * ev.pairs_decided_by_bounds() / all,
                      100.0 * static_cast<double>(ev.rows_with_coverage_of_a()) /
                          std::max<double>(1.0, static_cast<double>(ev.rows_rasterised()))));
    }
    for (const auto& r : rows) computed.emplace(computation_key(scene, pair, r.z, control.attribute), r);
    run.rows.insert(run.rows.end(), rows.begin(), rows.end());
  }
  sort_rows(scene, run.rows);
  for (const auto& r : run.rows) run.info.fragment_pairs += r.fragment_pairs;
  run.info.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return run;
}

}  // namespace depthprec
