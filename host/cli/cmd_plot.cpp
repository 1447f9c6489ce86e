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
#include "host/output/gnuplot.h"
#include "host/output/row_json.h"

namespace depthprec::cli {

namespace {

struct PlotOptions {
  std::string input;
  std::string output = "mts.png";
  std::string title;
};

void run_plot(const PlotOptions& o) {
  std::ifstream in(o.input);
  if (!in) throw InputError(fmt::format("plot: cannot read '{}'", o.input));
  const auto j = nlohmann::json::parse(in, nullptr, false);
  if (j.is_discarded() || !j.is_object() || !j.contains("rows"))
    throw InputError(fmt::format(
        "plot: '{}' is not a JSON output of mts, table or merge (--format-out json)", o.input));
  check_plot_output(o.output);
  const std::string terminal = gnuplot_terminal(o.output);

  std::map<std::string, std::vector<std::pair<double, double>>> series;  // label -> (z, mts)
  std::vector<std::string> order;
  std::map<double, double> bound;
  for (const auto& rj : j["rows"]) {
    const MtsRow r = row_from_json(rj);
    const std::string label = r.pair.label();
    if (!series.count(label)) order.push_back(label);
    if (!r.unresolvable && std::isfinite(r.mts))
      series[label].push_back({r.z, r.mts});
    else
      series[label];
    bound[r.z] = r.vertex_bound;
  }
  std::string script =
      fmt::format("set terminal {}\nset output {}\n", terminal, gnuplot_quote(o.output));
  double lowest = INFINITY;
  for (const auto& [z, vb] : bound) lowest = std::min(lowest, vb);
  for (const auto& [label, pts] : series)
    for (const auto& [z, m] : pts) lowest = std::min(lowest, m);
  const double floor = std::isfinite(lowest) && lowest > 0 ? lowest / 10 : 1e-12;
  script +=
      "set logscale x 2\nset logscale y 10\nset format x '2^{%L}'\nset format y '10^{%L}'\n"
      "set key outside right\nset grid\nset xlabel 'distance z of the front plane'\n"
      "set ylabel 'minimum triangle separation'\n";
  script += fmt::format("set yrange [{:.6g}:*]\n", floor);
  const std::string title =
      o.title.empty() ? fmt::format("MTS by distance ({})", j.value("scene_source", "")) : o.title;
  script += fmt::format("set title {} noenhanced\n", gnuplot_quote(title));
  script += "$bound << EOD\n";
  for (const auto& [z, vb] : bound) script += fmt::format("{:.17g} {:.17g}\n", z, vb);
  script += "EOD\n";
  for (size_t i = 0; i < order.size(); ++i) {
    script += fmt::format("$s{} << EOD\n", i);
    for (const auto& [z, m] : series[order[i]]) script += fmt::format("{:.17g} {:.17g}\n", z, m);
    script += "EOD\n";
  }
  script += fmt::format(
      "plot $bound using 1:2:({:.6g}) with filledcurves fs pattern 4 lc rgb '#888888' "
      "title 'below the binary32 vertex bound', \\\n",
      floor);
  for (size_t i = 0; i < order.size(); ++i)
    script +=
        fmt::format("  $s{} using 1:2 with linespoints lw 1.5 pt {} title {} noenhanced{}\n", i,
                    1 + i % 12, gnuplot_quote(order[i]), i + 1 < order.size() ? ", \\" : "");
  run_gnuplot(script, o.output);
}

}  // namespace

void add_plot_command(CLI::App& app) {
  auto o = std::make_shared<PlotOptions>();
  auto* cmd = app.add_subcommand(
      "plot",
      "Plot MTS against distance (log-log, one line per technique/format/depth range, the\n"
      "binary32 vertex-precision bound shaded, as Gilg et al.'s fig. 6) with gnuplot, from the\n"
      "JSON output of mts, table or merge.\n"
      "Example:\n"
      "  depthprec table --format-out json -o table.json && depthprec plot table.json -o "
      "table.png");
  cmd->add_option("input", o->input, "JSON output of mts, table or merge")->required();
  cmd->add_option("-o,--output", o->output, "Image to write: .png or .svg")->capture_default_str();
  cmd->add_option("--title", o->title, "Plot title");
  cmd->callback([o]() { run_plot(*o); });
}

}  // namespace depthprec::cli
