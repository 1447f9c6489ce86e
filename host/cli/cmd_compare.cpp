// compare: the emulation against a real rasterizer, per (pair, z): both MTS, their ratio and both
// verdicts, with a summary (within 1.1x and 2x, the worst ratio, how often the emulation is
// optimistic). From a scene it runs both (`mts` and `render`, as a batch: journal, --resume,
// --shard, merge); from two JSON outputs it pairs their rows.
#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>

#include "host/analysis/compare.h"
#include "host/base/errors.h"
#include "host/base/interrupt.h"
#include "host/base/json_number.h"
#include "host/batch/batch.h"
#include "host/cli/commands.h"
#include "host/cli/scene_options.h"
#include "host/mts/mts_run.h"
#include "host/mts/row_json.h"
#include "host/output/gnuplot.h"
#include "host/output/output_guard.h"
#include "host/output/plots.h"
#include "host/output/progress.h"
#include "host/output/read_output.h"
#include "host/output/report.h"
#include "host/output/text_table.h"
#include "host/render/render_run.h"
#include "host/runtime/opencl_runtime.h"

namespace depthprec::cli {

namespace {

using nlohmann::json;

struct CompareOptions {
  SceneOptions scene;
  OutputOptions out;
  BatchOptions batch;
  std::string emulated_file, rendered_file, plot;
  std::string gl_device = GlDeviceChoice{}.text;
  int jobs = RunControl{}.jobs;
};

void add_rendered_with(json& header, const RenderedWith& with) {
  header["gl_renderer"] = with.renderer;
  header["gl_version"] = with.version;
  header["egl_platform"] = with.platform;
  header["depth_buffers"] = with.depth_buffers;
}

double rel_precision_of(const json& header) {
  return scene_from_json(header.at("scene"), "compare header").rel_precision;
}

// journal: the run's, removed once the output is in place (nullptr: rows read from files).
void finish(const CompareOptions& o, const json& header, const std::vector<json>& records,
            RowJournal* journal) {
  const std::string text =
      for_terminal(render_compare_output(header, records, o.out), o.out.format_out);
  if (journal)
    write_batch_output(*journal, o.out.output, text);
  else
    write_output(o.out.output, text);
  if (!o.plot.empty()) plot_compare(records, o.plot);
}

void run_from_scene(const CompareOptions& o, const GlobalOptions& global) {
  const Scene scene = o.scene.load();
  check_writable(o.out.output);
  check_plot_output(o.plot);
  const Shard shard = Shard::parse(o.batch.shard);
  if (o.batch.resume && o.out.output.empty()) RowJournal(o.out.output, true, {});  // usage error
  GlContext gl(GlDeviceChoice::parse(o.gl_device));
  // The emulation may follow a profile's implementation forms; the driver has its own.
  const Scene rendered_scene = rendered_counterpart(scene);
  const RenderedWith with{gl.renderer(), gl.version(), gl.platform(),
                          check_scene_renders(rendered_scene)};
  OpenClRuntime rt(global.device);
  json header = batch_header("compare", rt.description(), o.batch.shard);
  header["scene_name"] = scene.name;
  header["scene_source"] = scene.source;
  header["scene"] = scene.json;
  add_rendered_with(header, with);
  RowJournal journal(o.out.output, o.batch.resume, journal_identity(header));

  const SceneRows units = scene_rows(scene);
  const auto log = [&global](const std::string& line) {
    if (global.verbose) fmt::print(stderr, "{}\n", line);
  };
  // The emulation first (seconds for a whole scene), then the rendering, whose rows are the
  // records: each is journaled as its rendered row finishes.
  const BulkCompute compute = [&](const std::vector<size_t>& todo, const Emit& emit) {
    RunControl control = control_for(units, todo, interrupt_requested);
    control.jobs = o.jobs;
    std::map<std::string, MtsRow> emulated;
    control.on_row = [&](const MtsRow& r) { emulated[row_key(r.pair, r.z)] = r; };
    // Both sides timed in this one run (wall time of each phase): how much faster the emulator
    // measures what rendering measures, on this machine.
    const auto t0 = std::chrono::steady_clock::now();
    run_scene(rt, scene, log, control);
    const auto t1 = std::chrono::steady_clock::now();
    header["emulated_seconds"] = std::chrono::duration<double>(t1 - t0).count();
    control.on_row = [&](const MtsRow& r) {
      const std::string key = row_key(r.pair, r.z);
      emit(units.index_of.at(key), compare_record(emulated.at(key), r));
    };
    render_scene(gl, rendered_scene, log, control);
    header["rendered_seconds"] =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t1).count();
  };
  const auto records = run_batch(
      units.keys, compute, journal, shard, "compare", !global.quiet && stderr_is_terminal(),
      [&](const std::vector<json>& done) {
        write_output("",
                     for_terminal(render_compare_output(header, done, o.out), o.out.format_out));
      });
  finish(o, header, records, &journal);
}

json read_rows_doc(const std::string& path, const char* which) {
  json j = read_json_output(path, "compare", fmt::format("{} file", which));
  check_rows_output(j, path, "compare",
                    "`compare --profile NAME` compares one profile's emulation with the rendering");
  return j;
}

void run_from_files(const CompareOptions& o) {
  check_writable(o.out.output);
  check_plot_output(o.plot);
  const json e = read_rows_doc(o.emulated_file, "--emulated");
  const json r = read_rows_doc(o.rendered_file, "--rendered");
  if (e.at("scene") != r.at("scene"))
    throw InputError(fmt::format("compare: '{}' and '{}' ran different scenes", o.emulated_file,
                                 o.rendered_file));
  const auto rows_of = [](const json& doc, RowSource want, const std::string& path) {
    std::map<std::string, MtsRow> out;
    for (const auto& rj : doc.at("rows")) {
      MtsRow row = row_from_json(rj);
      if (row.source != want)
        throw InputError(fmt::format("compare: '{}' holds {} rows where {} ones belong", path,
                                     to_string(row.source), to_string(want)));
      out[row_key(row.pair, row.z)] = row;
    }
    return out;
  };
  const auto emulated = rows_of(e, RowSource::emulated, o.emulated_file);
  const auto rendered = rows_of(r, RowSource::rendered, o.rendered_file);
  const Scene scene = scene_from_json(e.at("scene"), e.value("scene_source", ""));
  std::vector<MtsRow> order;
  for (const auto& [key, row] : emulated)
    if (rendered.count(key)) order.push_back(row);
  if (order.empty())
    throw InputError(fmt::format("compare: '{}' and '{}' share no (pair, z) row", o.emulated_file,
                                 o.rendered_file));
  sort_rows(scene, order);
  std::vector<json> records;
  for (const auto& row : order) {
    const std::string key = row_key(row.pair, row.z);
    json rec = compare_record(row, rendered.at(key));
    rec["key"] = key;
    records.push_back(rec);
  }
  const size_t unmatched = emulated.size() + rendered.size() - 2 * records.size();
  if (unmatched > 0)
    fmt::print(stderr, "compare: {} rows are in only one of the two files, left out\n", unmatched);
  json header = batch_header("compare", e.value("device", ""), "");
  header["scene_name"] = e.at("scene").value("name", std::string());
  header["scene_source"] = e.value("scene_source", "");
  header["scene"] = e.at("scene");
  add_rendered_with(
      header, {r.value("gl_renderer", ""), r.value("gl_version", ""), r.value("egl_platform", ""),
               r.value("depth_buffers", std::map<std::string, std::string>{})});
  finish(o, header, records, nullptr);
}

std::string cell(const json& v) {
  if (v.is_null()) return "-";
  const double d = number_from_json(v, "compare cell");
  return human(d);
}

}  // namespace

