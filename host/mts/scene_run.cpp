#include "host/mts/scene_run.h"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <thread>

#include "host/base/errors.h"
#include "host/model/frame_setup.h"
#include "host/mts/mts_exact.h"
#include "host/mts/mts_search.h"
#include "host/mts/row_json.h"
#include "host/mts/worst_case.h"

namespace depthprec {

namespace {

// The attribution factors of a pair's rows: the storage-limited MTS from the binary64 pipeline
// (kernels/mts_exact.cl) and the arithmetic-limited MTS from the same binary32 pipeline storing
// in float32, which holds every binary32 depth exactly (a float32 pair is its own; another
// pair's comes from arithmetic, given the float32 pair and the scene without stiffness probes).
// The factor searches skip the stiffness probes: they report a number, not a stability check.
using ArithmeticMts = std::function<std::vector<double>(const EvalPair& raw, const Scene& plain,
                                                        const std::vector<double>& zs)>;
void attribute_rows(OpenClRuntime& rt, const Scene& scene, const EvalPair& pair,
                    std::vector<MtsRow>& rows, const ArithmeticMts& arithmetic,
                    const std::function<bool()>& stop) {
  Scene plain = scene;
  plain.stiffness_probes = 0;
  std::vector<double> zs;
  for (const auto& r : rows) zs.push_back(r.z);
  // Under worst-case sampling each factor is its own worst case, as the MTS is.
  PairSource<ProbeEvaluator, ExactEvaluator> exact(rt, pair);
  const auto storage = search_sampled(exact, plain, pair, zs, {}, stop);
  EvalPair raw = pair;
  raw.format = "float32";
  std::vector<double> arithmetic_mts;
  if (pair.format == "float32")
    for (const auto& r : rows) arithmetic_mts.push_back(r.mts);
  else
    arithmetic_mts = arithmetic(raw, plain, zs);
  for (size_t i = 0; i < rows.size(); ++i) {
    rows[i].storage_mts = storage[i].beyond_far ? INFINITY : storage[i].mts;
    rows[i].arithmetic_mts = arithmetic_mts[i];
    rows[i].set_dominant(scene.rel_precision);
  }
}

}  // namespace

SceneRun::SceneRun(OpenClRuntime& rt, const Scene& scene, const Log& log, const RunControl& control)
    : rt_(rt), scene_(scene), log_(log), control_(control) {}

MtsRun SceneRun::run() {
  run_.info.device = rt_.description();
  const auto t0 = std::chrono::steady_clock::now();
  plan_pairs();
  plan_units();

  // The calling thread is one of the jobs.
  std::vector<std::thread> helpers;
  for (int j = 1; j < jobs_; ++j) helpers.emplace_back([this] { job(); });
  job();
  for (auto& t : helpers) t.join();
  if (failure_) {
    // A signal that stops the run can also break what another job is doing at that moment: a
    // program build inside PoCL's compiler fails ("1 error generated") when SIGINT arrives during
    // it. Once a stop is requested, any failure reads as the interruption it followed; --resume
    // then rebuilds and would show a genuine error.
    if (control_.stop && control_.stop()) throw Error(ExitCode::interrupted, "interrupted");
    std::rethrow_exception(failure_);
  }

  for (auto& rows : pair_rows_) run_.rows.insert(run_.rows.end(), rows.begin(), rows.end());
  sort_rows(scene_, run_.rows);
  for (const auto& r : run_.rows) run_.info.fragment_pairs += r.fragment_pairs;
  run_.info.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return std::move(run_);
}

// What decides a row's computation, byte for byte: the kernel program and its build options, the
// binary32 constants the set-up reads at this z (and the binary64 P a premultiplied binary64
// compose rounds from), and with attribution the technique (its exact mapping). Two pairs with
// the same key run the same instructions on the same data -- with binary32 matrices and
// n = 1, f = 1e9, standard and infinite do, as do reversed and reversed_infinite -- so the later
// one takes the earlier one's rows.
std::string SceneRun::computation_key(size_t p, double z) const {
  const EvalPair& pair = scene_.evaluate[p];
  const KernelVariant& v = plan_[p].variant;
  const ProbeConstants pc = probe_constants(scene_, pair, z);
  const auto packed = pc.packed(1);
  std::string key = v.program + "|" + v.options + "|" +
                    (control_.attribute ? info(pair.technique).name : "") + "|";
  key.append(reinterpret_cast<const char*>(packed.data()), sizeof(float) * packed.size());
  key.append(reinterpret_cast<const char*>(pc.P_full.data()), sizeof(double) * pc.P_full.size());
  key.append(reinterpret_cast<const char*>(&z), sizeof z);
  return key;
}

void SceneRun::plan_pairs() {
  const size_t np = scene_.evaluate.size();
  plan_.assign(np, PairPlan{});
  std::map<std::string, size_t> owner;  // computation_key -> the pair computing it
  std::set<std::string> variants_built;
  const size_t nd = scene_.distances.size();
  for (size_t p = 0; p < np; ++p) {
    const EvalPair& pair = scene_.evaluate[p];
    PairPlan& pair_plan = plan_[p];
    pair_plan.variant = mts_variant(scene_, pair);
    for (size_t d = 0; d < nd; ++d) {
      const size_t k = p * nd + d;
      const double z = scene_.distances[d];
      if (static_cast<int>(k % static_cast<size_t>(control_.shard_count)) != control_.shard_index)
        continue;
      if (control_.done.count(row_key(pair, z))) continue;
      const std::string key = computation_key(p, z);
      const auto [it, first] = owner.emplace(key, p);
      if (first) {
        pair_plan.fresh.push_back(z);
      } else if (it->second == p) {
        // A pair cannot wait for itself; scenes list each distance once (load_scene refuses
        // repeats).
        throw Error(ExitCode::internal, fmt::format("{} computes z = {} twice", pair.label(), z));
      } else {
        pair_plan.shared.push_back(key);
        pair_plan.owners.insert(it->second);
      }
    }
    if (!pair_plan.fresh.empty())
      pair_plan.logs_variant = variants_built.insert(pair_plan.variant.label).second;
  }
  // The run's variants (RunInfo::variants) from the plan's, every pair's whatever it computes.
  std::vector<KernelVariant> pair_variants;
  for (const PairPlan& pair_plan : plan_) pair_variants.push_back(pair_plan.variant);
  run_.info.variants = variant_labels(pair_variants);
}

void SceneRun::plan_units() {
  const size_t np = scene_.evaluate.size();
  // With fewer pairs to compute than jobs (one pair, say) a pair's distances are split between
  // jobs, every k-th to a part, so each part holds near and far distances alike; each part has
  // an evaluator of its own. A row does not depend on which distances share its launches.
  size_t computing = 0;
  for (const PairPlan& pair_plan : plan_) computing += pair_plan.fresh.empty() ? 0 : 1;
  const size_t parts_per_pair = std::max<size_t>(
      1, static_cast<size_t>(std::max(1, control_.jobs)) / std::max<size_t>(1, computing));
  parts_left_.assign(np, 0);
  for (size_t p = 0; p < np; ++p) {
    const std::vector<double>& fresh = plan_[p].fresh;
    const size_t k = std::clamp<size_t>(fresh.size(), 1, parts_per_pair);
    for (size_t i = 0; i < k; ++i) {
      Unit u{p, {}};
      for (size_t d = i; d < fresh.size(); d += k) u.zs.push_back(fresh[d]);
      units_.push_back(std::move(u));
    }
    parts_left_[p] = k;
  }
  // Units are taken in scene order, so a pair waits only for earlier ones, each finished or in
  // progress on another job: no cycle.
  jobs_ = static_cast<int>(
      std::min<size_t>(static_cast<size_t>(std::max(1, control_.jobs)), units_.size()));
  Scene round_scene = scene_;  // worst-case sampling's rounds, in chunks of round_size
  round_scene.frames = scene_.worst_case.round_size;
  Scene one_frame = scene_;  // and its searches of one frame, every distance of a pair at once
  one_frame.frames = 1;
  for (const Unit& u : units_) {
    std::vector<KernelVariant> variants{plan_[u.pair].variant};
    if (control_.attribute && scene_.evaluate[u.pair].format != "float32") {
      EvalPair raw = scene_.evaluate[u.pair];  // its arithmetic-limited MTS may be searched
      raw.format = "float32";
      variants.push_back(mts_variant(scene_, raw));
    }
    for (const KernelVariant& v : variants) {
      prime_widths_ |= MtsEvaluator::widest_launches(scene_, v, jobs_);
      if (scene_.sampling == Sampling::worst_case) {
        prime_widths_ |= MtsEvaluator::widest_launches(round_scene, v, jobs_);
        prime_widths_ |= MtsEvaluator::widest_launches(one_frame, v, jobs_);
      }
    }
  }
  stats_.assign(np, PairStats{});
  finished_.assign(np, 0);
  pair_rows_.assign(np, {});
  pair_log_.assign(np, {});
}

void SceneRun::job() {
  for (size_t u = next_unit_++; u < units_.size(); u = next_unit_++) {
    const size_t p = units_[u].pair;
    try {
      if (!units_[u].zs.empty()) compute(p, units_[u].zs);
    } catch (...) {
      fail();
    }
    {
      std::lock_guard<std::mutex> lock(m_);
      if (--parts_left_[p] > 0) continue;
    }
    try {
      log_pair(p);
      take_over_identical_rows(p);
    } catch (...) {
      fail();
    }
    finish_pair(p);
  }
}

std::unique_ptr<ProbeEvaluator> SceneRun::RunSource::make(const Scene& s, const Orientations& o) {
  auto ev = std::make_unique<MtsEvaluator>(run_.rt_, s, pair_, o);
  ev->share_plane_a_budget(run_.jobs_);
  if (run_.jobs_ > 1) ev->prime_launches(run_.prime_widths_, run_.primer_);
  ev->adopt_plane_a_buffers(std::move(spare_));  // leaves spare_'s buffers null
  return ev;
}

void SceneRun::RunSource::retire(ProbeEvaluator& ev) {
  auto& mts = static_cast<MtsEvaluator&>(ev);  // as make built it
  if (stats_of_ != kNoStats) run_.add_stats(stats_of_, mts);
  // An orientation searched alone retires between its chunk's evaluators: the chunks' larger
  // buffers are the ones worth keeping.
  MtsEvaluator::PlaneABuffers left = mts.release_plane_a_buffers();
  if (left.bytes() >= spare_.bytes()) spare_ = std::move(left);
}

// The arithmetic-limited MTS of pair p's distances zs: the MTS of raw, its float32 pair, where
// an earlier pair of the run is raw and computes the distance itself (its row, once that pair is
// done), else a search of raw over the plain scene, kept for later pairs. Either way the value
// does not depend on which job ran first: the jobs can attribute side by side.
std::vector<double> SceneRun::arithmetic_mts(size_t p, const EvalPair& raw, const Scene& plain,
                                             const std::vector<double>& zs,
                                             const std::function<bool()>& stop) {
  size_t sibling = p;
  for (size_t q = 0; q < p; ++q)
    if (scene_.evaluate[q].label() == raw.label()) sibling = q;
  std::vector<double> out(zs.size(), NAN);
  std::vector<double> missing;
  {
    std::unique_lock<std::mutex> lock(m_);
    if (sibling < p) {
      // The sibling's units were all taken before p's (scene order): it finishes without p.
      while (!pair_finished_.wait_for(lock, std::chrono::milliseconds(100),
                                      [&] { return finished_[sibling] != 0; }))
        if (control_.stop && control_.stop()) throw Error(ExitCode::interrupted, "interrupted");
      if (failed_) throw Error(ExitCode::interrupted, "interrupted");
    }
    const std::vector<double>& fresh = plan_[sibling].fresh;
    for (size_t i = 0; i < zs.size(); ++i) {
      if (sibling < p && std::find(fresh.begin(), fresh.end(), zs[i]) != fresh.end())
        out[i] = computed_.at(computation_key(sibling, zs[i])).mts;
      else if (const auto it = arithmetic_cache_.find(row_key(raw, zs[i]));
               it != arithmetic_cache_.end())
        out[i] = it->second;
      else
        missing.push_back(zs[i]);
    }
  }
  if (missing.empty()) return out;
  RunSource source(*this, raw, RunSource::kNoStats);
  const std::vector<MtsRow> found = search_sampled(source, plain, raw, missing, {}, stop);
  std::lock_guard<std::mutex> lock(m_);
  for (const MtsRow& r : found) arithmetic_cache_.emplace(row_key(raw, r.z), r.mts);
  for (size_t i = 0; i < zs.size(); ++i)
    if (std::isnan(out[i])) out[i] = arithmetic_cache_.at(row_key(raw, zs[i]));
  return out;
}

// Searches some of a pair's distances in one evaluator (and under worst-case sampling refines
// them, an evaluator per round); rows go to the journal as they finish.
void SceneRun::compute(size_t p, const std::vector<double>& zs) {
  const EvalPair& pair = scene_.evaluate[p];
  const std::function<bool()> stop = [this] { return stop_requested(); };
  // Attributed rows go to the journal once attributed.
  std::function<void(const MtsRow&)> on_row;
  if (!control_.attribute) on_row = [this](const MtsRow& r) { pass_on(r); };
  // The run's evaluators: the plane-A budget shared between the jobs, launches primed, and
  // their statistics the pair's.
  std::vector<MtsRow> rows;
  {  // the source, and the plane-A buffers it keeps between evaluators, end with the search
    RunSource source(*this, pair, p);
    rows = search_sampled(source, scene_, pair, zs, on_row, stop);
  }
  if (control_.attribute) {
    const ArithmeticMts arithmetic = [&](const EvalPair& raw, const Scene& plain,
                                         const std::vector<double>& want) {
      return arithmetic_mts(p, raw, plain, want, stop);
    };
    attribute_rows(rt_, scene_, pair, rows, arithmetic, stop);
    for (const auto& r : rows) pass_on(r);
  }
  std::lock_guard<std::mutex> lock(m_);
  stats_[p].distances += rows.size();
  for (const auto& r : rows) computed_.emplace(computation_key(p, r.z), r);
  pair_rows_[p].insert(pair_rows_[p].end(), rows.begin(), rows.end());
}

// One evaluator's statistics into its pair's and the run's.
void SceneRun::add_stats(size_t p, const MtsEvaluator& ev) {
  std::lock_guard<std::mutex> lock(m_);
  PairStats& st = stats_[p];
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
  run_.info.launches += ev.launches();
  run_.info.evaluated_pairs += ev.fragment_pairs();
  run_.info.kernel_seconds += ev.kernel_seconds();
}

// Once every part of pair p has run: the rows an identical computation gives, taken over once
// their pairs are done, with no work of their own. The row is the computation's, work included,
// so it reads the same whichever pair (or shard) ran it; only its measured time is this run's:
// none.
void SceneRun::take_over_identical_rows(size_t p) {
  const PairPlan& pair_plan = plan_[p];
  if (pair_plan.shared.empty()) return;
  const EvalPair& pair = scene_.evaluate[p];
  std::vector<MtsRow> taken;
  {
    std::unique_lock<std::mutex> lock(m_);
    const auto owners_done = [&]() {
      for (size_t o : pair_plan.owners)
        if (!finished_[o]) return false;
      return true;
    };
    // The owners stop between launches when interrupted and then finish (failed); the wait
    // still looks at the interrupt itself, so no path waits without honouring it.
    while (!pair_finished_.wait_for(lock, std::chrono::milliseconds(100), owners_done)) {
      if (control_.stop && control_.stop()) throw Error(ExitCode::interrupted, "interrupted");
    }
    // An owner that did not finish its rows failed, and so has the run; otherwise every key is
    // there.
    if (failed_) return;
    for (const std::string& key : pair_plan.shared) {
      MtsRow r = computed_.at(key);
      r.pair = pair;
      r.seconds = r.kernel_seconds = 0;
      taken.push_back(r);
    }
    pair_rows_[p].insert(pair_rows_[p].begin(), taken.begin(), taken.end());
    if (!taken.empty())
      pair_log_[p].insert(
          pair_log_[p].begin(),
          fmt::format("{}: {} distances computed exactly as by an earlier pair, rows taken over",
                      pair.label(), taken.size()));
  }
  for (const auto& r : taken) pass_on(r);
}

// Pair p is done (or failed): its lines are printed once every earlier pair's are, and the pairs
// waiting to take over its rows wake.
void SceneRun::finish_pair(size_t p) {
  std::lock_guard<std::mutex> lock(m_);
  finished_[p] = 1;
  print_finished_logs();
  pair_finished_.notify_all();
}

// Once every part of pair p has run: the -v lines of the pair's own computation (the variant it
// was first to build, its evaluators' statistics).
void SceneRun::log_pair(size_t p) {
  const PairPlan& pair_plan = plan_[p];
  if (pair_plan.fresh.empty()) return;
  std::lock_guard<std::mutex> lock(m_);
  if (pair_plan.logs_variant) {
    const KernelVariant& v = pair_plan.variant;
    pair_log_[p].push_back(fmt::format("kernel variant {}: {} {}; set-up {} {}", v.label, v.program,
                                       v.options, v.setup_program, v.setup_options));
  }
  const PairStats& st = stats_[p];
  const auto& o = st.by_outcome;
  const double all = std::max<double>(1.0, static_cast<double>(st.pairs));
  pair_log_[p].push_back(fmt::format(
      "{}: {} distances, {} fragment pairs, {} launches, {:.2f} s ({:.2f} s in kernels); "
      "pairs on clean probes {:.0f} %, fighting {:.0f} % (of which past the deciding frame "
      "{:.0f} %), clipped or non-finite {:.0f} %; decided from code bounds without "
      "rasterising {:.0f} %; rasterised rows with plane B's coverage taken from A's {:.0f} %; "
      "probes taken from an earlier one with the same plane B {}",
      scene_.evaluate[p].label(), st.distances, st.pairs, st.launches, st.wall, st.kernel,
      100 * o[0] / all, 100 * o[1] / all, 100 * st.after_decision / all, 100 * (o[2] + o[3]) / all,
      100 * st.by_bounds / all,
      100.0 * static_cast<double>(st.rows_reused) /
          std::max<double>(1.0, static_cast<double>(st.rows_rasterised)),
      st.repeats));
}

void SceneRun::print_finished_logs() {
  for (; next_log_ < plan_.size() && finished_[next_log_]; ++next_log_)
    if (log_)
      for (const auto& line : pair_log_[next_log_]) log_(line);
}

bool SceneRun::stop_requested() {
  {
    std::lock_guard<std::mutex> lock(m_);
    if (failed_) return true;
  }
  return control_.stop && control_.stop();
}

void SceneRun::pass_on(const MtsRow& r) {
  std::lock_guard<std::mutex> lock(m_);
  if (control_.on_row) control_.on_row(r);
}

void SceneRun::fail() {
  std::lock_guard<std::mutex> lock(m_);
  if (!failure_) failure_ = std::current_exception();
  failed_ = true;
}

}  // namespace depthprec
