// mts and table: the scene's rows through the batch loop every batch command shares
// (host/batch/batch.h: journal, --resume, --shard, progress, interrupts), computed together by
// run_scene, which shares launches between a pair's distances; Ctrl-C or SIGTERM stops after the
// current launch round with every finished row kept.
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>

#include "host/analysis/profiles.h"
#include "host/base/errors.h"
#include "host/base/interrupt.h"
#include "host/base/json_number.h"
#include "host/batch/batch.h"
#include "host/cli/commands.h"
#include "host/cli/record_batch.h"
#include "host/cli/scene_options.h"
#include "host/model/profile.h"
#include "host/mts/mts_run.h"
#include "host/mts/row_json.h"
#include "host/output/json_header.h"
#include "host/output/output_guard.h"
#include "host/output/progress.h"
#include "host/output/report.h"
#include "host/output/text_table.h"
#include "host/render/render_run.h"

namespace depthprec::cli {

namespace {

const char* const kMtsUnits = "rows (k = pair index x distances + distance index)";

struct MtsOptions {
  SceneOptions scene;
  OutputOptions out;
  BatchOptions batch;
  bool attribute = false;
  int jobs = RunControl{}.jobs;
  bool render = false;  // probes decided by the system's OpenGL, not the emulator
  std::string gl_device = GlDeviceChoice{}.text;
  std::vector<std::string> profiles;  // --profiles: the spread between implementation profiles
};

void add_profiles_option(CLI::App* cmd, MtsOptions& o) {
  cmd->add_option("--profiles", o.profiles,
                  "Compare implementation profiles (" + profile_names() +
                      "): each pair's MTS under every one named, and the spread (largest over "
                      "smallest), to see where the answer depends on the rasterizer")
      ->delimiter(',');
}

// --profiles: a record batch of one record per pair (host/analysis/profiles.h), so it journals,
// resumes, shards and merges as the other record batches do.
void run_profiles(const MtsOptions& o, const GlobalOptions& global, bool wide) {
  if (!o.scene.profile.empty())
    throw Error(ExitCode::usage,
                "--profile and --profiles: give --profiles alone (it runs each profile named)");
  if (o.attribute) throw Error(ExitCode::usage, "--attribute does not combine with --profiles");
  if (o.profiles.size() < 2)
    throw Error(ExitCode::usage,
                fmt::format("--profiles: name two or more of {}", profile_names()));
  std::vector<ProfiledScene> scenes;
  nlohmann::json settings = nlohmann::json::object();
  for (const std::string& name : o.profiles) {
    for (const auto& s : scenes)
      if (s.profile == name)
        throw Error(ExitCode::usage, fmt::format("--profiles: '{}' is named twice", name));
    SceneOptions so = o.scene;
    so.profile = name;
    scenes.push_back({name, so.load()});
    settings[name] = profile(name).sets;
  }
  const Scene& scene = scenes.front().scene;
  check_writable(o.out.output);
  run_record_batch(
      "profiles", o.out, o.batch, global,
      [&](OpenClRuntime& rt, nlohmann::json& header) {
        header["scene"] = scene.json;
        header["scene_name"] = scene.name;
        header["profiles"] = o.profiles;
        header["profile_settings"] = settings;
        header["layout"] = wide ? "table" : "mts";
        return pair_units(scene, [&rt, &scenes](const EvalPair& pair) {
          return profiles_record(rt, scenes, pair);
        });
      },
      render_profiles_output);
}

void add_jobs_option(CLI::App* cmd, MtsOptions& o) {
  cmd->add_option(
         "--jobs", o.jobs,
         "Pairs evaluated side by side, each by its own host thread and OpenCL queue, so the "
         "device's cores stay busy while one pair waits between launches; they share the plane-A "
         "cache's memory, and with fewer pairs than jobs a pair's distances are split between "
         "them. The rows are the same for any value; measured times include the other "
         "pairs' share of the device, so use 1 to time rows alone")
      ->check(CLI::Range(1, 64))
      ->capture_default_str();
}

void add_attribute_flag(CLI::App* cmd, MtsOptions& o) {
  cmd->add_flag(
      "--attribute", o.attribute,
      "Attribute each MTS: also the storage-limited MTS (the pipeline exact up to binary64, "
      "then stored), the arithmetic-limited MTS (binary32 pipeline, no storage quantisation), "
      "next to the vertex bound, and the dominant factor (docs/stability.md). About 2-3x the work");
}

// Rows that left kernel pixels uncovered (at some orientation the planes do not reach them, so
// nothing was compared there) say why and what covers them: said once, not left to the flags.
void note_uncovered(const Scene& scene, const std::vector<MtsRow>& rows) {
  const auto n =
      std::count_if(rows.begin(), rows.end(), [](const MtsRow& r) { return r.uncovered; });
  if (n == 0) return;
  fmt::print(stderr,
             "depthprec: note: {} of {} rows left kernel pixels uncovered (flag uncovered): at "
             "some orientation within {} degrees the planes, {} times the view's height "
             "(plane_margin), do not reach every kernel pixel, and nothing is compared there; a "
             "larger plane_margin (--set plane_margin=...) or a smaller --kernel covers them\n",
             n, rows.size(), human(scene.rotation_range_deg), human(scene.plane_margin));
}

void run(const MtsOptions& o, const GlobalOptions& global, bool wide) {
  check_output_spares_inputs("-o", o.out.output, {{"the scene file", o.scene.scene_file}});
  if (!o.profiles.empty()) return run_profiles(o, global, wide);
  const Scene scene = o.scene.load();
  check_writable(o.out.output);
  const Shard shard = Shard::parse(o.batch.shard);
  const std::string kind = wide ? "table" : "mts";
  // The journal belongs to this command, scene, version and shard: rows of another run must not
  // be resumed into this one.
  nlohmann::json identity = journal_identity(output_header(o.render ? "render" : kind, ""));
  identity["scene"] = scene.json;
  identity["attribute"] = o.attribute;
  identity["shard"] = o.batch.shard;
  RowJournal journal(o.out.output, o.batch.resume, identity);
  const SceneRows units = scene_rows(scene);
  // The backend: the emulator on the OpenCL device, or the system's OpenGL; a rendered run
  // checks every pair's depth buffer before it starts.
  std::optional<OpenClRuntime> rt;
  std::optional<GlContext> gl;
  RunInfo info;
  if (o.render) {
    gl.emplace(GlDeviceChoice::parse(o.gl_device));
    info.device = gl->description();
    info.rendered = {gl->renderer(), gl->version(), gl->platform(), check_scene_renders(scene)};
  } else {
    rt.emplace(global.device);
    info.device = rt->description();
  }
  const auto log = [&global](const std::string& line) {
    if (global.verbose) fmt::print(stderr, "{}\n", line);
  };
  const auto render = [&](std::vector<MtsRow> rows, RunInfo info) {
    sort_rows(scene, rows);
    info.fragment_pairs = 0;
    for (const auto& r : rows) info.fragment_pairs += r.fragment_pairs;
    if (!o.render) info.variants = scene_variants(scene);
    info.timing = !o.out.no_timing;
    info.kind = kind;
    return wide ? render_table(scene, rows, info, o.out.format_out)
                : render_rows(scene, rows, info, o.out.format_out);
  };
  const auto to_rows = [](const std::vector<nlohmann::json>& records) {
    std::vector<MtsRow> rows;
    for (const auto& r : records) rows.push_back(row_from_json(r));
    return rows;
  };
  // All units of the batch are computed together: run_scene shares launches between a pair's
  // distances and runs pairs side by side; it stops between launch rounds on an interrupt.
  const BulkCompute compute = [&](const std::vector<size_t>& todo, const Emit& emit) {
    RunControl control = control_for(units, todo, interrupt_requested);
    control.attribute = o.attribute;
    control.jobs = o.jobs;
    control.on_row = [&](const MtsRow& r) {
      emit(units.index_of.at(row_key(r.pair, r.z)), row_to_json(r, true));
    };
    const RenderedWith with = info.rendered;
    info = o.render ? render_scene(*gl, scene, log, control).info
                    : run_scene(*rt, scene, log, control).info;
    info.rendered = with;
  };
  const auto records =
      run_batch(units.keys, compute, journal, shard, kind, !global.quiet && stderr_is_terminal(),
                [&](const std::vector<nlohmann::json>& done) {
                  write_output("", render(to_rows(done), info));
                });
  info.shard = o.batch.shard;
  note_uncovered(scene, to_rows(records));
  write_batch_output(journal, o.out.output, render(to_rows(records), info));
}

}  // namespace

std::string render_profiles_output(const nlohmann::json& header,
                                   const std::vector<nlohmann::json>& records,
                                   const OutputOptions& out) {
  if (out.format_out == "json") return records_json(header, records, !out.no_timing);
  const bool csv = out.format_out == "csv";
  const auto names = header.at("profiles").get<std::vector<std::string>>();
  // A profile's cell: its MTS, or (text) the verdict that replaces it; CSV keeps numbers apart.
  const auto cell = [&](const nlohmann::json& row, const std::string& p) -> std::string {
    const nlohmann::json& v = row.at("mts").at(p);
    if (!v.is_null()) return number_cell(number_from_json(v, "mts"), out.format_out);
    return csv ? "" : row.at("verdict").at(p).get<std::string>();
  };
  const auto spread = [&](const nlohmann::json& row) -> std::string {
    return row.at("spread").is_null()
               ? (csv ? "" : "-")
               : number_cell(row.at("spread").get<double>(), out.format_out, "{:.3f}");
  };
  const std::string caption = fmt::format(
      "MTS under each implementation profile ({}; scene {}) and the spread, the largest over the "
      "smallest: 1 where the format and technique decide the answer, above 1 where the "
      "rasterizer's arithmetic does. '-': a profile has no number there",
      fmt::join(names, ", "), header.value("scene_name", std::string("?")));
  std::vector<Column> cols;
  Cells cells;
  if (header.value("layout", std::string("mts")) == "mts") {
    cols = {{"technique", true}, {"format", true}, {"depth_range", true}, {"z"}};
    for (const auto& p : names) cols.push_back({p});
    cols.push_back({"spread"});
    if (csv)
      for (const auto& p : names) cols.push_back({p + " verdict", true});
    for (const auto& rec : records)
      for (const auto& row : rec.at("rows")) {
        std::vector<std::string> line = {rec.at("technique").get<std::string>(),
                                         rec.at("format").get<std::string>(),
                                         rec.at("depth_range").get<std::string>(),
                                         number_cell(row.at("z").get<double>(), out.format_out)};
        for (const auto& p : names) line.push_back(cell(row, p));
        line.push_back(spread(row));
        if (csv)
          for (const auto& p : names) line.push_back(row.at("verdict").at(p).get<std::string>());
        cells.push_back(line);
      }
    return captioned(caption, cols, cells, out.format_out);
  }
  // The wide layout: one row per distance, per pair a column per profile and its spread.
  cols = {{"z"}};
  for (const auto& rec : records) {
    const std::string pair = pair_label(rec);
    for (const auto& p : names) cols.push_back({pair + " " + p});
    cols.push_back({pair + " spread"});
  }
  const size_t n = records.empty() ? 0 : records.front().at("rows").size();
  for (size_t k = 0; k < n; ++k) {
    std::vector<std::string> line = {
        number_cell(records.front().at("rows")[k].at("z").get<double>(), out.format_out)};
    for (const auto& rec : records) {
      const nlohmann::json& row = rec.at("rows")[k];
      for (const auto& p : names) line.push_back(cell(row, p));
      line.push_back(spread(row));
    }
    cells.push_back(line);
  }
  return captioned(caption, cols, cells, out.format_out);
}

void add_gl_device_option(CLI::App* cmd, std::string& choice) {
  cmd->add_option("--gl-device", choice,
                  "The EGL display to render on: auto (Mesa's surfaceless platform when the EGL "
                  "client offers it, else the first EGL device), surfaceless, or device:N (the "
                  "N-th EGL device, from 0, e.g. a GPU's)")
      ->capture_default_str();
}

void add_mts_commands(CLI::App& app, GlobalOptions& global) {
  auto mts = std::make_shared<MtsOptions>();
  auto* cmd = app.add_subcommand(
      "mts",
      "Minimum triangle separation (Gilg et al. 2021, docs/spec.md 5): per technique, storage "
      "format,\n"
      "depth range and distance z, the smallest separation s of two planes at z and fl32(z+s)\n"
      "for which the farther plane never wins the depth test, found by the host's bisection\n"
      "over an emulated binary32 pipeline. One line per (pair, distance) with the bracket,\n"
      "the vertex-precision bound, work done and flags. The MTS is the worst case over the\n"
      "orientations the scene allows (mts_paper: the paper's 100 frames alone; orientations and\n"
      "convergence: what it rests on; docs/mts.md, \"The worst case\"). Beside it, mts_bound:\n"
      "the guaranteed MTS, at and above which no orientation and no implementation of the\n"
      "scene's bound_model (binary32: every profile's choices) fights, and bound_by, the error\n"
      "term that weighs most (docs/bound.md).\n"
      "Examples:\n"
      "  depthprec mts -t reversed -f float32 --depth-range zero_to_one --distances 2,1024,1e6\n"
      "  depthprec mts -t standard -f unorm24 --distances 512 --set bound_model=d3d11\n"
      "  depthprec mts -t linear -f float32 --distances 16384 --set sampling=paper\n"
      "  depthprec mts -t standard,linear -f unorm24 --kernel 50x50 --frames 20\n"
      "  depthprec mts data/gilg2021.json -t standard --distances 512 --set pipeline.divide=exact "
      "--format-out csv\n"
      "      (a scene file: the default's own, installed in /usr/share/depthprec/scenes)");
  mts->scene.add_to(*cmd, true);
  mts->out.add_to(*cmd);
  mts->batch.add_to(*cmd, kMtsUnits);
  add_attribute_flag(cmd, *mts);
  add_jobs_option(cmd, *mts);
  add_profiles_option(cmd, *mts);
  cmd->callback([mts, &global]() { run(*mts, global, false); });

  auto table = std::make_shared<MtsOptions>();
  auto* tcmd = app.add_subcommand(
      "table",
      "The batch precision table: every pair of the scene (default: Gilg et al.'s 7 techniques\n"
      "x float32, unorm24), one row per distance, one column per pair, the vertex bound\n"
      "alongside. inf = unresolvable; * = flagged (the flags are listed under the table).\n"
      "Finished rows survive Ctrl-C: with -o FILE they are journaled to FILE.rows.jsonl, and\n"
      "--resume continues; --shard i/N splits a batch over machines, `merge` joins the parts.\n"
      "Examples:\n"
      "  depthprec table\n"
      "  depthprec table --set sampling=paper --no-timing --format-out markdown -o paper.md\n"
      "  depthprec table --shard 1/4 --format-out json -o part1.json   (then merge part*.json)");
  table->scene.add_to(*tcmd, true);
  table->out.add_to(*tcmd);
  table->batch.add_to(*tcmd, kMtsUnits);
  add_attribute_flag(tcmd, *table);
  add_jobs_option(tcmd, *table);
  add_profiles_option(tcmd, *table);
  tcmd->callback([table, &global]() { run(*table, global, true); });

  auto render = std::make_shared<MtsOptions>();
  render->render = true;
  auto* rcmd = app.add_subcommand(
      "render",
      "The MTS measurement done by rendering, as Gilg et al. did it: the same search, scene and\n"
      "rows as `mts`, each probe decided by drawing plane A then plane B through the system's\n"
      "OpenGL 4.5 (headless EGL) and reading the kernel back from the colour buffer. Ground\n"
      "truth for the emulation on this machine's rasterizer (Mesa llvmpipe without a GPU);\n"
      "`compare` puts both side by side. Storage: the driver's depth buffers (unorm16,\n"
      "unorm24, unorm32, float32 where it stores them exactly); the divide, rounding,\n"
      "denormals and contraction are the driver's (docs/validation.md).\n"
      "Examples:\n"
      "  depthprec render -t standard -f unorm24 --distances 16,1024 --frames 20\n"
      "  depthprec render --format-out json -o rendered.json      (the default scene, minutes)\n"
      "  LIBGL_ALWAYS_SOFTWARE=1 depthprec render ...             (llvmpipe on a GPU machine)\n"
      "  GALLIUM_DRIVER=softpipe MESA_GL_VERSION_OVERRIDE=4.5 MESA_GLSL_VERSION_OVERRIDE=450\n"
      "    depthprec compare --profile softpipe ...               (Mesa's softpipe, emulated\n"
      "                                                            with its profile)");
  render->scene.add_to(*rcmd, true);
  render->out.add_to(*rcmd);
  render->batch.add_to(*rcmd, kMtsUnits);
  add_gl_device_option(rcmd, render->gl_device);
  rcmd->callback([render, &global]() { run(*render, global, false); });
}

}  // namespace depthprec::cli
