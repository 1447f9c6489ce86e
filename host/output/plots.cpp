#include "host/output/plots.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
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

void plot_compare(const std::vector<nlohmann::json>& records, const std::string& output) {
  struct Series {
    std::vector<std::array<double, 3>> mts;    // z, emulated, rendered (NaN: no number)
    std::vector<std::array<double, 2>> ratio;  // z, emulated / rendered
  };
  std::vector<std::string> order;
  std::map<std::string, Series> series;
  const auto finite_or_nan = [](const nlohmann::json& v) {
    const double d = number_from_json(v, "compare record");
    return std::isfinite(d) ? d : NAN;
  };
  double lo = 1, hi = 1;  // the ratios' range
  for (const auto& r : records) {
    const std::string label = r.at("technique").get<std::string>() + "/" +
                              r.at("format").get<std::string>() + "/" +
                              r.at("depth_range").get<std::string>();
    if (!series.count(label)) order.push_back(label);
    const double z = r.at("z").get<double>();
    series[label].mts.push_back(
        {z, finite_or_nan(r.at("emulated_mts")), finite_or_nan(r.at("rendered_mts"))});
    if (r.contains("ratio")) {
      const double q = r.at("ratio").get<double>();
      series[label].ratio.push_back({z, q});
      lo = std::min(lo, q);
      hi = std::max(hi, q);
    }
  }
  std::string script = fmt::format("set terminal {}\nset output {}\n", gnuplot_terminal(output),
                                   gnuplot_quote(output));
  for (size_t i = 0; i < order.size(); ++i) {
    script += fmt::format("$m{} << EOD\n", i);
    for (const auto& p : series[order[i]].mts)
      script += fmt::format("{:.17g} {:.17g} {:.17g}\n", p[0], p[1], p[2]);
    script += fmt::format("EOD\n$r{} << EOD\n", i);
    for (const auto& p : series[order[i]].ratio)
      script += fmt::format("{:.17g} {:.17g}\n", p[0], p[1]);
    script += "EOD\n";
  }
  // One colour per pair from a list of distinct hues, point shapes changing every 12 pairs; the
  // ratio panel shares the MTS panel's key and margins.
  static const char* const kColours[] = {"#1f77b4", "#ff7f0e", "#2ca02c", "#d62728",
                                         "#9467bd", "#8c564b", "#e377c2", "#7f7f7f",
                                         "#bcbd22", "#17becf", "#000000", "#aec7e8"};
  const auto style = [](size_t i) {
    return fmt::format("lc rgb '{}' pt {}", kColours[i % 12], 4 + 2 * (i / 12));
  };
  script +=
      "set multiplot layout 2,1\nset lmargin 12\nset rmargin at screen 0.62\n"
      "set logscale x 2\nset format x '2^{%L}'\nset grid\nset key outside right top\n"
      "set logscale y 10\nset format y '10^{%L}'\nset ylabel 'minimum triangle separation'\n"
      "set title 'MTS: emulated (solid) and rendered (dashed)' noenhanced\nplot ";
  for (size_t i = 0; i < order.size(); ++i)
    script += fmt::format(
        "$m{0} using 1:2 with linespoints lw 1.5 ps 0.6 {1} title {2} noenhanced, "
        "$m{0} using 1:3 with linespoints lw 1.5 dt 2 ps 0.6 {1} notitle{3}",
        i, style(i), gnuplot_quote(order[i]), i + 1 < order.size() ? ", " : "\n");
  script += fmt::format(
      "set title 'emulated / rendered (below 1: the emulation is optimistic)' noenhanced\n"
      "set ylabel 'ratio'\nset format y '%g'\nset xlabel 'distance z of the front plane'\n"
      "set key off\nset yrange [{:.6g}:{:.6g}]\n"
      "plot 1 with lines lc rgb '#000000' lw 1 notitle, ",
      lo / 1.25, hi * 1.25);
  for (size_t i = 0; i < order.size(); ++i)
    script += fmt::format("$r{} using 1:2 with linespoints lw 1.5 ps 0.6 {} notitle{}", i, style(i),
                          i + 1 < order.size() ? ", " : "\n");
  script += "unset multiplot\n";
  run_gnuplot(script, output);
}

}  // namespace depthprec
