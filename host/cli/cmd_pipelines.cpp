// pipelines: how much the host's own choices move the MTS -- matrices built in binary32 or
// binary64 (matrix_precision) and P and MV applied separately or premultiplied (compose) -- per
// technique, against the scene's pipeline. The literature says reversed depth makes these
// differences vanish; this shows whether it does.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

#include "host/analysis/pipelines.h"
#include "host/base/errors.h"
#include "host/base/json_number.h"
#include "host/cli/commands.h"
#include "host/cli/record_batch.h"
#include "host/cli/scene_options.h"
#include "host/mts/mts_run.h"
#include "host/output/report.h"
#include "host/output/text_table.h"

namespace depthprec::cli {

namespace {

struct PipelinesOptions {
  SceneOptions scene;
  OutputOptions out;
  BatchOptions batch;
};

}  // namespace

std::string render_pipelines_output(const nlohmann::json& header,
                                    const std::vector<nlohmann::json>& records,
                                    const OutputOptions& out) {
  if (out.format_out == "json") return records_json(header, records, !out.no_timing);
  std::vector<Column> cols = {{"pair", true}};
  for (const PipelineVariant& v : kPipelineVariants)
    if (v.precision != MatrixPrecision::single || v.compose != Compose::separate) {
      cols.push_back({fmt::format("{} median", v.name)});
      cols.push_back({fmt::format("{} max", v.name)});
      cols.push_back({fmt::format("{} verdicts", v.name)});
    }
  Cells cells;
  for (const auto& rec : records) {
    std::vector<std::string> row = {rec.at("pair").get<std::string>()};
    const auto& base = rec.at("variants").at(kPipelineVariants[0].name);
    for (const PipelineVariant& v : kPipelineVariants) {
      if (v.precision == MatrixPrecision::single && v.compose == Compose::separate) continue;
      const auto& other = rec.at("variants").at(v.name);
      std::vector<double> ratios;
      int changes = 0;
      for (size_t i = 0; i < base.size(); ++i) {
        const double a = number_from_json(base[i], "mts"), b = number_from_json(other[i], "mts");
        if (std::isinf(a) != std::isinf(b))
          ++changes;
        else if (!std::isinf(a))
          ratios.push_back(b / a);
      }
      std::sort(ratios.begin(), ratios.end());
      // the ratio farthest from 1, either way
      double worst = 1;
      for (double r : ratios)
        if (std::abs(std::log(r)) > std::abs(std::log(worst))) worst = r;
      row.push_back(ratios.empty() ? "-" : fmt::format("{:.4g}", ratios[ratios.size() / 2]));
      row.push_back(ratios.empty() ? "-" : fmt::format("{:.4g}", worst));
      row.push_back(std::to_string(changes));
    }
    cells.push_back(row);
  }
  return fmt::format(
             "MTS under other host pipelines, relative to {} (matrix_precision/compose) on scene "
             "{}: "
             "median and farthest-from-1 ratio over the distances; verdicts = distances whose "
             "resolvable/unresolvable verdict changed\n\n",
             kPipelineVariants[0].name, header.value("scene_name", std::string("?"))) +
         render_cells(cols, cells, out.format_out);
}

namespace {

void run_pipelines(const PipelinesOptions& o, const GlobalOptions& g) {
  const Scene scene = o.scene.load();
  check_writable(o.out.output);
  run_record_batch(
      "pipelines", o.out, o.batch, g,
      [&scene](OpenClRuntime& rt, nlohmann::json& header) {
        header["scene"] = scene.json;
        header["scene_name"] = scene.name;
        std::vector<BatchUnit> units;
        for (const EvalPair& pair : scene.evaluate)
          units.push_back(
              {pair.label(), [&rt, &scene, pair] { return pair_record(rt, scene, pair); }});
        return units;
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
      "  depthprec pipelines --kernel 100x100 --frames 50 --format-out markdown");
  o->scene.add_to(*cmd, true);
  o->out.add_to(*cmd);
  o->batch.add_to(*cmd, "pairs (k in scene order)");
  cmd->callback([o, &global]() { run_pipelines(*o, global); });
}

}  // namespace depthprec::cli
