// Emulated against rendered, row by row: the two MTS of a (pair, z), their ratio and verdicts, and
// what a set of such records says (how many agree within 1.1x and 2x, the worst ratio, on how
// many rows the emulation is optimistic), for `depthprec compare` and docs/validation.md.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "host/mts/mts_row.h"

namespace depthprec {

// ratio = emulated MTS / rendered MTS when both are resolved (below 1: the emulation calls a
// separation safe that fights on the rasterizer), absent otherwise. The full rows ride along
// under "emulated" and "rendered", so any output can be re-rendered from the record.
nlohmann::json compare_record(const MtsRow& emulated, const MtsRow& rendered);

// Checks a record read back from a file (a journal, a shard to merge): every field the
// summaries and outputs read, with its type. Throws InputError naming the field.
void check_compare_record(const nlohmann::json& record);

struct CompareSummary {
  size_t rows = 0;
  size_t both_resolved = 0;
  size_t within_1_1 = 0, within_2 = 0;  // of both_resolved: max(r, 1/r) <= 1.1, <= 2
  // Ratios below (above) 1 by more than the bisection's precision twice over: the emulation
  // needs a smaller (larger) separation than the rasterizer.
  size_t optimistic = 0, pessimistic = 0;
  size_t verdicts_differ = 0;
  double median_ratio = 0;  // of both_resolved (NaN when none)
  double worst_ratio = 0;   // farthest from 1 (either way), with its row's key
  std::string worst_key;
};

// rel_precision: the scene's bisection precision.
CompareSummary summarise(const std::vector<nlohmann::json>& records, double rel_precision);
nlohmann::json to_json(const CompareSummary& s);
std::string summary_line(const CompareSummary& s);

// Records grouped by pair (technique/format/depth_range), in first-seen order, with each group's
// summary: the per-pair lines of docs/validation.md.
std::vector<std::pair<std::string, CompareSummary>> summarise_by_pair(
    const std::vector<nlohmann::json>& records, double rel_precision);

}  // namespace depthprec
