#include "host/mts/mts_run.h"

#include <fmt/format.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <exception>
#include <map>
#include <mutex>
#include <set>
#include <thread>

#include "host/base/errors.h"
#include "host/model/frame_setup.h"
#include "host/mts/mts_exact.h"
#include "host/mts/mts_search.h"
#include "host/mts/row_json.h"
#include "host/mts/worst_case.h"
#include "host/runtime/kernel_variant.h"

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

SceneRows scene_rows(const Scene& scene) {
  SceneRows out;
  for (const auto& pair : scene.evaluate)
    for (double z : scene.distances) {
      out.index_of[row_key(pair, z)] = out.keys.size();
      out.keys.push_back(row_key(pair, z));
    }
  return out;
}

RunControl control_for(const SceneRows& rows, const std::vector<size_t>& todo,
                       const std::function<bool()>& stop) {
  RunControl control;
  const std::set<size_t> wanted(todo.begin(), todo.end());
  for (size_t k = 0; k < rows.keys.size(); ++k)
    if (!wanted.count(k)) control.done.insert(rows.keys[k]);
  control.stop = stop;
  return control;
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
void attribute_rows(OpenClRuntime& rt, const Scene& scene, const EvalPair& pair,
                    std::vector<MtsRow>& rows, std::map<std::string, double>& arithmetic_cache,
                    const std::function<bool()>& stop) {
  Scene plain = scene;
  plain.stiffness_probes = 0;
  std::vector<double> zs;
  for (const auto& r : rows) zs.push_back(r.z);
  ExactEvaluator exact(rt, plain, pair);
  auto storage = search_pair(exact, plain, pair, zs, {}, stop);
  // Under worst-case sampling each factor is its own worst case, as the MTS is.
  if (scene.sampling == Sampling::worst_case)
    refine_worst_case(
        [&rt, &pair](const Scene& s, const std::function<void(ProbeEvaluator&)>& use) {
          ExactEvaluator round_ev(rt, s, pair);
          use(round_ev);
        },
        plain, pair, storage, stop);
  EvalPair raw = pair;
  raw.format = "float32";
  const bool is_raw = pair.format == "float32";
  if (is_raw)
    for (const auto& r : rows) arithmetic_cache[row_key(raw, r.z)] = r.mts;
  std::vector<double> missing;
  for (double z : zs)
    if (!arithmetic_cache.count(row_key(raw, z))) missing.push_back(z);
  if (!missing.empty()) {
    for (const auto& r : search_sampled(rt, plain, raw, missing, stop))
      arithmetic_cache[row_key(raw, r.z)] = r.mts;
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
  std::string key =
      v.program + "|" + v.options + "|" + (attribute ? info(pair.technique).name : "") + "|";
  key.append(reinterpret_cast<const char*>(packed.data()), sizeof(float) * packed.size());
  key.append(reinterpret_cast<const char*>(pc.P_full.data()), sizeof(double) * pc.P_full.size());
  key.append(reinterpret_cast<const char*>(&z), sizeof z);
  return key;
}

}  // namespace

namespace {

// One pair's share of a run: the distances it computes itself, and those an earlier pair of the
// run computes exactly (same computation_key), whose rows it takes over once that pair is done.
struct PairWork {
  std::vector<double> fresh;
  std::vector<std::string> shared;  // the computation keys of the rows taken over
  std::set<size_t> owners;          // the pairs the shared rows come from
  bool logs_variant = false;        // the first pair to build its variant
};

std::vector<PairWork> plan_pairs(const Scene& scene, const RunControl& control) {
  std::vector<PairWork> work(scene.evaluate.size());
  std::map<std::string, size_t> owner;  // computation_key -> the pair computing it
  std::set<std::string> variants;
  const size_t nd = scene.distances.size();
  for (size_t p = 0; p < scene.evaluate.size(); ++p) {
    const EvalPair& pair = scene.evaluate[p];
    for (size_t d = 0; d < nd; ++d) {
      const size_t k = p * nd + d;
      const double z = scene.distances[d];
      if (static_cast<int>(k % static_cast<size_t>(control.shard_count)) != control.shard_index)
        continue;
      if (control.done.count(row_key(pair, z))) continue;
      const std::string key = computation_key(scene, pair, z, control.attribute);
      const auto [it, first] = owner.emplace(key, p);
      if (first) {
        work[p].fresh.push_back(z);
      } else if (it->second == p) {
        // A pair cannot wait for itself; scenes list each distance once (load_scene refuses
        // repeats).
        throw Error(ExitCode::internal, fmt::format("{} computes z = {} twice", pair.label(), z));
      } else {
        work[p].shared.push_back(key);
        work[p].owners.insert(it->second);
      }
    }
    if (!work[p].fresh.empty())
      work[p].logs_variant = variants.insert(mts_variant(scene, pair).label).second;
  }
  return work;
}

}  // namespace

MtsRun run_scene(OpenClRuntime& rt, const Scene& scene,
                 const std::function<void(const std::string&)>& log, const RunControl& control) {
  MtsRun run;
  run.info.device = rt.description();
  run.info.variants = scene_variants(scene);
  const auto t0 = std::chrono::steady_clock::now();
  const size_t np = scene.evaluate.size();
  const std::vector<PairWork> work = plan_pairs(scene, control);

  // Shared between the jobs, under `m`: rows by computation key, the arithmetic-limited MTS of
  // attribution, which pairs are finished, each pair's rows and log lines (printed in pair order,
  // so verbose output does not depend on which job finished first), the first failure.
  std::mutex m;
  std::condition_variable pair_finished;
  std::map<std::string, MtsRow> computed;
  std::map<std::string, double> arithmetic_cache;  // row key of a float32 pair -> its MTS
  std::vector<char> finished(np, 0);
  std::vector<std::vector<MtsRow>> pair_rows(np);
  std::vector<std::vector<std::string>> pair_log(np);
  size_t next_log = 0;
  std::exception_ptr failure;
  bool failed = false;
  const auto stop = [&control, &m, &failed]() {
    {
      std::lock_guard<std::mutex> lock(m);
      if (failed) return true;
    }
    return control.stop && control.stop();
  };
  const auto on_row = [&control, &m](const MtsRow& r) {
    std::lock_guard<std::mutex> lock(m);
    if (control.on_row) control.on_row(r);
  };

  // With fewer pairs to compute than jobs (one pair, say) a pair's distances are split between
  // jobs, every k-th to a part, so each part holds near and far distances alike; each part has
  // an evaluator of its own. A row does not depend on which distances share its launches.
  size_t computing = 0;
  for (const PairWork& w : work) computing += w.fresh.empty() ? 0 : 1;
  const size_t parts_per_pair = std::max<size_t>(
      1, static_cast<size_t>(std::max(1, control.jobs)) / std::max<size_t>(1, computing));
  struct Unit {
    size_t pair;
    std::vector<double> zs;
  };
  std::vector<Unit> units;
  std::vector<size_t> parts_left(np, 0);
  for (size_t p = 0; p < np; ++p) {
    const size_t k =
        control.attribute ? 1 : std::clamp<size_t>(work[p].fresh.size(), 1, parts_per_pair);
    for (size_t i = 0; i < k; ++i) {
      Unit u{p, {}};
      for (size_t d = i; d < work[p].fresh.size(); d += k) u.zs.push_back(work[p].fresh[d]);
      units.push_back(std::move(u));
    }
    parts_left[p] = k;
  }
  // Units are taken in scene order, so a pair waits only for earlier ones, each finished or in
  // progress on another job: no cycle. The calling thread is one of the jobs.
  const int jobs = control.attribute
                       ? 1
                       : static_cast<int>(std::min<size_t>(
                             static_cast<size_t>(std::max(1, control.jobs)), units.size()));
  // What the -v line says of a pair: its parts' evaluators summed.
  struct PairStats {
    size_t distances = 0;
    uint64_t pairs = 0, launches = 0, after_decision = 0, by_bounds = 0, rows_rasterised = 0,
             rows_reused = 0, repeats = 0;
    std::array<uint64_t, 4> by_outcome{};
    double wall = 0, kernel = 0;
  };
  std::vector<PairStats> stats(np);
  // Jobs side by side first prime the kernels they launch, wide enough for every launch of the
  // run (MtsEvaluator::prime_launches: PoCL 3.1 aborts otherwise).
  LaunchPrimer primer;
  MtsEvaluator::LaunchWidths prime_widths;
  Scene round_scene = scene;  // worst-case sampling's rounds, in chunks of round_size
  round_scene.frames = scene.worst_case.round_size;
  for (const Unit& u : units) {
    prime_widths |= MtsEvaluator::widest_launches(scene, scene.evaluate[u.pair], jobs);
    if (scene.sampling == Sampling::worst_case)
      prime_widths |= MtsEvaluator::widest_launches(round_scene, scene.evaluate[u.pair], jobs);
  }

  // Search some of a pair's distances in one evaluator; rows go to on_row as they finish.
  // One evaluator's statistics into its pair's and the run's.
  const auto add_stats = [&](size_t p, const MtsEvaluator& ev) {
    std::lock_guard<std::mutex> lock(m);
    PairStats& st = stats[p];
    st.pairs += ev.fragment_pairs();
    st.launches += ev.launches();
    st.after_decision += ev.pairs_after_decision();
    st.by_bounds += ev.pairs_decided_by_bounds();
    st.rows_rasterised += ev.rows_rasterised();
    st.rows_reused += ev.rows_with_coverage_of_a();
    st.repeats += ev.probes_repeated();
    for (size_t i = 0; i < st.by_outcome.size(); ++i) st.by_outcome[i] += ev.pairs_by_outcome()[i];
    st.wall += ev.wall_seconds();
    st.kernel += ev.kernel_seconds();
    run.info.launches += ev.launches();
    run.info.evaluated_pairs += ev.fragment_pairs();
    run.info.kernel_seconds += ev.kernel_seconds();
  };
  const bool worst_case = scene.sampling == Sampling::worst_case;
  // Search some of a pair's distances in one evaluator (and under worst-case sampling refine
  // them, an evaluator per round); rows go to on_row as they finish.
  const auto compute = [&](size_t p, const std::vector<double>& zs) {
    const EvalPair& pair = scene.evaluate[p];
    const auto with_evaluator = [&](const Scene& s,
                                    const std::function<void(ProbeEvaluator&)>& use) {
      MtsEvaluator ev(rt, s, pair);
      ev.share_plane_a_budget(jobs);
      if (jobs > 1) ev.prime_launches(prime_widths, primer);
      use(ev);
      add_stats(p, ev);
    };
    const bool rows_later = control.attribute || worst_case;
    std::vector<MtsRow> rows;
    with_evaluator(scene, [&](ProbeEvaluator& ev) {
      rows = search_pair(ev, scene, pair, zs,
                         rows_later ? std::function<void(const MtsRow&)>() : on_row, stop);
    });
    if (worst_case) refine_worst_case(with_evaluator, scene, pair, rows, stop);
    if (worst_case && !control.attribute)
      for (const auto& r : rows) on_row(r);
    if (control.attribute) {
      // The arithmetic cache makes a row's attribution depend on which pairs ran before it:
      // attribution runs one job (RunControl::jobs), so that order is the scene's.
      attribute_rows(rt, scene, pair, rows, arithmetic_cache, stop);
      for (const auto& r : rows) on_row(r);
    }
    std::lock_guard<std::mutex> lock(m);
    stats[p].distances += rows.size();
    for (const auto& r : rows)
      computed.emplace(computation_key(scene, pair, r.z, control.attribute), r);
    pair_rows[p].insert(pair_rows[p].end(), rows.begin(), rows.end());
  };

  // Once every part of pair p has run: its -v lines, then the rows an identical computation gives,
  // taken over once their pairs are done, with no work of their own. The row is the
  // computation's, work included, so it reads the same whichever pair (or shard) ran it; only its
  // measured time is this run's: none.
  const auto finish_pair = [&](size_t p) {
    const EvalPair& pair = scene.evaluate[p];
    if (!work[p].fresh.empty()) {
      std::lock_guard<std::mutex> lock(m);
      if (work[p].logs_variant) {
        const KernelVariant v = mts_variant(scene, pair);
        pair_log[p].push_back(fmt::format("kernel variant {}: {} {}; set-up {} {}", v.label,
                                          v.program, v.options, v.setup_program, v.setup_options));
      }
      const PairStats& st = stats[p];
      const auto& w = st.by_outcome;
      const double all = std::max<double>(1.0, static_cast<double>(st.pairs));
      pair_log[p].push_back(fmt::format(
          "{}: {} distances, {} fragment pairs, {} launches, {:.2f} s ({:.2f} s in kernels); "
          "pairs on clean probes {:.0f} %, fighting {:.0f} % (of which past the deciding frame "
          "{:.0f} %), clipped or non-finite {:.0f} %; decided from code bounds without "
          "rasterising {:.0f} %; rasterised rows with plane B's coverage taken from A's {:.0f} %; "
          "probes taken from an earlier one with the same plane B {}",
          pair.label(), st.distances, st.pairs, st.launches, st.wall, st.kernel, 100 * w[0] / all,
          100 * w[1] / all, 100 * st.after_decision / all, 100 * (w[2] + w[3]) / all,
          100 * st.by_bounds / all,
          100.0 * static_cast<double>(st.rows_reused) /
              std::max<double>(1.0, static_cast<double>(st.rows_rasterised)),
          st.repeats));
    }
    if (work[p].shared.empty()) return;
    std::vector<MtsRow> taken;
    {
      std::unique_lock<std::mutex> lock(m);
      const auto owners_done = [&]() {
        for (size_t o : work[p].owners)
          if (!finished[o]) return false;
        return true;
      };
      // The owners stop between launches when interrupted and then finish (failed); the wait
      // still looks at the interrupt itself, so no path waits without honouring it.
      while (!pair_finished.wait_for(lock, std::chrono::milliseconds(100), owners_done)) {
        if (control.stop && control.stop()) throw Error(ExitCode::interrupted, "interrupted");
      }
      // An owner that did not finish its rows failed, and so has the run; otherwise every key is
      // there.
      if (failed) return;
      for (const std::string& key : work[p].shared) {
        MtsRow r = computed.at(key);
        r.pair = pair;
        r.seconds = r.kernel_seconds = 0;
        taken.push_back(r);
      }
      pair_rows[p].insert(pair_rows[p].begin(), taken.begin(), taken.end());
      if (!taken.empty())
        pair_log[p].insert(
            pair_log[p].begin(),
            fmt::format("{}: {} distances computed exactly as by an earlier pair, rows taken over",
                        pair.label(), taken.size()));
    }
    for (const auto& r : taken) on_row(r);
  };

  const auto fail = [&]() {
    std::lock_guard<std::mutex> lock(m);
    if (!failure) failure = std::current_exception();
    failed = true;
  };
  std::atomic<size_t> next_unit{0};
  const auto job = [&]() {
    for (size_t u = next_unit++; u < units.size(); u = next_unit++) {
      const size_t p = units[u].pair;
      try {
        if (!units[u].zs.empty()) compute(p, units[u].zs);
      } catch (...) {
        fail();
      }
      {
        std::lock_guard<std::mutex> lock(m);
        if (--parts_left[p] > 0) continue;
      }
      try {
        finish_pair(p);
      } catch (...) {
        fail();
      }
      std::lock_guard<std::mutex> lock(m);
      finished[p] = 1;
      for (; next_log < np && finished[next_log]; ++next_log)
        if (log)
          for (const auto& line : pair_log[next_log]) log(line);
      pair_finished.notify_all();
    }
  };
  std::vector<std::thread> helpers;
  for (int j = 1; j < jobs; ++j) helpers.emplace_back(job);
  job();
  for (auto& t : helpers) t.join();
  if (failure) {
    // A signal that stops the run can also break what another job is doing at that moment: a
    // program build inside PoCL's compiler fails ("1 error generated") when SIGINT arrives during
    // it. Once a stop is requested, any failure reads as the interruption it followed; --resume
    // then rebuilds and would show a genuine error.
    if (control.stop && control.stop()) throw Error(ExitCode::interrupted, "interrupted");
    std::rethrow_exception(failure);
  }

  for (auto& rows : pair_rows) run.rows.insert(run.rows.end(), rows.begin(), rows.end());
  sort_rows(scene, run.rows);
  for (const auto& r : run.rows) run.info.fragment_pairs += r.fragment_pairs;
  run.info.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return run;
}

}  // namespace depthprec
