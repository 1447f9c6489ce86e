// tradeoff's computation: the ladder of reduced budgets (kernel pixels, frames, bisection
// precision), one record per level, and each level's error against the full-budget reference
// with the Pareto front of work against error.
#pragma once

#include <cstdint>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "host/model/scene.h"

namespace depthprec {

class OpenClRuntime;  // host/runtime/opencl_runtime.h

struct Level {
  std::string name;
  int kernel;
  int frames;
  int precision_log2;  // rel_precision = 2^-precision_log2
  // How the orientations are sampled: the scene's own sampling (-1), the paper's frames alone
  // (0), or the worst case with exactly this many rounds (docs/mts.md, "The worst case").
  int rounds = -1;
};
// "scene", "paper" or "N rounds": the sampling column of a level.
std::string sampling_of(const Level& lv);

// The ladder: each budget alone, then combined, then the sampling of orientations from the
// paper's frames to four rounds of the worst case; the first is the reference.
std::vector<Level> ladder();

struct LevelResult {
  Level level;
  double seconds = 0;
  uint64_t pairs = 0;
  double mean_orientations = 0;  // per resolved row
  double median_err = 0, max_err = 0;
  // The median of mts_bound / mts over the level's rows that have both: what the guaranteed
  // answer costs against the sampled one (NaN when none has).
  double median_bound_cost = std::numeric_limits<double>::quiet_NaN();
  int verdict_changes = 0;
  std::vector<std::string> changed;  // "technique/format/range z" of each verdict change
  bool pareto = false;
};

// One record per level: its work, time and every row's MTS (errors are derived when rendering,
// against the reference level's record).
nlohmann::json level_record(OpenClRuntime& rt, const Scene& base, const Level& lv);

// Errors against the reference record and the Pareto front; empty when the reference level is
// not among the records (a shard without it).
std::vector<LevelResult> evaluate_levels(const std::vector<nlohmann::json>& records);

}  // namespace depthprec
