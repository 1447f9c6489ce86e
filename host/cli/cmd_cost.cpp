// cost: per technique and format, what its depth path costs in the kernel next to the precision
// it buys, and the costs a GPU would pay that an emulator does not measure.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

#include "host/analysis/cost.h"
#include "host/base/errors.h"
#include "host/base/json_number.h"
#include "host/base/version.h"
#include "host/cli/commands.h"
#include "host/cli/record_batch.h"
#include "host/cli/scene_options.h"
#include "host/lj/lj_metric.h"
#include "host/mts/mts_run.h"
#include "host/mts/mts_timing.h"
#include "host/output/gnuplot.h"
#include "host/output/output_guard.h"
#include "host/output/plots.h"
#include "host/output/report.h"
#include "host/output/text_table.h"

namespace depthprec::cli {

namespace {

struct CostOptions {
  SceneOptions scene;
  OutputOptions out;
  std::string plot;
  BatchOptions batch;
};

void run_cost(const CostOptions& o, const GlobalOptions& g) {
  check_output_spares_inputs("-o", o.out.output, {{"the scene file", o.scene.scene_file}});
  check_output_spares_inputs("--plot", o.plot, {{"the scene file", o.scene.scene_file}});
  const Scene scene = o.scene.load();
  check_writable(o.out.output);
  check_plot_output(o.plot);
  if (!o.plot.empty() && o.out.no_timing)
    throw Error(ExitCode::usage, "cost: --plot needs the timing pass (drop --no-timing)");
  const bool timing = !o.out.no_timing;
  const auto records = run_record_batch(
      "cost", o.out, o.batch, g,
      [&scene, timing](OpenClRuntime& rt, nlohmann::json& header) {
        header["scene"] = scene.json;
        header["scene_name"] = scene.name;
        return pair_units(scene, [&rt, &scene, timing](const EvalPair& pair) {
          return cost_record(rt, scene, pair, timing);
        });
      },
      render_cost_output);
  if (o.plot.empty()) return;
  std::vector<CostPoint> points;
  for (const auto& r : records)
    if (r.contains("ns_per_fragment_pair"))
      points.push_back(
          {pair_label(r), r["ns_per_fragment_pair"].get<double>(),
           number_from_json(r["median_mts_over_vertex_bound"], "median_mts_over_vertex_bound")});
  plot_cost(points, o.plot);
}

// inf in the lj ae column is LJ's own answer, not a failure: say what it means.
std::string lj_note(const std::vector<nlohmann::json>& records, const std::string& format_out) {
  if (format_out != "text") return "";
  for (const auto& r : records)
    if (r.contains("lj_ae") && !std::isfinite(number_from_json(r["lj_ae"], "lj_ae")))
      return "lj ae inf: the buffer has no finite average error over [near, far]: past its Z pole "
             "the stored code no longer separates distances (depthprec lj says for how many "
             "samples)\n";
  return "";
}

}  // namespace

std::string render_cost_output(const nlohmann::json& header,
                               const std::vector<nlohmann::json>& records,
                               const OutputOptions& out) {
  const bool timing = !out.no_timing;
  if (out.format_out == "json") return records_json(header, records, timing);
  Cells cells;
  for (const auto& r : records) {
    std::vector<std::string> row = {r["technique"].get<std::string>(),
                                    r["format"].get<std::string>(),
                                    r["depth_range"].get<std::string>()};
    const std::string none = out.format_out == "csv" ? "" : "-";
    if (timing)
      row.push_back(
          r.contains("ns_per_fragment_pair")
              ? number_cell(r["ns_per_fragment_pair"].get<double>(), out.format_out, "{:.2f}")
              : none);
    row.push_back(number_cell(
        number_from_json(r["median_mts_over_vertex_bound"], "median_mts_over_vertex_bound"),
        out.format_out));
    row.push_back(std::to_string(r["unresolvable_distances"].get<int>()));
    row.push_back(r.contains("lj_ae")
                      ? number_cell(number_from_json(r["lj_ae"], "lj_ae"), out.format_out)
                      : none);
    row.push_back(r["structural_cost"].get<std::string>());
    cells.push_back(row);
  }
  std::vector<Column> cols = {{"technique", true}, {"format", true}, {"depth_range", true}};
  if (timing) cols.push_back({"ns/pair"});
  for (const char* c : {"median mts/vb", "unresolvable", "lj ae"}) cols.push_back({c});
  cols.push_back({"structural cost on a GPU", true});
  return captioned(
             fmt::format(
                 "Cost and precision per technique (scene {}): {}median MTS over the vertex bound "
                 "across the scene's distances, Lapidous-Jiao ae where the technique is one of "
                 "its buffers",
                 header.value("scene_name", std::string("?")),
                 timing ? "ns per fragment pair of the kernel's depth path (timing pass: one "
                          "clean probe 2 % above each resolved distance's MTS, where every pixel "
                          "is evaluated), "
                        : ""),
             cols, cells, out.format_out) +
         lj_note(records, out.format_out);
}

void add_cost_command(CLI::App& app, GlobalOptions& global) {
  auto o = std::make_shared<CostOptions>();
  auto* cmd = app.add_subcommand(
      "cost",
      "Per technique x format: the kernel's cost per fragment pair of its depth path (a dedicated\n"
      "timing pass), the precision it buys (median MTS / vertex bound over the scene's distances,\n"
      "and the Lapidous-Jiao error where the technique is one of LJ's buffers), and the "
      "structural\n"
      "costs a GPU pays (fragment-depth writes disable early depth test; layering costs a pass "
      "per\n"
      "layer). CSV/JSON output is the error-vs-cost plot data.\n"
      "Examples:\n"
      "  depthprec cost -t standard,reversed,log_fragment,linear -f float32,unorm24 --distances "
      "2,1024,1e6\n"
      "  depthprec cost --format-out csv -o cost.csv");
  o->scene.add_to(*cmd, true);
  o->out.add_to(*cmd);
  cmd->add_option("--plot", o->plot,
                  "Also plot precision against cost (gnuplot), FILE.png or FILE.svg");
  o->batch.add_to(*cmd, "techniques x formats (k in scene order)");
  cmd->callback([o, &global]() { run_cost(*o, global); });
}

}  // namespace depthprec::cli
