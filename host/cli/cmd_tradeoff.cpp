// tradeoff: how the evaluator's own answer degrades as it spends less (kernel pixels, frames,
// bisection precision), against its full-fidelity answer.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

#include "host/analysis/tradeoff.h"
#include "host/base/errors.h"
#include "host/base/json_number.h"
#include "host/base/version.h"
#include "host/batch/batch.h"
#include "host/cli/commands.h"
#include "host/cli/record_batch.h"
#include "host/cli/scene_options.h"
#include "host/mts/mts_run.h"
#include "host/mts/row_json.h"
#include "host/output/gnuplot.h"
#include "host/output/output_guard.h"
#include "host/output/plots.h"
#include "host/output/report.h"
#include "host/output/text_table.h"

namespace depthprec::cli {

namespace {

struct TradeoffOptions {
  SceneOptions scene;
  OutputOptions out;
  std::string plot;
  BatchOptions batch;
};

void run_tradeoff(const TradeoffOptions& o, const GlobalOptions& g) {
  check_output_spares_inputs("-o", o.out.output, {{"the scene file", o.scene.scene_file}});
  check_output_spares_inputs("--plot", o.plot, {{"the scene file", o.scene.scene_file}});
  const Scene base = o.scene.load();
  check_writable(o.out.output);
  check_plot_output(o.plot);
  if (!Shard::parse(o.batch.shard).holds(0) && o.out.format_out != "json")
    throw Error(ExitCode::usage,
                "tradeoff --shard: this shard does not run the reference level the errors are "
                "relative to; write shards with --format-out json and render them with merge");
  const auto records = run_record_batch(
      "tradeoff", o.out, o.batch, g,
      [&base](OpenClRuntime& rt, nlohmann::json& header) {
        header["scene"] = base.json;
        header["scene_name"] = base.name;
        header["pairs"] = base.evaluate.size();
        header["distances"] = base.distances.size();
        std::vector<BatchUnit> units;
        for (const Level& lv : ladder())
          units.push_back({lv.name, [&rt, &base, lv] { return level_record(rt, base, lv); }});
        return units;
      },
      render_tradeoff_output);
  if (!o.plot.empty()) plot_tradeoff(evaluate_levels(records), o.plot);
}

}  // namespace

std::string render_tradeoff_output(const nlohmann::json& header,
                                   const std::vector<nlohmann::json>& records,
                                   const OutputOptions& out) {
  const bool timing = !out.no_timing;
  const std::vector<LevelResult> results = evaluate_levels(records);
  if (out.format_out == "json") {
    nlohmann::json levels = nlohmann::json::array();
    for (const auto& r : results) {
      // null where no row has both a sampled and a guaranteed MTS
      const nlohmann::json cost = std::isnan(r.median_bound_cost)
                                      ? nlohmann::json(nullptr)
                                      : nlohmann::json(r.median_bound_cost);
      levels.push_back({{"level", r.level.name},
                        {"kernel", r.level.kernel},
                        {"frames", r.level.frames},
                        {"rel_precision", std::ldexp(1.0, -r.level.precision_log2)},
                        {"sampling", sampling_of(r.level)},
                        {"mean_orientations", r.mean_orientations},
                        {"fragment_pairs", r.pairs},
                        {"seconds", r.seconds},
                        {"median_rel_err", r.median_err},
                        {"max_rel_err", r.max_err},
                        {"verdict_changes", r.changed},
                        {"median_bound_over_mts", cost},
                        {"pareto", r.pareto}});
    }
    return records_json(header, records, timing, {{"levels", levels}});
  }
  std::vector<Column> cols = {{"level", true},   {"kernel"},         {"frames"},
                              {"rel_precision"}, {"sampling", true}, {"orientations"},
                              {"fragment_pairs"}};
  if (timing) cols.push_back({"seconds"});
  for (const char* c : {"median_rel_err", "max_rel_err", "verdict_changes", "bound/mts"})
    cols.push_back({c});
  cols.push_back({"pareto", true});
  const bool csv = out.format_out == "csv";
  Cells cells;
  for (const auto& r : results) {
    std::vector<std::string> row = {r.level.name,
                                    fmt::format("{}x{}", r.level.kernel, r.level.kernel),
                                    std::to_string(r.level.frames),
                                    csv ? exact(std::ldexp(1.0, -r.level.precision_log2))
                                        : fmt::format("2^-{}", r.level.precision_log2),
                                    sampling_of(r.level),
                                    number_cell(r.mean_orientations, out.format_out, "{:.0f}"),
                                    std::to_string(r.pairs)};
    if (timing) row.push_back(number_cell(r.seconds, out.format_out, "{:.2f}"));
    row.push_back(number_cell(r.median_err, out.format_out, "{:.3g}"));
    row.push_back(number_cell(r.max_err, out.format_out, "{:.3g}"));
    row.push_back(std::to_string(r.verdict_changes));
    row.push_back(std::isnan(r.median_bound_cost)
                      ? (csv ? "" : "-")
                      : number_cell(r.median_bound_cost, out.format_out, "{:.3g}"));
    row.push_back(r.pareto ? "yes" : "");
    cells.push_back(row);
  }
  std::string changed;
  for (const auto& r : results)
    for (const auto& c : r.changed)
      changed += fmt::format("{}: verdict changed at {}\n", r.level.name, c);
  return captioned(fmt::format("Fidelity trade-off on scene {} ({} pairs x {} distances); errors "
                               "relative to the reference level; bound/mts: the median of "
                               "mts_bound / mts, what the guaranteed answer costs against the "
                               "level's sampled one; Pareto front by fragment pairs "
                               "vs (verdict changes, max error)",
                               header.value("scene_name", std::string("?")),
                               header.value("pairs", 0), header.value("distances", 0)),
                   cols, cells, out.format_out) +
         (changed.empty() || csv ? "" : "\n" + changed);
}

void add_tradeoff_command(CLI::App& app, GlobalOptions& global) {
  auto o = std::make_shared<TradeoffOptions>();
  auto* cmd = app.add_subcommand(
      "tradeoff",
      "How the MTS answer degrades as the evaluator spends less: kernel 25^2..200^2, frames\n"
      "10..100, rel_precision 2^-4..2^-12, alone and combined, then the orientations sampled\n"
      "(the paper's frames alone, then the worst case with 1 to 4 rounds, each doubling them),\n"
      "each against the reference level (200^2, 100 frames, 2^-12, the scene's sampling):\n"
      "median and max relative MTS error, distances whose resolvable/unresolvable verdict\n"
      "changed, orientations per row, work and time, what the guaranteed MTS costs against\n"
      "the sampled one, and the Pareto front.\n"
      "Nineteen full runs of the scene's pairs: choose few pairs and distances.\n"
      "Examples:\n"
      "  depthprec tradeoff -t reversed -f float32 --depth-range zero_to_one --distances "
      "2,1024,1e6\n"
      "  depthprec tradeoff -t standard,linear -f unorm24 --format-out json -o tradeoff.json");
  o->scene.add_to(*cmd, true);
  o->out.add_to(*cmd);
  cmd->add_option("--plot", o->plot,
                  "Also plot error against cost (gnuplot), FILE.png or FILE.svg");
  o->batch.add_to(*cmd, "ladder levels (k in the order above)");
  cmd->callback([o, &global]() { run_tradeoff(*o, global); });
}

}  // namespace depthprec::cli
