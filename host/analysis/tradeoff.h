// tradeoff's computation: the ladder of reduced budgets (kernel pixels, frames, bisection
// precision), one record per level, and each level's error against the full-budget reference
// with the Pareto front of work against error.
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "host/model/scene.h"
#include "host/runtime/opencl_runtime.h"

namespace depthprec {

struct Level {
  std::string name;
  int kernel;
  int frames;
  int precision_log2;  // rel_precision = 2^-precision_log2
};

// The ladder of the issue: each budget alone, then combined; the first is the reference.
std::vector<Level> ladder();

struct LevelResult {
  Level level;
  double seconds = 0;
  uint64_t pairs = 0;
  double median_err = 0, max_err = 0;
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
