// plot: MTS against distance, log-log, one line per (technique, format, depth range), the
// binary32 vertex-precision bound shaded beneath (as Gilg et al.'s fig. 6), rendered by gnuplot
// from the JSON output of `mts`, `table` or `merge`.
#include <fmt/format.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>

#include "host/base/errors.h"
#include "host/cli/commands.h"
#include "host/mts/row_json.h"
#include "host/output/gnuplot.h"
#include "host/output/output_guard.h"
#include "host/output/plots.h"
#include "host/output/read_output.h"

namespace depthprec::cli {

namespace {

struct PlotOptions {
  std::string input;
  std::string output = "mts.png";
  std::string title;
  bool output_named = false;  // -o given: it may replace a file; the default name never does
};

void run_plot(const PlotOptions& o) {
  check_default_output_is_new("plot", o.output, o.output_named);
  check_output_spares_inputs("-o", o.output, {{"the file to plot", o.input}});
  const auto j = read_json_output(o.input, "plot", "input");
  if (j.value("kind", "") == "profiles" &&
      j.contains("records")) {  // `mts --profiles` / `table --profiles`: the band between them
    refuse_shard(j, o.input, "plot");
    check_plot_output(o.output);
    const std::string scene = j.value("scene_name", "?");
    plot_profiles(j["records"].get<std::vector<nlohmann::json>>(),
                  j.at("profiles").get<std::vector<std::string>>(),
                  o.title.empty() ? fmt::format("MTS by profile, scene {}", scene) : o.title,
                  o.output);
    return;
  }
  check_rows_output(j, o.input, "plot", "plot draws one from its records, which this file lacks");
  check_plot_output(o.output);
  std::vector<MtsRow> rows;
  for (const auto& rj : j["rows"]) rows.push_back(row_from_json(rj));
  const std::string scene =
      j.contains("scene") && j["scene"].is_object() ? j["scene"].value("name", "") : "";
  plot_mts(rows,
           o.title.empty() ? fmt::format("MTS by distance, scene {}", scene.empty() ? "?" : scene)
                           : o.title,
           o.output);
}

}  // namespace

void add_plot_command(CLI::App& app) {
  auto o = std::make_shared<PlotOptions>();
  auto* cmd = app.add_subcommand(
      "plot",
      "Plot MTS against distance (log-log, one line per technique/format/depth range, the\n"
      "binary32 vertex-precision bound shaded, as Gilg et al.'s fig. 6) with gnuplot, from the\n"
      "JSON output of a whole run of mts, table, render or merge (one shard alone is refused:\n"
      "merge the shards first); for `--profiles` outputs, a line per profile and the band\n"
      "between them. Without -o it writes mts.png, and only where there is no such file.\n"
      "Example:\n"
      "  depthprec table --format-out json -o table.json && depthprec plot table.json -o "
      "table.png");
  cmd->add_option("input", o->input, "JSON output of mts, table, render or merge")->required();
  CLI::Option* output =
      cmd->add_option("-o,--output", o->output,
                      "Image to write: .png or .svg, replaced if it exists (without -o: mts.png, "
                      "written only where there is no such file)")
          ->capture_default_str();
  cmd->add_option("--title", o->title, "Plot title");
  cmd->callback([o, output]() {
    o->output_named = output->count() > 0;
    run_plot(*o);
  });
}

}  // namespace depthprec::cli
