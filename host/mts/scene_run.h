// One run of a scene's pairs through the MTS search (run_scene, host/mts/mts_run.h), in steps:
// plan each pair's share (its kernel variant, the distances it computes, those it takes over from
// an identical pair) and the units the jobs take; run the units side by side; take over the
// identical rows once their pairs are done; log each pair's lines in pair order.
#pragma once

#include <array>
#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <exception>
#include <functional>
#include <map>
#include <mutex>
#include <set>
#include <string>
#include <vector>

#include "host/mts/mts_evaluator.h"
#include "host/mts/refinement.h"
#include "host/mts/run_rows.h"
#include "host/runtime/kernel_variant.h"

namespace depthprec {

class SceneRun {
 public:
  using Log = std::function<void(const std::string&)>;
  // log and control as run_scene takes them; all four must outlive the SceneRun.
  SceneRun(OpenClRuntime& rt, const Scene& scene, const Log& log, const RunControl& control);
  SceneRun(const SceneRun&) = delete;
  SceneRun& operator=(const SceneRun&) = delete;

  // The rows this run computed or took over, in scene order. Once per SceneRun.
  MtsRun run();

 private:
  // One pair's share of the run, fixed before anything is computed: its kernel variant (made
  // once here: the keys, the launch widths, the -v line and the run's list all read it), the
  // distances it computes itself, and those an earlier pair of the run computes exactly (same
  // computation_key), whose rows it takes over once that pair is done.
  struct PairPlan {
    KernelVariant variant;
    std::vector<double> fresh;
    std::vector<std::string> shared;  // the computation keys of the rows taken over
    std::set<size_t> owners;          // the pairs the shared rows come from
    bool logs_variant = false;        // the first pair to build its variant
  };
  // Some of a pair's fresh distances, searched by one job in one evaluator.
  struct Unit {
    size_t pair;
    std::vector<double> zs;
  };
  // What the -v line says of a pair: its parts' evaluators summed.
  struct PairStats {
    size_t distances = 0;
    uint64_t pairs = 0, launches = 0, after_decision = 0, by_bounds = 0, rows_rasterised = 0,
             rows_reused = 0, repeats = 0;
    std::array<uint64_t, 4> by_outcome{};
    double wall = 0, kernel = 0;
  };

  // Planning, before any job starts.
  void plan_pairs();
  void plan_units();
  std::string computation_key(size_t p, double z) const;

  // Running: each job takes the next unit until none is left; the job that runs a pair's last
  // part logs the pair, takes over its identical rows and finishes it.
  void job();
  void compute(size_t p, const std::vector<double>& zs);
  std::vector<double> arithmetic_mts(size_t p, const EvalPair& raw, const Scene& plain,
                                     const std::vector<double>& zs,
                                     const std::function<bool()>& stop);
  // The run's evaluators of one pair: the plane-A budget shared between the jobs, launches
  // primed, and their statistics those of pair stats_of (kNoStats: nobody's).
  class RunSource : public EvaluatorSource<ProbeEvaluator> {
   public:
    static constexpr size_t kNoStats = SIZE_MAX;
    RunSource(SceneRun& run, const EvalPair& pair, size_t stats_of)
        : run_(run), pair_(pair), stats_of_(stats_of) {}
    std::unique_ptr<ProbeEvaluator> make(const Scene& s, const Orientations& o) override;
    void retire(ProbeEvaluator& ev) override;

   private:
    SceneRun& run_;
    const EvalPair& pair_;
    size_t stats_of_;
    // The largest plane-A buffers a retired evaluator left, for the next evaluator, which takes
    // those at least as large as it needs and at most half as large again.
    MtsEvaluator::PlaneABuffers spare_;
  };
  void add_stats(size_t p, const MtsEvaluator& ev);
  void take_over_identical_rows(size_t p);
  void finish_pair(size_t p);

  // Logging: a pair's -v lines are gathered as it finishes and printed in pair order.
  void log_pair(size_t p);
  void print_finished_logs();  // with m_ held

  // Shared by the jobs: the interrupt (or a failed job), rows passed on as they finish (the
  // journal), the first failure.
  bool stop_requested();
  void pass_on(const MtsRow& r);
  void fail();

  OpenClRuntime& rt_;
  const Scene& scene_;
  const Log& log_;
  const RunControl& control_;
  MtsRun run_;

  // The plan: fixed before the jobs start, read by them without the lock.
  std::vector<PairPlan> plan_;
  std::vector<Unit> units_;
  int jobs_ = 1;
  // Jobs side by side first prime the kernels they launch, wide enough for every launch of the
  // run (MtsEvaluator::prime_launches: PoCL 3.1 aborts otherwise).
  MtsEvaluator::LaunchWidths prime_widths_;
  LaunchPrimer primer_;
  std::atomic<size_t> next_unit_{0};

  // Shared between the jobs, under m_: rows by computation key, the arithmetic-limited MTS of
  // attribution, which pairs are finished, each pair's rows and log lines (printed in pair order,
  // so verbose output does not depend on which job finished first), the first failure.
  std::mutex m_;
  std::condition_variable pair_finished_;
  std::vector<size_t> parts_left_;
  std::vector<PairStats> stats_;
  std::map<std::string, MtsRow> computed_;
  std::map<std::string, double> arithmetic_cache_;  // row key of a float32 pair -> its search
  std::vector<char> finished_;
  std::vector<std::vector<MtsRow>> pair_rows_;
  std::vector<std::vector<std::string>> pair_log_;
  size_t next_log_ = 0;
  std::exception_ptr failure_;
  bool failed_ = false;
};

}  // namespace depthprec
