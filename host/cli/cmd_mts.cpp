// mts and table. Batch runs keep every finished row: with --output, each row is appended
// to FILE.rows.jsonl (flushed) as it finishes; Ctrl-C or SIGTERM stops after the current launch
// round; --resume continues from the journal; the final file replaces atomically and the journal
// goes. --shard i/N computes a deterministic part; merge joins the parts' JSON outputs.
#include <fmt/format.h>

#include <cstdio>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>

#include "host/base/errors.h"
#include "host/base/interrupt.h"
#include "host/batch/batch.h"
#include "host/cli/commands.h"
#include "host/cli/scene_options.h"
#include "host/mts/mts_run.h"
#include "host/output/progress.h"
#include "host/output/row_json.h"

namespace depthprec::cli {

namespace {

const char* const kMtsUnits = "rows (k = pair index x distances + distance index)";

struct MtsOptions {
  SceneOptions scene;
  OutputOptions out;
  BatchOptions batch;
  bool attribute = false;
  int jobs = RunControl{}.jobs;
};

void add_jobs_option(CLI::App* cmd, MtsOptions& o) {
  cmd->add_option(
         "--jobs", o.jobs,
         "Pairs evaluated side by side, each by its own host thread and OpenCL queue, so the "
         "device's cores stay busy while one pair waits between launches. The rows are the same "
         "for any value; measured times include the other pairs' share of the device, so use 1 "
         "to time rows alone. --attribute always runs one")
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

void run(const MtsOptions& o, const GlobalOptions& global, bool wide) {
  const Scene scene = o.scene.load();
  check_writable(o.out.output);
  RunControl control;
  const Shard shard = Shard::parse(o.batch.shard);
  control.shard_index = shard.index;
  control.shard_count = shard.count;
  control.attribute = o.attribute;
  control.jobs = o.jobs;
  RowJournal journal(o.out.output, o.batch.resume);
  std::vector<MtsRow> earlier;
  for (const auto& j : journal.earlier()) {
    earlier.push_back(row_from_json(j));
    control.done.insert(row_key(earlier.back().pair, earlier.back().z));
  }
  if (journal.active())
    control.on_row = [&journal](const MtsRow& r) { journal.append(row_to_json(r, true)); };
  std::vector<MtsRow> finished = earlier;
  size_t total = 0;
  for (size_t k = 0; k < scene.evaluate.size() * scene.distances.size(); ++k)
    if (static_cast<int>(k % static_cast<size_t>(control.shard_count)) == control.shard_index)
      ++total;
  Progress progress(wide ? "table" : "mts", total - std::min(total, earlier.size()),
                    !global.quiet && stderr_is_terminal());
  auto journal_write = control.on_row;
  control.on_row = [journal_write, &finished, &progress](const MtsRow& r) {
    if (journal_write) journal_write(r);
    finished.push_back(r);
    progress.advance();
  };
  control.stop = interrupt_requested;
  install_interrupt_handlers();

  OpenClRuntime rt(global.device);
  auto log = [&global](const std::string& line) {
    if (global.verbose) fmt::print(stderr, "{}\n", line);
  };
  MtsRun result;
  try {
    result = run_scene(rt, scene, log, control);
  } catch (const Error& e) {
    if (e.code() != ExitCode::interrupted) throw;
    if (journal.active()) throw_interrupted(journal, finished.size());
    sort_rows(scene, finished);
    RunInfo partial;
    partial.device = rt.description();
    partial.variants = scene_variants(scene);
    partial.timing = !o.out.no_timing;
    partial.kind = wide ? "table" : "mts";
    write_output("", wide ? render_table(scene, finished, partial, o.out.format_out)
                          : render_rows(scene, finished, partial, o.out.format_out));
    throw_interrupted(journal, finished.size());
  }
  std::vector<MtsRow> rows = earlier;
  rows.insert(rows.end(), result.rows.begin(), result.rows.end());
  sort_rows(scene, rows);
  result.info.fragment_pairs = 0;
  for (const auto& r : rows) result.info.fragment_pairs += r.fragment_pairs;
  result.info.timing = !o.out.no_timing;
  result.info.kind = wide ? "table" : "mts";
  result.info.shard = o.batch.shard;
  const std::string text = wide ? render_table(scene, rows, result.info, o.out.format_out)
                                : render_rows(scene, rows, result.info, o.out.format_out);
  write_output(o.out.output, text);
  journal.remove();
}

}  // namespace

void add_mts_commands(CLI::App& app, GlobalOptions& global) {
  auto mts = std::make_shared<MtsOptions>();
  auto* cmd = app.add_subcommand(
      "mts",
      "Minimum triangle separation (Gilg et al. 2021, docs/spec.md 5): per technique, storage "
      "format,\n"
      "depth range and distance z, the smallest separation s of two planes at z and fl32(z+s)\n"
      "for which the farther plane never wins the depth test, found by the host's bisection\n"
      "over an emulated binary32 pipeline. One line per (pair, distance) with the bracket,\n"
      "the vertex-precision bound, work done and flags.\n"
      "Examples:\n"
      "  depthprec mts -t reversed -f float32 --depth-range zero_to_one --distances 2,1024,1e6\n"
      "  depthprec mts -t standard,linear -f unorm24 --kernel 50x50 --frames 20\n"
      "  depthprec mts my_scene.json --set pipeline.divide=exact --format-out csv");
  mts->scene.add_to(*cmd, true);
  mts->out.add_to(*cmd);
  mts->batch.add_to(*cmd, kMtsUnits);
  add_attribute_flag(cmd, *mts);
  add_jobs_option(cmd, *mts);
  cmd->callback([mts, &global]() { run(*mts, global, false); });

  auto table = std::make_shared<MtsOptions>();
  auto* tcmd = app.add_subcommand(
      "table",
      "The batch precision table: every pair of the scene (default: Gilg et al.'s 7 techniques\n"
      "x float32, unorm24), one row per distance, one column per pair, the vertex bound\n"
      "alongside. inf = unresolvable; * = flagged (details with --format-out json).\n"
      "Finished rows survive Ctrl-C: with -o FILE they are journaled to FILE.rows.jsonl, and\n"
      "--resume continues; --shard i/N splits a batch over machines, `merge` joins the parts.\n"
      "Examples:\n"
      "  depthprec table\n"
      "  depthprec table --format-out markdown -o docs/gilg2021-table.md\n"
      "  depthprec table --shard 1/4 --format-out json -o part1.json   (then merge part*.json)");
  table->scene.add_to(*tcmd, true);
  table->out.add_to(*tcmd);
  table->batch.add_to(*tcmd, kMtsUnits);
  add_attribute_flag(tcmd, *table);
  add_jobs_option(tcmd, *table);
  tcmd->callback([table, &global]() { run(*table, global, true); });
}

}  // namespace depthprec::cli