std::string render_compare_output(const json& header, const std::vector<json>& records,
                                  const OutputOptions& out) {
  const bool timing = !out.no_timing;
  const double rel = rel_precision_of(header);
  const CompareSummary all = summarise(records, rel);
  const auto pairs = summarise_by_pair(records, rel);
  if (out.format_out == "json") {
    json derived = {{"summary", to_json(all)}, {"pairs", json::array()}};
    for (const auto& [label, s] : pairs) {
      json p = to_json(s);
      p["pair"] = label;
      derived["pairs"].push_back(p);
    }
    json h = header;
    if (!timing)
      for (const char* k : {"emulated_seconds", "rendered_seconds"}) h.erase(k);
    return records_json(h, records, timing, derived);
  }
  const bool full = out.format_out == "csv";
  // Column names are unique, so CSV readers keep every column.
  std::vector<Column> cols = {
      {"technique", true},   {"format", true}, {"depth_range", true}, {"z"},
      {"emulated"},          {"rendered"},     {"emu/rend"},          {"emu verdict", true},
      {"rend verdict", true}};
  if (timing)
    for (const char* c : {"emulated s", "rendered s", "frames/s"}) cols.push_back({c});
  const std::string none = full ? "" : "-";
  Cells cells;
  for (const auto& r : records) {
    const auto num = [full, &none](const json& v) {
      return v.is_null() ? none : full ? exact(number_from_json(v, "compare")) : cell(v);
    };
    std::vector<std::string> row = {
        r.at("technique").get<std::string>(),
        r.at("format").get<std::string>(),
        r.at("depth_range").get<std::string>(),
        num(r.at("z")),
        num(r.at("emulated_mts")),
        num(r.at("rendered_mts")),
        r.contains("ratio") ? number_cell(r["ratio"].get<double>(), out.format_out, "{:.3f}")
                            : none,
        r.at("emulated_verdict").get<std::string>(),
        r.at("rendered_verdict").get<std::string>()};
    if (timing) {
      const json& e = r.at("emulated");
      const json& d = r.at("rendered");
      const auto seconds = [&out, &none](const json& side) {
        if (!side.contains("seconds")) return none;
        const double v = number_from_json(side["seconds"], "seconds");
        return number_cell(v, out.format_out, "{:.3f}");
      };
      row.push_back(seconds(e));
      row.push_back(seconds(d));
      row.push_back(d.contains("frames_per_second") ? num(d["frames_per_second"]) : none);
    }
    cells.push_back(row);
  }
  if (full) return render_cells(cols, cells, "csv");
  std::string text = fmt::format(
      "Emulated against rendered on {} (OpenGL {}), scene {}: MTS per (pair, z); emu/rend below 1 "
      "is a separation the emulation calls safe that fights on the rasterizer\n\n",
      header.value("gl_renderer", "?"), header.value("gl_version", "?"),
      header.value("scene_name", "?"));
  text += render_cells(cols, cells, out.format_out);
  Cells per_pair;
  for (const auto& [label, s] : pairs)
    per_pair.push_back({label, std::to_string(s.rows), std::to_string(s.both_resolved),
                        std::to_string(s.within_1_1), std::to_string(s.within_2),
                        std::isnan(s.median_ratio) ? "-" : fmt::format("{:.3f}", s.median_ratio),
                        s.both_resolved ? fmt::format("{:.3f}", s.worst_ratio) : "-",
                        std::to_string(s.optimistic), std::to_string(s.verdicts_differ)});
  text +=
      "\nPer pair: rows resolved by both, within 1.1x and 2x of each other, median and worst "
      "emu/rend, rows on which the emulation is optimistic, verdicts that differ\n\n";
  text += render_cells({{"pair", true},
                        {"rows"},
                        {"resolved"},
                        {"in 1.1x"},
                        {"in 2x"},
                        {"median"},
                        {"worst"},
                        {"optimistic"},
                        {"verdicts differ"}},
                       per_pair, out.format_out);
  text += "\n" + summary_line(all) + "\n";
  if (timing && header.contains("rendered_seconds"))
    text += fmt::format("wall time: emulated {:.1f} s, rendered {:.1f} s\n",
                        header["emulated_seconds"].get<double>(),
                        header["rendered_seconds"].get<double>());
  return text;
}

