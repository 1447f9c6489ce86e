#include "host/analysis/compare.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>

#include "host/base/errors.h"
#include "host/base/json_number.h"
#include "host/mts/row_json.h"

namespace depthprec {

using nlohmann::json;

json compare_record(const MtsRow& emulated, const MtsRow& rendered) {
  json j = emulated.pair.fields();
  j.update({{"z", emulated.z},
            {"emulated_mts", json_number(emulated.mts)},
            {"rendered_mts", json_number(rendered.mts)},
            {"emulated_verdict", to_string(emulated.verdict())},
            {"rendered_verdict", to_string(rendered.verdict())},
            {"emulated", row_to_json(emulated, true)},
            {"rendered", row_to_json(rendered, true)}});
  if (emulated.verdict() == Verdict::resolved && rendered.verdict() == Verdict::resolved)
    j["ratio"] = emulated.mts / rendered.mts;
  return j;
}

void check_compare_record(const json& r) {
  const auto fail = [&r](const std::string& what) {
    const std::string name = r.is_object() && r.contains("key") && r["key"].is_string()
                                 ? r["key"].get<std::string>()
                                 : r.dump().substr(0, 80) + "...";
    throw InputError(fmt::format("compare record {}: {}", name, what));
  };
  if (!r.is_object()) fail("not a JSON object");
  for (const char* k :
       {"technique", "format", "depth_range", "emulated_verdict", "rendered_verdict"})
    if (!r.contains(k) || !r[k].is_string())
      fail(fmt::format("'{}' is missing or not a string", k));
  if (!r.contains("z") || !r["z"].is_number()) fail("'z' is missing or not a number");
  for (const char* k : {"emulated_mts", "rendered_mts"}) {
    if (!r.contains(k)) fail(fmt::format("'{}' is missing", k));
    (void)number_from_json(r[k], k);
  }
  if (r.contains("ratio") && !r["ratio"].is_number()) fail("'ratio' is not a number");
  for (const char* side : {"emulated", "rendered"})
    if (!r.contains(side) || !r[side].is_object())
      fail(fmt::format("'{}' is missing or not a row object", side));
}

CompareSummary summarise(const std::vector<json>& records, double rel_precision) {
  for (const auto& r : records) check_compare_record(r);
  CompareSummary s;
  std::vector<double> ratios;
  double worst_log = -1;
  for (const auto& r : records) {
    ++s.rows;
    if (r.at("emulated_verdict") != r.at("rendered_verdict")) ++s.verdicts_differ;
    if (!r.contains("ratio")) continue;
    const double ratio = r.at("ratio").get<double>();
    ratios.push_back(ratio);
    ++s.both_resolved;
    const double spread = std::max(ratio, 1 / ratio);
    if (spread <= 1.1) ++s.within_1_1;
    if (spread <= 2) ++s.within_2;
    if (ratio < 1 - 2 * rel_precision) ++s.optimistic;
    if (ratio > 1 + 2 * rel_precision) ++s.pessimistic;
    if (std::abs(std::log(ratio)) > worst_log) {
      worst_log = std::abs(std::log(ratio));
      s.worst_ratio = ratio;
      s.worst_key = fmt::format("{} z={}", pair_label(r), r.at("z").get<double>());
    }
  }
  if (ratios.empty()) {
    s.median_ratio = NAN;
  } else {
    std::sort(ratios.begin(), ratios.end());
    const size_t n = ratios.size();
    s.median_ratio = n % 2 ? ratios[n / 2] : 0.5 * (ratios[n / 2 - 1] + ratios[n / 2]);
  }
  return s;
}

json to_json(const CompareSummary& s) {
  return {{"rows", s.rows},
          {"both_resolved", s.both_resolved},
          {"within_1_1", s.within_1_1},
          {"within_2", s.within_2},
          {"optimistic", s.optimistic},
          {"pessimistic", s.pessimistic},
          {"verdicts_differ", s.verdicts_differ},
          {"median_ratio", json_number(s.median_ratio)},
          {"worst_ratio", json_number(s.worst_ratio)},
          {"worst", s.worst_key}};
}

std::string summary_line(const CompareSummary& s) {
  if (s.both_resolved == 0)
    return fmt::format("{} rows, none resolved by both; verdicts differ on {}", s.rows,
                       s.verdicts_differ);
  return fmt::format(
      "{} rows, {} resolved by both: {} within 1.1x, {} within 2x; median emulated/rendered "
      "{:.3g}, "
      "worst {:.3g} ({}); emulation optimistic on {}, pessimistic on {}; verdicts differ on {}",
      s.rows, s.both_resolved, s.within_1_1, s.within_2, s.median_ratio, s.worst_ratio, s.worst_key,
      s.optimistic, s.pessimistic, s.verdicts_differ);
}

std::vector<std::pair<std::string, CompareSummary>> summarise_by_pair(
    const std::vector<json>& records, double rel_precision) {
  for (const auto& r : records) check_compare_record(r);
  std::vector<std::string> order;
  std::map<std::string, std::vector<json>> groups;
  for (const auto& r : records) {
    const std::string l = pair_label(r);
    if (!groups.count(l)) order.push_back(l);
    groups[l].push_back(r);
  }
  std::vector<std::pair<std::string, CompareSummary>> out;
  for (const auto& l : order) out.emplace_back(l, summarise(groups[l], rel_precision));
  return out;
}

}  // namespace depthprec
