// report: the page an engineer attaches to a design review -- a scene measured (or a measurement
// read back from JSON) written as one self-contained HTML file (host/output/html_report.h).
#include <fmt/format.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>

#include "host/base/errors.h"
#include "host/base/interrupt.h"
#include "host/cli/commands.h"
#include "host/cli/scene_options.h"
#include "host/lj/lj_metric.h"
#include "host/mts/mts_run.h"
#include "host/mts/row_json.h"
#include "host/output/html_report.h"
#include "host/output/output_guard.h"
#include "host/output/plots.h"
#include "host/output/read_output.h"
#include "host/runtime/opencl_runtime.h"
#include "host/shadow/shadow_options.h"

namespace depthprec::cli {

namespace {

struct ReportOptions {
  SceneOptions scene;
  std::string output = "report.html";
  std::string from;
  bool no_timing = false;
  bool no_attribute = false;
  bool output_named = false;  // -o given: it may replace a file; the default name never does
};

// The Lapidous-Jiao figure of every pair whose technique is one of LJ99's buffers, over the
// scene's [near, far].
std::vector<LjFigure> lj_figures(const Scene& scene) {
  std::vector<LjFigure> out;
  for (const auto& pair : scene.evaluate)
    if (const auto c = lj_config_for(pair.technique, scene.near, scene.far))
      out.push_back({pair.label(), info(pair.technique).lj_buffer, pair.format,
                     lj_average_error(*c, scene.storage_format(pair)).ae});
  return out;
}

// The plot as SVG text: gnuplot writes a temporary file, which is read back and removed.
std::string plot_svg(const std::vector<MtsRow>& rows, const std::string& scene_name) {
  const std::filesystem::path tmp =
      std::filesystem::temp_directory_path() / fmt::format("depthprec-report-{}.svg", ::getpid());
  plot_mts(rows, "MTS by distance, scene " + scene_name, tmp.string());
  std::ifstream in(tmp);
  std::stringstream svg;
  svg << in.rdbuf();
  std::filesystem::remove(tmp);
  return svg.str();
}

void run_report(const ReportOptions& o, const GlobalOptions& global) {
  check_output_spares_inputs("-o", o.output,
                             {{"the scene file", o.scene.scene_file}, {"the --from file", o.from}});
  if (!o.from.empty() && o.scene.any())
    throw Error(ExitCode::usage,
                "report: --from takes the scene and rows from its file; give no scene or scene "
                "option with it");
  check_default_output_is_new("report", o.output, o.output_named);
  check_writable(o.output);
  std::optional<Scene> scene;
  ReportPage page;
  // The scene's shadow block (docs/shadow.md): checked before the long run, emulated with it.
  auto shadow_of = [&page](const Scene& s, OpenClRuntime* rt) {
    if (!s.json.contains("shadow")) return;
    const ShadowRequest r =
        shadow_request(shadow_options_from_json(s.json["shadow"], s.source), rt != nullptr);
    page.shadow_header = shadow_header(r);
    page.shadow_records.clear();
    for (size_t i = 0; i < r.setup.cascades.size(); ++i)
      page.shadow_records.push_back(shadow_record(rt, r, i));
  };
  if (!o.from.empty()) {
    const auto j = read_json_output(o.from, "report", "--from file");
    check_rows_output(j, o.from, "report",
                      "`depthprec plot` draws it, and `report --profile NAME` reports one profile");
    scene = scene_from_json(j.at("scene"), o.from);
    for (const auto& r : j.at("rows")) page.rows.push_back(row_from_json(r));
    page.run.device = j.value("device", "");
    if (j.contains("gl_renderer"))
      page.run.rendered = {
          j.value("gl_renderer", ""), j.value("gl_version", ""), j.value("egl_platform", ""), {}};
    page.run.timing = false;     // the file's times belong to the run that wrote it
    shadow_of(*scene, nullptr);  // the proof and the engines' values; no device to emulate on
  } else {
    scene = o.scene.load();
    if (scene->json.contains("shadow"))
      shadow_request(shadow_options_from_json(scene->json["shadow"], scene->source), false);
    install_interrupt_handlers();
    OpenClRuntime rt(global.device);
    RunControl control;
    control.attribute = !o.no_attribute;  // the report shows what limits each number
    control.stop = interrupt_requested;
    const auto log = [&global](const std::string& line) {
      if (global.verbose) fmt::print(stderr, "{}\n", line);
    };
    MtsRun run = run_scene(rt, *scene, log, control);
    if (interrupt_requested())
      throw Error(ExitCode::interrupted, "report: interrupted; no report written");
    page.rows = std::move(run.rows);
    page.run = run.info;
    page.run.device = rt.description();
    page.run.variants = scene_variants(*scene);
    page.run.timing = !o.no_timing;
    shadow_of(*scene, &rt);
  }
  sort_rows(*scene, page.rows);
  page.run.fragment_pairs = 0;
  for (const auto& r : page.rows) page.run.fragment_pairs += r.fragment_pairs;
  page.scene = &*scene;
  page.lj = lj_figures(*scene);
  page.plot_svg = plot_svg(page.rows, scene->name);
  page.command = global.command_line;
  write_output(o.output, html_report(page));
  if (!global.quiet) fmt::print(stderr, "depthprec: report written to {}\n", o.output);
}

}  // namespace

void add_report_command(CLI::App& app, GlobalOptions& global) {
  auto o = std::make_shared<ReportOptions>();
  auto* cmd = app.add_subcommand(
      "report",
      "One self-contained HTML page to share: the scene, the MTS table with the dominant factor\n"
      "of each cell, the plot with the vertex bound (inline SVG), the attribution and the\n"
      "Lapidous-Jiao figures where they apply. No network, no other files: attach it to a\n"
      "review or open it in any browser. Runs the scene as `table --attribute` (the default\n"
      "scene: about a minute on 2 cores; --no-attribute: the table alone, seconds), or reads\n"
      "the JSON output of a whole mts/table/render/merge run with --from (not one shard).\n"
      "Examples:\n"
      "  depthprec report -o report.html\n"
      "  depthprec report data/gilg2021.json -t reversed,standard -f float32 -o decals.html\n"
      "  depthprec report --from table.json -o table.html");
  o->scene.add_to(*cmd, true);
  CLI::Option* output =
      cmd->add_option("-o,--output", o->output,
                      "The HTML file to write, replaced if it exists (without -o: report.html, "
                      "written only where there is no such file)")
          ->capture_default_str();
  cmd->add_option("--from", o->from,
                  "Build the page from this JSON output of mts, table, render or merge instead "
                  "of running the scene");
  cmd->add_flag("--no-attribute", o->no_attribute,
                "Leave the attribution out: the table's run alone, a fraction of the time");
  cmd->add_flag("--no-timing", o->no_timing,
                "Leave measured times out, so two reports compare byte for byte");
  cmd->callback([o, output, &global]() {
    o->output_named = output->count() > 0;
    run_report(*o, global);
  });
}

}  // namespace depthprec::cli