void add_compare_command(CLI::App& app, GlobalOptions& global) {
  auto o = std::make_shared<CompareOptions>();
  auto* cmd = app.add_subcommand(
      "compare",
      "The emulation side by side with a real rasterizer: per (pair, z) the emulated MTS (`mts`)\n"
      "and the rendered one (`render`, the system's OpenGL), their ratio emulated/rendered and\n"
      "both verdicts, a summary per pair and overall (rows within 1.1x and 2x, worst ratio, rows\n"
      "on which the emulation is optimistic), and with --plot both curves. From a scene it runs\n"
      "both (a batch: journal, --resume, --shard, merge); from --emulated and --rendered JSON\n"
      "outputs it pairs their rows. docs/validation.md explains the differences.\n"
      "Examples:\n"
      "  depthprec compare -t standard,reversed -f float32 --distances 2,1024,1e6 --frames 20\n"
      "  depthprec compare -o compare.md --plot compare.png      (the default scene, minutes)\n"
      "  depthprec compare --emulated mts.json --rendered render.json --format-out csv");
  o->scene.add_to(*cmd, true);
  o->out.add_to(*cmd);
  o->batch.add_to(*cmd, "rows (k = pair index x distances + distance index)");
  cmd->add_option("--emulated", o->emulated_file,
                  "JSON output of mts/table (--format-out json): compare its rows instead of "
                  "running the scene; needs --rendered");
  cmd->add_option("--rendered", o->rendered_file,
                  "JSON output of render (--format-out json), to pair with --emulated");
  cmd->add_option("--plot", o->plot,
                  "Also plot both MTS curves and their ratio (gnuplot), FILE.png or FILE.svg");
  add_gl_device_option(cmd, o->gl_device);
  cmd->add_option("--jobs", o->jobs, "Emulated pairs evaluated side by side (as for mts)")
      ->check(CLI::Range(1, 64))
      ->capture_default_str();
  cmd->callback([o, &global]() {
    const std::vector<NamedInput> inputs = {{"the scene file", o->scene.scene_file},
                                            {"the --emulated file", o->emulated_file},
                                            {"the --rendered file", o->rendered_file}};
    check_output_spares_inputs("-o", o->out.output, inputs);
    check_output_spares_inputs("--plot", o->plot, inputs);
    if (o->emulated_file.empty() != o->rendered_file.empty())
      throw Error(ExitCode::usage, "compare: --emulated and --rendered go together");
    if (!o->emulated_file.empty() && (o->scene.any() || !o->batch.shard.empty() || o->batch.resume))
      throw Error(ExitCode::usage,
                  "compare: --emulated and --rendered pair the rows of two outputs, whose scene is "
                  "in their headers; drop the scene options (and --shard, --resume)");
    if (o->emulated_file.empty()) {
      run_from_scene(*o, global);
      return;
    }
    // The files may hold any JSON: a field of the wrong type is bad input, as for merge.
    try {
      run_from_files(*o);
    } catch (const json::exception& e) {
      throw InputError(fmt::format("compare: a file is not an output it can pair: {}", e.what()));
    }
  });
}

}  // namespace depthprec::cli
