#include "host/analysis/tradeoff.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "host/base/json_number.h"
#include "host/mts/mts_run.h"
#include "host/mts/row_json.h"

namespace depthprec {

std::vector<Level> ladder() {
  return {{"reference", 200, 100, 12},
          {"kernel 100", 100, 100, 12},
          {"kernel 50", 50, 100, 12},
          {"kernel 25", 25, 100, 12},
          {"frames 50", 200, 50, 12},
          {"frames 25", 200, 25, 12},
          {"frames 10", 200, 10, 12},
          {"precision 2^-10", 200, 100, 10},
          {"precision 2^-8", 200, 100, 8},
          {"precision 2^-6", 200, 100, 6},
          {"precision 2^-4", 200, 100, 4},
          {"100/50/2^-8", 100, 50, 8},
          {"50/25/2^-6", 50, 25, 6},
          {"25/10/2^-4", 25, 10, 4},
          {"paper frames", 200, 100, 12, 0},
          {"worst case, 1 round", 200, 100, 12, 1},
          {"worst case, 2 rounds", 200, 100, 12, 2},
          {"worst case, 3 rounds", 200, 100, 12, 3},
          {"worst case, 4 rounds", 200, 100, 12, 4}};
}

std::string sampling_of(const Level& lv) {
  if (lv.rounds < 0) return "scene";
  if (lv.rounds == 0) return "paper";
  return fmt::format("{} round{}", lv.rounds, lv.rounds == 1 ? "" : "s");
}

nlohmann::json level_record(OpenClRuntime& rt, const Scene& base, const Level& lv) {
  Scene s = base;
  s.kernel_w = s.kernel_h = s.viewport_w = s.viewport_h = lv.kernel;
  s.frames = lv.frames;
  s.rel_precision = std::ldexp(1.0, -lv.precision_log2);
  if (lv.rounds == 0) s.sampling = Sampling::paper;
  if (lv.rounds > 0) {
    s.sampling = Sampling::worst_case;
    s.worst_case.min_rounds = s.worst_case.max_rounds = lv.rounds;
  }
  const MtsRun run = run_scene(rt, s);
  uint64_t orientations = 0;  // summed over the resolved rows
  size_t resolved = 0;
  for (const auto& r : run.rows)
    if (r.verdict() == Verdict::resolved) {
      orientations += r.orientations;
      ++resolved;
    }
  nlohmann::json rows = nlohmann::json::array();
  for (const auto& r : run.rows)
    rows.push_back({{"row", row_key(r.pair, r.z)},
                    {"mts", json_number(r.mts)},
                    {"mts_bound", json_number(r.mts_bound)},
                    {"unresolvable", r.unresolvable}});
  return {{"level", lv.name},
          {"kernel", lv.kernel},
          {"frames", lv.frames},
          {"precision_log2", lv.precision_log2},
          {"rounds", lv.rounds},
          {"mean_orientations", resolved ? static_cast<double>(orientations) / resolved : 0.0},
          {"fragment_pairs", run.info.fragment_pairs},
          {"seconds", run.info.wall_seconds},
          {"rows", rows}};
}

std::vector<LevelResult> evaluate_levels(const std::vector<nlohmann::json>& records) {
  const nlohmann::json* reference = nullptr;
  for (const auto& r : records)
    if (r.at("level") == ladder().front().name) reference = &r;
  std::vector<LevelResult> results;
  if (!reference) return results;
  const auto& ref_rows = reference->at("rows");
  for (const auto& rec : records) {
    LevelResult r;
    r.level = {rec.at("level").get<std::string>(), rec.at("kernel").get<int>(),
               rec.at("frames").get<int>(), rec.at("precision_log2").get<int>(),
               rec.value("rounds", -1)};
    r.mean_orientations = rec.value("mean_orientations", 0.0);
    r.seconds = rec.value("seconds", 0.0);
    r.pairs = rec.at("fragment_pairs").get<uint64_t>();
    std::vector<double> errs, costs;
    const auto& rows = rec.at("rows");
    // What the guaranteed MTS costs against this level's sampled answer, row by row.
    for (const auto& row : rows) {
      const double m = number_from_json(row.at("mts"), "mts"),
                   b = row.contains("mts_bound")
                           ? number_from_json(row.at("mts_bound"), "mts_bound")
                           : NAN;
      if (std::isfinite(m) && m > 0 && std::isfinite(b)) costs.push_back(b / m);
    }
    std::sort(costs.begin(), costs.end());
    if (!costs.empty())
      r.median_bound_cost = costs.size() % 2
                                ? costs[costs.size() / 2]
                                : 0.5 * (costs[costs.size() / 2 - 1] + costs[costs.size() / 2]);
    for (size_t i = 0; i < rows.size() && i < ref_rows.size(); ++i) {
      const bool unres = rows[i].at("unresolvable").get<bool>(),
                 ref_unres = ref_rows[i].at("unresolvable").get<bool>();
      if (unres != ref_unres) {
        ++r.verdict_changes;
        r.changed.push_back(rows[i].at("row").get<std::string>());
      } else if (!unres) {
        const double mts = number_from_json(rows[i].at("mts"), "mts"),
                     ref = number_from_json(ref_rows[i].at("mts"), "mts");
        errs.push_back(std::abs(mts - ref) / ref);
      }
    }
    std::sort(errs.begin(), errs.end());
    if (!errs.empty()) {
      r.median_err = errs.size() % 2 ? errs[errs.size() / 2]
                                     : 0.5 * (errs[errs.size() / 2 - 1] + errs[errs.size() / 2]);
      r.max_err = errs.back();
    }
    results.push_back(r);
  }
  // Pareto front by work (fragment pairs: deterministic, proportional to time) against accuracy
  // (verdict changes first, then the largest relative error): keep the levels no other level
  // beats on both.
  for (auto& a : results) {
    a.pareto = true;
    for (const auto& b : results) {
      const bool cheaper_or_same = b.pairs <= a.pairs;
      const bool better_or_same = std::make_pair(b.verdict_changes, b.max_err) <=
                                  std::make_pair(a.verdict_changes, a.max_err);
      const bool strictly = b.pairs < a.pairs || std::make_pair(b.verdict_changes, b.max_err) <
                                                     std::make_pair(a.verdict_changes, a.max_err);
      if (&a != &b && cheaper_or_same && better_or_same && strictly) a.pareto = false;
    }
  }
  return results;
}

}  // namespace depthprec
