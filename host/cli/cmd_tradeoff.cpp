// tradeoff: how the evaluator's own answer degrades as it spends less (kernel pixels, frames,
// bisection precision), against its full-fidelity answer.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

#include "host/base/errors.h"
#include "host/base/json_number.h"
#include "host/base/version.h"
#include "host/batch/batch.h"
#include "host/cli/commands.h"
#include "host/cli/record_batch.h"
#include "host/cli/scene_options.h"
#include "host/mts/mts_run.h"
#include "host/output/gnuplot.h"
#include "host/output/row_json.h"
#include "host/output/text_table.h"

namespace depthprec::cli {

namespace {

struct Level {
  std::string name;
  int kernel;
  int frames;
  int precision_log2;  // rel_precision = 2^-precision_log2
};

// The ladder of the issue: each budget alone, then combined; the first is the reference.
std::vector<Level> ladder() {
  return {{"reference", 200, 100, 12},     {"kernel 100", 100, 100, 12},
          {"kernel 50", 50, 100, 12},      {"kernel 25", 25, 100, 12},
          {"frames 50", 200, 50, 12},      {"frames 25", 200, 25, 12},
          {"frames 10", 200, 10, 12},      {"precision 2^-10", 200, 100, 10},
          {"precision 2^-8", 200, 100, 8}, {"precision 2^-6", 200, 100, 6},
          {"precision 2^-4", 200, 100, 4}, {"100/50/2^-8", 100, 50, 8},
          {"50/25/2^-6", 50, 25, 6},       {"25/10/2^-4", 25, 10, 4}};
}

struct LevelResult {
  Level level;
  double seconds = 0;
  uint64_t pairs = 0;
  double median_err = 0, max_err = 0;
  int verdict_changes = 0;
  std::vector<std::string> changed;  // "technique/format/range z" of each verdict change
  bool pareto = false;
};

struct TradeoffOptions {
  SceneOptions scene;
  OutputOptions out;
  std::string plot;
  BatchOptions batch;
};

// Error against cost: one point per level, the Pareto front joined. Errors of 0 sit on a floor.
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

// One record per level: its work, time and every row's MTS (errors are derived when rendering,
// against the reference level's record).
nlohmann::json level_record(OpenClRuntime& rt, const Scene& base, const Level& lv) {
  Scene s = base;
  s.kernel_w = s.kernel_h = s.viewport_w = s.viewport_h = lv.kernel;
  s.frames = lv.frames;
  s.rel_precision = std::ldexp(1.0, -lv.precision_log2);
  const MtsRun run = run_scene(rt, s);
  nlohmann::json rows = nlohmann::json::array();
  for (const auto& r : run.rows)
    rows.push_back({{"row", row_key(r.pair, r.z)},
                    {"mts", json_number(r.mts)},
                    {"unresolvable", r.unresolvable}});
  return {{"level", lv.name},
          {"kernel", lv.kernel},
          {"frames", lv.frames},
          {"precision_log2", lv.precision_log2},
          {"fragment_pairs", run.info.fragment_pairs},
          {"seconds", run.info.wall_seconds},
          {"rows", rows}};
}

// Errors against the reference record and the Pareto front; empty when the reference level is
// not among the records (a shard without it).
std::vector<LevelResult> evaluate_levels(const std::vector<nlohmann::json>& records) {
  const nlohmann::json* reference = nullptr;
  for (const auto& r : records)
    if (r.at("level") == ladder().front().name) reference = &r;
  std::vector<LevelResult> results;
  if (!reference) return results;
  const auto& ref_rows = reference->at("rows");
  for (const auto& rec : records) {
    LevelResult r;
    r.level = {rec.at("level").get<std::string>(), rec.at("kernel").get<int>(),
               rec.at("frames").get<int>(), rec.at("precision_log2").get<int>()};
    r.seconds = rec.value("seconds", 0.0);
    r.pairs = rec.at("fragment_pairs").get<uint64_t>();
    std::vector<double> errs;
    const auto& rows = rec.at("rows");
    for (size_t i = 0; i < rows.size() && i < ref_rows.size(); ++i) {
      const bool unres = rows[i].at("unresolvable").get<bool>(),
                 ref_unres = ref_rows[i].at("unresolvable").get<bool>();
      if (unres != ref_unres) {
        ++r.verdict_changes;
        r.changed.push_back(rows[i].at("row").get<std::string>());
      } else if (!unres) {
        const double mts = number_from_json(rows[i].at("mts"), "mts"),
                     ref = number_from_json(ref_rows[i].at("mts"), "mts");
        errs.push_back(std::abs(mts - ref) / ref);
      }
    }
    std::sort(errs.begin(), errs.end());
    if (!errs.empty()) {
      r.median_err = errs.size() % 2 ? errs[errs.size() / 2]
                                     : 0.5 * (errs[errs.size() / 2 - 1] + errs[errs.size() / 2]);
      r.max_err = errs.back();
    }
    results.push_back(r);
  }
  // Pareto front by work (fragment pairs: deterministic, proportional to time) against accuracy
  // (verdict changes first, then the largest relative error): keep the levels no other level
  // beats on both.
  for (auto& a : results) {
    a.pareto = true;
    for (const auto& b : results) {
      const bool cheaper_or_same = b.pairs <= a.pairs;
      const bool better_or_same = std::make_pair(b.verdict_changes, b.max_err) <=
                                  std::make_pair(a.verdict_changes, a.max_err);
      const bool strictly = b.pairs < a.pairs || std::make_pair(b.verdict_changes, b.max_err) <
                                                     std::make_pair(a.verdict_changes, a.max_err);
      if (&a != &b && cheaper_or_same && better_or_same && strictly) a.pareto = false;
    }
  }
  return results;
}

void run_tradeoff(const TradeoffOptions& o, const GlobalOptions& g) {
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
  if (!o.plot.empty()) plot_tradeoff(evaluate_levels(records), !o.out.no_timing, o.plot);
}

}  // namespace

std::string render_tradeoff_output(const nlohmann::json& header,
                                   const std::vector<nlohmann::json>& records,
                                   const OutputOptions& out) {
  const bool timing = !out.no_timing;
  const std::vector<LevelResult> results = evaluate_levels(records);
  if (out.format_out == "json") {
    nlohmann::json levels = nlohmann::json::array();
    for (const auto& r : results)
      levels.push_back({{"level", r.level.name},
                        {"kernel", r.level.kernel},
                        {"frames", r.level.frames},
                        {"rel_precision", std::ldexp(1.0, -r.level.precision_log2)},
                        {"fragment_pairs", r.pairs},
                        {"seconds", r.seconds},
                        {"median_rel_err", r.median_err},
                        {"max_rel_err", r.max_err},
                        {"verdict_changes", r.changed},
                        {"pareto", r.pareto}});
    return records_json(header, records, timing, {{"levels", levels}});
  }
  std::vector<Column> cols = {
      {"level", true}, {"kernel"}, {"frames"}, {"rel_precision"}, {"fragment_pairs"}};
  if (timing) cols.push_back({"seconds"});
  for (const char* c : {"median_rel_err", "max_rel_err", "verdict_changes"}) cols.push_back({c});
  cols.push_back({"pareto", true});
  Cells cells;
  for (const auto& r : results) {
    std::vector<std::string> row = {
        r.level.name, fmt::format("{}x{}", r.level.kernel, r.level.kernel),
        std::to_string(r.level.frames), fmt::format("2^-{}", r.level.precision_log2),
        std::to_string(r.pairs)};
    if (timing) row.push_back(fmt::format("{:.2f}", r.seconds));
    row.push_back(fmt::format("{:.3g}", r.median_err));
    row.push_back(fmt::format("{:.3g}", r.max_err));
    row.push_back(std::to_string(r.verdict_changes));
    row.push_back(r.pareto ? "yes" : "");
    cells.push_back(row);
  }
  std::string changed;
  for (const auto& r : results)
    for (const auto& c : r.changed)
      changed += fmt::format("{}: verdict changed at {}\n", r.level.name, c);
  return fmt::format(
             "Fidelity trade-off on scene {} ({} pairs x {} distances); errors relative to the "
             "reference level; Pareto front by fragment pairs vs (verdict changes, max error)\n\n",
             header.value("scene_name", std::string("?")), header.value("pairs", 0),
             header.value("distances", 0)) +
         render_cells(cols, cells, out.format_out) +
         (changed.empty() || out.format_out == "csv" ? "" : "\n" + changed);
}

void add_tradeoff_command(CLI::App& app, GlobalOptions& global) {
  auto o = std::make_shared<TradeoffOptions>();
  auto* cmd = app.add_subcommand(
      "tradeoff",
      "How the MTS answer degrades as the evaluator spends less: kernel 25^2..200^2, frames\n"
      "10..100, rel_precision 2^-4..2^-12, alone and combined, each against the reference level\n"
      "(200^2, 100 frames, 2^-12): median and max relative MTS error, distances whose\n"
      "resolvable/unresolvable verdict changed, work and time, and the Pareto front.\n"
      "Fourteen full runs of the scene's pairs: choose few pairs and distances.\n"
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
