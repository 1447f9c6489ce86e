// pipelines: how much the host's own choices move the MTS -- matrices built in binary32 or
// binary64 (matrix_precision) and P and MV applied separately or premultiplied (compose) -- per
// technique, against the scene's pipeline. The literature says reversed depth makes these
// differences vanish; this shows whether it does.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>

#include "host/analysis/pipelines.h"
#include "host/base/errors.h"
#include "host/base/json_number.h"
#include "host/cli/commands.h"
#include "host/cli/record_batch.h"
#include "host/cli/scene_options.h"
#include "host/mts/mts_run.h"
#include "host/output/implementations.h"
#include "host/output/output_guard.h"
#include "host/output/report.h"
#include "host/output/text_table.h"

namespace depthprec::cli {

namespace {

struct PipelinesOptions {
  SceneOptions scene;
  OutputOptions out;
  BatchOptions batch;
  bool list = false;
};

}  // namespace

namespace {

// How one pipeline variant's MTS compare with the first variant's over a pair's distances.
struct VariantSummary {
  std::string variant;
  double median = 0, farthest = 0;  // of the ratios where both resolve; NaN when none do
  int verdict_changes = 0;
};

std::vector<VariantSummary> summarise_variants(const nlohmann::json& rec) {
  std::vector<VariantSummary> out;
  const auto& base = rec.at("variants").at(kPipelineVariants[0].name);
  for (const PipelineVariant& v : kPipelineVariants) {
    if (v.precision == MatrixPrecision::single && v.compose == Compose::separate) continue;
    const auto& other = rec.at("variants").at(v.name);
    VariantSummary sum{v.name};
    std::vector<double> ratios;
    for (size_t i = 0; i < base.size(); ++i) {
      const double a = number_from_json(base[i], "mts"), b = number_from_json(other[i], "mts");
      if (std::isinf(a) != std::isinf(b))
        ++sum.verdict_changes;
      else if (!std::isinf(a))
        ratios.push_back(b / a);
    }
    std::sort(ratios.begin(), ratios.end());
    sum.median = sum.farthest = std::numeric_limits<double>::quiet_NaN();
    if (!ratios.empty()) {
      sum.median = ratios[ratios.size() / 2];
      sum.farthest = 1;  // the ratio farthest from 1, either way
      for (double r : ratios)
        if (std::abs(std::log(r)) > std::abs(std::log(sum.farthest))) sum.farthest = r;
    }
    out.push_back(sum);
  }
  return out;
}

}  // namespace

std::string render_pipelines_output(const nlohmann::json& header,
                                    const std::vector<nlohmann::json>& records,
                                    const OutputOptions& out) {
  if (out.format_out == "json") {
    nlohmann::json summary = nlohmann::json::array();
    for (const auto& rec : records)
      for (const auto& v : summarise_variants(rec))
        summary.push_back({{"pair", rec.at("pair")},
                           {"variant", v.variant},
                           {"median_ratio", json_number(v.median)},
                           {"farthest_ratio", json_number(v.farthest)},
                           {"verdict_changes", v.verdict_changes}});
    return records_json(header, records, !out.no_timing, {{"summary", summary}});
  }
  const bool csv = out.format_out == "csv";
  std::vector<Column> cols = {{"pair", true}};
  for (const PipelineVariant& v : kPipelineVariants)
    if (v.precision != MatrixPrecision::single || v.compose != Compose::separate) {
      cols.push_back({fmt::format("{} median", v.name)});
      cols.push_back({fmt::format("{} farthest", v.name)});
      cols.push_back({fmt::format("{} verdicts", v.name)});
    }
  Cells cells;
  for (const auto& rec : records) {
    std::vector<std::string> row = {rec.at("pair").get<std::string>()};
    for (const auto& v : summarise_variants(rec)) {
      const auto num = [csv, &out](double x) {
        return std::isnan(x) ? (csv ? "" : "-") : number_cell(x, out.format_out, "{:.4g}");
      };
      row.push_back(num(v.median));
      row.push_back(num(v.farthest));
      row.push_back(std::to_string(v.verdict_changes));
    }
    cells.push_back(row);
  }
  return captioned(
      fmt::format("MTS under other host pipelines, relative to {} (matrix_precision/compose) on "
                  "scene {}: median ratio, the ratio farthest from 1 (either way) over the "
                  "distances where both resolve, and verdicts = distances whose "
                  "resolvable/unresolvable verdict changed",
                  kPipelineVariants[0].name, header.value("scene_name", std::string("?"))),
      cols, cells, out.format_out);
}

namespace {

void run_pipelines(const PipelinesOptions& o, const GlobalOptions& g) {
  check_output_spares_inputs("-o", o.out.output, {{"the scene file", o.scene.scene_file}});
  if (o.list) {  // what the profiles and bound models are, no measurement
    if (o.scene.any())
      throw Error(ExitCode::usage,
                  "pipelines --list takes no scene options: it lists, it measures "
                  "nothing");
    check_writable(o.out.output);
    write_output(o.out.output,
                 for_terminal(implementations_output(o.out.format_out), o.out.format_out));
    return;
  }
  const Scene scene = o.scene.load();
  check_writable(o.out.output);
  run_record_batch(
      "pipelines", o.out, o.batch, g,
      [&scene](OpenClRuntime& rt, nlohmann::json& header) {
        header["scene"] = scene.json;
        header["scene_name"] = scene.name;
        return pair_units(
            scene, [&rt, &scene](const EvalPair& pair) { return pair_record(rt, scene, pair); });
      },
      render_pipelines_output);
}

}  // namespace

void add_pipelines_command(CLI::App& app, GlobalOptions& global) {
  auto o = std::make_shared<PipelinesOptions>();
  auto* cmd = app.add_subcommand(
      "pipelines",
      "The host's pipeline choices against MTS: matrices built in binary32 or binary64\n"
      "(matrix_precision) and P, MV applied separately or premultiplied (compose), each pair's\n"
      "MTS at every distance relative to float/separate. Four full runs of the scene's pairs.\n"
      "Examples:\n"
      "  depthprec pipelines -t standard,reversed -f float32 --depth-range zero_to_one\n"
      "  depthprec pipelines --kernel 100x100 --frames 50 --format-out markdown\n"
      "  depthprec pipelines --list --format-out markdown");
  o->scene.add_to(*cmd, true);
  o->out.add_to(*cmd);
  o->batch.add_to(*cmd, "pairs (k in scene order)");
  cmd->add_flag("--list", o->list,
                "List the implementation profiles and the bound models, the API envelopes "
                "among them (what each allows, and its source), and exit");
  cmd->callback([o, &global]() { run_pipelines(*o, global); });
}

}  // namespace depthprec::cli
