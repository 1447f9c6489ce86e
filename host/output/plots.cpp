#include "host/output/plots.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "host/analysis/lj_tables.h"
#include "host/base/json_number.h"
#include "host/output/gnuplot.h"

namespace depthprec {

void plot_cost(const std::vector<CostPoint>& points, const std::string& output) {
  std::string script = fmt::format("set terminal {}\nset output {}\n", gnuplot_terminal(output),
                                   gnuplot_quote(output));
  script +=
      "set logscale y\nset grid\nset key off\nset xlabel 'kernel cost [ns per fragment pair]'\n"
      "set ylabel 'median MTS / vertex bound (lower is more precise)'\n"
      "set title 'Precision against cost per technique and format' noenhanced\n"
      "set offsets graph 0.05, graph 0.25, graph 0.1, graph 0.1\n$pts << EOD\n";
  for (const auto& p : points)
    if (std::isfinite(p.median) && p.median > 0)
      script += fmt::format("{:.6g} {:.6g} {}\n", p.ns, p.median, gnuplot_quote(p.label));
  script +=
      "EOD\nplot $pts using 1:2 with points pt 7 ps 1.5, $pts using 1:2:3 with labels offset 1,0.5 "
      "left noenhanced\n";
  run_gnuplot(script, output);
}

void plot_tradeoff(const std::vector<LevelResult>& results, bool timing,
                   const std::string& output) {
  std::string script = fmt::format("set terminal {}\nset output {}\n", gnuplot_terminal(output),
                                   gnuplot_quote(output));
  script += fmt::format("set logscale xy\nset grid\nset key top right\nset xlabel '{}'\n",
                        timing ? "run time [s]" : "fragment pairs evaluated");
  script +=
      "set ylabel 'max relative MTS error vs the reference (0 plotted at 1e-6)'\n"
      "set title 'Fidelity trade-off' noenhanced\nset offsets graph 0.05, graph 0.05, graph 0.05, "
      "graph 0.05\n";
  script += "$levels << EOD\n";
  for (const auto& r : results)
    script += fmt::format("{:.6g} {:.6g} {}\n", timing ? r.seconds : static_cast<double>(r.pairs),
                          std::max(r.max_err, 1e-6), gnuplot_quote(r.level.name));
  script += "EOD\n$front << EOD\n";
  std::vector<const LevelResult*> front;
  for (const auto& r : results)
    if (r.pareto) front.push_back(&r);
  std::sort(front.begin(), front.end(),
            [](const LevelResult* a, const LevelResult* b) { return a->pairs < b->pairs; });
  for (const auto* r : front)
    script += fmt::format("{:.6g} {:.6g}\n", timing ? r->seconds : static_cast<double>(r->pairs),
                          std::max(r->max_err, 1e-6));
  script +=
      "EOD\nplot $levels using 1:2 with points pt 7 ps 1.5 title 'level', "
      "$levels using 1:2:3 with labels offset 1,0.6 left noenhanced notitle, "
      "$front using 1:2 with lines lw 2 title 'Pareto front'\n";
  run_gnuplot(script, output);
}

void plot_lj_table(const std::map<std::string, nlohmann::json>& records,
                   const std::string& output) {
  std::string script = fmt::format("set terminal {}\nset output {}\n", gnuplot_terminal(output),
                                   gnuplot_quote(output));
  script +=
      "set multiplot layout 2,2 title 'Lapidous-Jiao average error, 16-bit buffers, uniform "
      "sampling' noenhanced\n"
      "set logscale xy\nset grid\nset key top left font ',8'\nset xlabel 'f/d'\nset ylabel 'ae'\n";
  for (const LjBuffer b : kLjBuffers) {
    script += fmt::format("set title {} noenhanced\nplot ",
                          gnuplot_quote(std::string(to_string(b)) + " buffer"));
    for (int e = 0; e <= 8; ++e)
      script += fmt::format("'-' using 1:2 with linespoints title {}{}",
                            gnuplot_quote(e == 0 ? "unorm16" : fmt::format("e{}m{}", e, 16 - e)),
                            e < 8 ? ", " : "\n");
    for (int e = 0; e <= 8; ++e) {
      for (double r : kLjRatios) {
        const auto it = records.find(split_key("uniform", 16, b, r));
        if (it == records.end()) continue;
        const double ae = number_from_json(it->second.at("ae").at(e), "ae");
        if (std::isfinite(ae)) script += fmt::format("{:.6g} {:.6g}\n", r, ae);
      }
      script += "e\n";
    }
  }
  script += "unset multiplot\n";
  run_gnuplot(script, output);
}

}  // namespace depthprec
