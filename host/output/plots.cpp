#include "host/output/plots.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>

#include "host/analysis/lj_tables.h"
#include "host/base/errors.h"
#include "host/base/json_number.h"
#include "host/output/gnuplot.h"

namespace depthprec {

namespace {

// One colour per series from a list of distinct hues, point shapes changing every 12 series.
// Plots that draw one series per line may also change the dash (series_dash); the ones that dash
// their own lines (compare's, the profiles') must not get two.
const char* const kColours[] = {"#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd", "#8c564b",
                                "#e377c2", "#7f7f7f", "#bcbd22", "#17becf", "#000000", "#aec7e8"};
std::string series_style(size_t i) {
  return fmt::format("lc rgb '{}' pt {}", kColours[i % 12], 4 + 2 * (i / 12));
}
std::string series_dash(size_t i) {
  return fmt::format("dt {}", 1 + i / 12);
}

// The first lines of every plot's script: the terminal the output's name asks for, and the file
// gnuplot writes (run_gnuplot puts it in place).
std::string script_start(const std::string& output) {
  return fmt::format("set terminal {}\nset output {}\n", gnuplot_terminal(output),
                     gnuplot_quote(gnuplot_writes(output)));
}

// Log axes labelled as powers of ten (gnuplot's enhanced text), never as 0.000010.
constexpr const char* kLogTenY = "set logscale y 10\nset format y '10^{%L}'\n";

}  // namespace

void plot_mts(const std::vector<MtsRow>& rows, const std::string& title,
              const std::string& output) {
  if (rows.empty()) throw InputError("plot: there are no MTS rows to plot");
  struct Series {
    std::vector<std::pair<double, double>> mts;  // z, mts
    std::vector<double> none;                    // z where the pair has no MTS
  };
  std::map<std::string, Series> series;
  std::vector<std::string> order;
  std::map<double, double> bound;
  for (const MtsRow& r : rows) {
    const std::string label = r.pair.label();
    if (!series.count(label)) order.push_back(label);
    if (r.verdict() == Verdict::resolved)
      series[label].mts.push_back({r.z, r.mts});
    else
      series[label].none.push_back(r.z);
    bound[r.z] = r.vertex_bound;
  }
  double lowest = INFINITY, highest = 0;
  for (const auto& [z, vb] : bound) lowest = std::min(lowest, vb);
  for (const auto& [label, s] : series)
    for (const auto& [z, m] : s.mts) {
      lowest = std::min(lowest, m);
      highest = std::max(highest, m);
    }
  const double floor = std::isfinite(lowest) && lowest > 0 ? lowest / 10 : 1e-12;
  // Distances without an MTS are drawn as crosses along a band above every number, so a pair's
  // missing points are seen, not silently absent.
  const double top = std::max(highest, floor * 10) * 100;
  std::string script = script_start(output);
  script += "set logscale x 2\nset format x '2^{%L}'\n";
  script += kLogTenY;
  script +=
      "set key outside right\nset grid\nset xlabel 'distance z of the front plane (scene units)'\n"
      "set ylabel 'minimum triangle separation (scene units)'\n";
  script += fmt::format("set yrange [{:.6g}:{:.6g}]\n", floor, top * 3);
  script += fmt::format("set title {} noenhanced\n", gnuplot_quote(title));
  script += "$bound << EOD\n";
  for (const auto& [z, vb] : bound) script += fmt::format("{:.17g} {:.17g}\n", z, vb);
  script += "EOD\n";
  bool any_none = false;
  for (size_t i = 0; i < order.size(); ++i) {
    script += fmt::format("$s{} << EOD\n", i);
    for (const auto& [z, m] : series[order[i]].mts)
      script += fmt::format("{:.17g} {:.17g}\n", z, m);
    script += fmt::format("EOD\n$n{} << EOD\n", i);
    for (double z : series[order[i]].none) script += fmt::format("{:.17g} {:.17g}\n", z, top);
    any_none |= !series[order[i]].none.empty();
    script += "EOD\n";
  }
  script += fmt::format(
      "plot $bound using 1:2:({:.6g}) with filledcurves fs pattern 4 lc rgb '#888888' "
      "title 'below the binary32 vertex bound'",
      floor);
  if (any_none)
    script += fmt::format(
        ", {:.6g} with lines dt 3 lc rgb '#888888' title 'x: no MTS at this z (see the table)'",
        top);
  for (size_t i = 0; i < order.size(); ++i) {
    script += fmt::format(", $s{} using 1:2 with linespoints lw 1.5 {} {} title {} noenhanced", i,
                          series_style(i), series_dash(i), gnuplot_quote(order[i]));
    if (!series[order[i]].none.empty())
      script += fmt::format(", $n{} using 1:2 with points pt 2 ps 1.2 lc rgb '{}' notitle", i,
                            kColours[i % 12]);
  }
  script += "\n";
  run_gnuplot(script, output);
}

void plot_cost(const std::vector<CostPoint>& points, const std::string& output) {
  std::string script = script_start(output);
  // Each point its own key entry: labels written beside points overlap where pairs cost alike.
  script +=
      "set grid\nset key outside right\nset xlabel 'kernel cost [ns per fragment pair]'\n"
      "set ylabel 'median MTS / vertex bound (lower is more precise)'\n"
      "set title 'Precision against cost per technique and format' noenhanced\n"
      "set offsets graph 0.05, graph 0.05, graph 0.1, graph 0.1\n";
  script += kLogTenY;
  std::string plot;
  size_t i = 0;
  for (const auto& p : points) {
    if (!std::isfinite(p.median) || p.median <= 0) continue;
    script += fmt::format("$p{} << EOD\n{:.6g} {:.6g}\nEOD\n", i, p.ns, p.median);
    plot += fmt::format("{}$p{} using 1:2 with points ps 1.5 {} title {} noenhanced",
                        plot.empty() ? "plot " : ", ", i, series_style(i), gnuplot_quote(p.label));
    ++i;
  }
  script += (plot.empty() ? "plot NaN notitle" : plot) + "\n";
  run_gnuplot(script, output);
}

void plot_tradeoff(const std::vector<LevelResult>& results, const std::string& output) {
  std::string script = script_start(output);
  // Drawn on the axis the Pareto front is computed on (fragment pairs, which a run repeats
  // exactly), and each level its own key entry, so no label covers another.
  script +=
      "set logscale x 10\nset format x '10^{%L}'\nset grid\nset key outside right\n"
      "set xlabel 'fragment pairs evaluated'\n"
      "set ylabel 'max relative MTS error vs the reference (0 drawn at 10^{-6})'\n"
      "set title 'Fidelity trade-off: error against work, Pareto front joined' noenhanced\n"
      "set offsets graph 0.05, graph 0.05, graph 0.05, graph 0.05\n";
  script += kLogTenY;
  std::vector<const LevelResult*> front;
  std::string plot;
  for (size_t i = 0; i < results.size(); ++i) {
    const auto& r = results[i];
    script += fmt::format("$l{} << EOD\n{:.6g} {:.6g}\nEOD\n", i, static_cast<double>(r.pairs),
                          std::max(r.max_err, 1e-6));
    plot += fmt::format("{}$l{} using 1:2 with points ps 1.5 {} title {} noenhanced",
                        plot.empty() ? "plot " : ", ", i, series_style(i),
                        gnuplot_quote(r.level.name + (r.pareto ? " (front)" : "")));
    if (r.pareto) front.push_back(&r);
  }
  std::sort(front.begin(), front.end(),
            [](const LevelResult* a, const LevelResult* b) { return a->pairs < b->pairs; });
  script += "$front << EOD\n";
  for (const auto* r : front)
    script +=
        fmt::format("{:.6g} {:.6g}\n", static_cast<double>(r->pairs), std::max(r->max_err, 1e-6));
  script += "EOD\n";
  script += (plot.empty() ? "plot NaN notitle" : plot) +
            ", $front using 1:2 with lines lw 2 lc rgb '#444444' title 'Pareto front'\n";
  run_gnuplot(script, output);
}

void plot_lj_table(const std::map<std::string, nlohmann::json>& records,
                   const std::string& output) {
  std::string script = script_start(output);
  script +=
      "set multiplot layout 2,2 title 'Lapidous-Jiao average error, 16-bit buffers, uniform "
      "sampling' noenhanced\n"
      "set logscale xy\nset format x '10^{%L}'\nset format y '10^{%L}'\nset grid\n"
      "set key top left font ',8'\nset xlabel 'f/d'\nset ylabel 'ae'\n";
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
    const std::string label = pair_label(r);
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
  std::string script = script_start(output);
  for (size_t i = 0; i < order.size(); ++i) {
    script += fmt::format("$m{} << EOD\n", i);
    for (const auto& p : series[order[i]].mts)
      script += fmt::format("{:.17g} {:.17g} {:.17g}\n", p[0], p[1], p[2]);
    script += fmt::format("EOD\n$r{} << EOD\n", i);
    for (const auto& p : series[order[i]].ratio)
      script += fmt::format("{:.17g} {:.17g}\n", p[0], p[1]);
    script += "EOD\n";
  }
  // The ratio panel shares the MTS panel's key and margins.
  const auto style = series_style;
  script +=
      "set multiplot layout 2,1\nset lmargin 12\nset rmargin at screen 0.62\n"
      "set logscale x 2\nset format x '2^{%L}'\nset grid\nset key outside right top\n"
      "set logscale y 10\nset format y '10^{%L}'\nset ylabel 'minimum triangle separation (scene "
      "units)'\n"
      "set title 'MTS: emulated (solid) and rendered (dashed)' noenhanced\nplot ";
  for (size_t i = 0; i < order.size(); ++i)
    script += fmt::format(
        "$m{0} using 1:2 with linespoints lw 1.5 ps 0.6 {1} title {2} noenhanced, "
        "$m{0} using 1:3 with linespoints lw 1.5 dt 2 ps 0.6 {1} notitle{3}",
        i, style(i), gnuplot_quote(order[i]), i + 1 < order.size() ? ", " : "\n");
  script += fmt::format(
      "set title 'emulated / rendered (below 1: the emulation is optimistic)' noenhanced\n"
      "set ylabel 'ratio'\nset format y '%g'\nset xlabel 'distance z of the front plane (scene "
      "units)'\n"
      "set key off\nset yrange [{:.6g}:{:.6g}]\n"
      "plot 1 with lines lc rgb '#000000' lw 1 notitle, ",
      lo / 1.25, hi * 1.25);
  for (size_t i = 0; i < order.size(); ++i)
    script += fmt::format("$r{} using 1:2 with linespoints lw 1.5 ps 0.6 {} notitle{}", i, style(i),
                          i + 1 < order.size() ? ", " : "\n");
  script += "unset multiplot\n";
  run_gnuplot(script, output);
}

void plot_profiles(const std::vector<nlohmann::json>& records,
                   const std::vector<std::string>& profiles, const std::string& title,
                   const std::string& output) {
  if (records.empty()) throw InputError("plot: there are no profile records to plot");
  std::string script = script_start(output);
  std::vector<std::string> labels;
  for (size_t i = 0; i < records.size(); ++i) {
    const auto& r = records[i];
    labels.push_back(pair_label(r));
    script += fmt::format("$p{} << EOD\n", i);
    for (const auto& row : r.at("rows")) {
      // z, the band (min, max over the profiles that resolved it), then each profile (NaN: none)
      double lo = INFINITY, hi = -INFINITY;
      std::string values;
      for (const auto& p : profiles) {
        const nlohmann::json& v = row.at("mts").at(p);
        const double m = v.is_null() ? NAN : number_from_json(v, "mts");
        if (std::isfinite(m)) {
          lo = std::min(lo, m);
          hi = std::max(hi, m);
        }
        values += fmt::format(" {:.17g}", m);
      }
      if (!std::isfinite(lo)) lo = hi = NAN;
      script +=
          fmt::format("{:.17g} {:.17g} {:.17g}{}\n", row.at("z").get<double>(), lo, hi, values);
    }
    script += "EOD\n";
  }
  script += "set logscale x 2\nset format x '2^{%L}'\n";
  script += kLogTenY;
  script += fmt::format(
      "set key outside right\nset grid\nset xlabel 'distance z of the front plane (scene units)'\n"
      "set ylabel 'minimum triangle separation (scene units)'\nset title {} noenhanced\nplot ",
      gnuplot_quote(title));
  for (size_t i = 0; i < records.size(); ++i) {
    script += fmt::format(
        "$p{0} using 1:2:3 with filledcurves fs transparent solid 0.2 noborder lc rgb '{1}' "
        "notitle, ",
        i, kColours[i % 12]);
    for (size_t k = 0; k < profiles.size(); ++k)
      script += fmt::format(
          "$p{} using 1:{} with linespoints lw 1.5 dt {} ps 0.5 {} title {} "
          "noenhanced{}",
          i, 4 + k, 1 + k, series_style(i), gnuplot_quote(labels[i] + " " + profiles[k]),
          i + 1 == records.size() && k + 1 == profiles.size() ? "\n" : ", ");
  }
  run_gnuplot(script, output);
}

}  // namespace depthprec
