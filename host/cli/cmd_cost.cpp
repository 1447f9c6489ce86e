// cost: per technique and format, what its depth path costs in the kernel next to the precision
// it buys, and the costs a GPU would pay that an emulator does not measure.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

#include "host/cli/commands.h"
#include "host/cli/scene_options.h"
#include "host/errors.h"
#include "host/gnuplot.h"
#include "host/lj_metric.h"
#include "host/mts_run.h"
#include "host/mts_timing.h"
#include "host/text_table.h"
#include "host/version.h"

namespace depthprec::cli {

namespace {

struct CostOptions {
  SceneOptions scene;
  OutputOptions out;
  std::string plot;
};

struct CostPoint {
  std::string label;
  double ns = 0, median = 0;
};

// Precision against cost: one labelled point per technique x format.
void plot_cost(const std::vector<CostPoint>& points, const std::string& output) {
  std::string script = fmt::format("set terminal {}\nset output {}\n", gnuplot_terminal(output), gnuplot_quote(output));
  script += "set logscale y\nset grid\nset key off\nset xlabel 'kernel cost [ns per fragment pair]'\n"
            "set ylabel 'median MTS / vertex bound (lower is more precise)'\n"
            "set title 'Precision against cost per technique and format' noenhanced\n"
            "set offsets graph 0.05, graph 0.25, graph 0.1, graph 0.1\n$pts << EOD\n";
  for (const auto& p : points)
    if (std::isfinite(p.median) && p.median > 0)
      script += fmt::format("{:.6g} {:.6g} {}\n", p.ns, p.median, gnuplot_quote(p.label));
  script += "EOD\nplot $pts using 1:2 with points pt 7 ps 1.5, $pts using 1:2:3 with labels offset 1,0.5 left noenhanced\n";
  run_gnuplot(script, output);
}

// What a real GPU pays for the technique beyond its arithmetic.
std::string structural_cost(const Scene& s, Technique t) {
  const TechniqueInfo& ti = info(t);
  if (t == Technique::layered)
    return fmt::format("{} passes, depth cleared per layer; {} mapping per layer", s.params.layers,
                       info(s.params.layer_mapping).name);
  if (ti.from == DepthFrom::fragment)
    return "writes depth in the fragment stage: no early depth test, weaker depth compression";
  if (ti.from == DepthFrom::vertex_log) return "a log per vertex; depth not interpolated perspective-correctly";
  return "projection matrix only";
}

// The LJ buffer a technique is, where there is one (SPEC 6), else none.
bool lj_buffer_of(Technique t, LjBuffer& b) {
  switch (t) {
    case Technique::standard: b = LjBuffer::z; return true;
    case Technique::w_buffer: b = LjBuffer::w; return true;
    case Technique::inverse_w: b = LjBuffer::inverse_w; return true;
    case Technique::reversed: b = LjBuffer::complementary_z; return true;
    default: return false;
  }
}

void run_cost(const CostOptions& o, const GlobalOptions& g) {
  const Scene scene = o.scene.load();
  check_writable(o.out.output);
  OpenClRuntime rt(g.device);
  const MtsRun mts = run_scene(rt, scene);
  const bool timing = !o.out.no_timing;
  nlohmann::json rows = nlohmann::json::array();
  Cells cells;
  std::vector<CostPoint> points;
  for (const EvalPair& pair : scene.evaluate) {
    std::vector<double> ratio;
    int unresolved = 0;
    for (const auto& r : mts.rows)
      if (r.pair.label() == pair.label()) {
        if (r.unresolvable) ++unresolved;
        else ratio.push_back(r.mts / r.vertex_bound);
      }
    std::sort(ratio.begin(), ratio.end());
    const double median = ratio.empty() ? INFINITY : ratio[ratio.size() / 2];
    LjBuffer b;
    double ae = NAN;
    if (lj_buffer_of(pair.technique, b) && std::isfinite(scene.far)) {
      LjConfig c;
      c.buffer = b;
      c.near = scene.near;
      c.far = scene.far;
      ae = lj_average_error_device(rt, c, scene.storage_format(pair)).ae;
    }
    const Throughput t = timing ? time_depth_path(rt, scene, pair, TimingRegime::near) : Throughput{};
    const std::string structural = structural_cost(scene, pair.technique);
    points.push_back({pair.label(), t.ns_per_pair(), median});
    nlohmann::json j = {{"technique", info(pair.technique).name}, {"format", pair.format},
                        {"depth_range", to_string(pair.depth_range)}, {"median_mts_over_vertex_bound", median},
                        {"unresolvable_distances", unresolved}, {"structural_cost", structural}};
    if (!std::isnan(ae)) j["lj_ae"] = ae;
    if (timing) j["ns_per_fragment_pair"] = t.ns_per_pair();
    rows.push_back(j);
    std::vector<std::string> row = {info(pair.technique).name, pair.format, to_string(pair.depth_range)};
    if (timing) row.push_back(fmt::format("{:.2f}", t.ns_per_pair()));
    row.push_back(std::isinf(median) ? "inf" : fmt::format("{:.3g}", median));
    row.push_back(std::to_string(unresolved));
    row.push_back(std::isnan(ae) ? "-" : fmt::format("{:.3g}", ae));
    row.push_back(structural);
    cells.push_back(row);
  }
  std::string text;
  if (o.out.format_out == "json") {
    nlohmann::json j = {{"program", "depthprec"}, {"version", kVersion}, {"device", rt.description()},
                        {"scene", scene.json}, {"rows", rows}};
    text = j.dump(2) + "\n";
  } else {
    std::vector<Column> cols = {{"technique", true}, {"format", true}, {"depth_range", true}};
    if (timing) cols.push_back({"ns/pair"});
    for (const char* c : {"median mts/vb", "unresolvable", "lj ae"}) cols.push_back({c});
    cols.push_back({"structural cost on a GPU", true});
    text = fmt::format("Cost and precision per technique (scene {}): ns per fragment pair of the kernel's "
                       "depth path (timing pass, near-MTS probes), median MTS over the vertex bound across "
                       "the scene's distances, Lapidous-Jiao ae where the technique is one of its buffers\n\n",
                       scene.name) +
           render_cells(cols, cells, o.out.format_out);
  }
  write_output(o.out.output, text);
  if (!o.plot.empty()) {
    if (!timing) throw Error(ExitCode::usage, "cost: --plot needs the timing pass (drop --no-timing)");
    plot_cost(points, o.plot);
  }
}

}  // namespace

void add_cost_command(CLI::App& app, GlobalOptions& global) {
  auto o = std::make_shared<CostOptions>();
  auto* cmd = app.add_subcommand(
      "cost",
      "Per technique x format: the kernel's cost per fragment pair of its depth path (a dedicated\n"
      "timing pass), the precision it buys (median MTS / vertex bound over the scene's distances,\n"
      "and the Lapidous-Jiao error where the technique is one of LJ's buffers), and the structural\n"
      "costs a GPU pays (fragment-depth writes disable early depth test; layering costs a pass per\n"
      "layer). CSV/JSON output is the error-vs-cost plot data.\n"
      "Examples:\n"
      "  depthprec cost -t standard,reversed,log_fragment,linear -f float32,unorm24 --distances 2,1024,1e6\n"
      "  depthprec cost --format-out csv -o cost.csv");
  o->scene.add_to(*cmd, true);
  o->out.add_to(*cmd);
  cmd->add_option("--plot", o->plot, "Also plot precision against cost (gnuplot), FILE.png or FILE.svg");
  cmd->callback([o, &global]() { run_cost(*o, global); });
}

}  // namespace depthprec::cli
