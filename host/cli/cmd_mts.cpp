// mts, table and merge. Batch runs keep every finished row: with --output, each row is appended
// to FILE.rows.jsonl (flushed) as it finishes; Ctrl-C or SIGTERM stops after the current launch
// round; --resume continues from the journal; the final file replaces atomically and the journal
// goes. --shard i/N computes a deterministic part; merge joins the parts' JSON outputs.
#include <fmt/format.h>

#include <cstdio>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>

#include "host/cli/commands.h"
#include "host/cli/scene_options.h"
#include "host/errors.h"
#include "host/interrupt.h"
#include "host/mts_run.h"
#include "host/progress.h"
#include "host/row_json.h"

namespace depthprec::cli {

namespace {

struct MtsOptions {
  SceneOptions scene;
  OutputOptions out;
  bool resume = false;
  std::string shard;
};

std::string journal_path(const std::string& output) { return output + ".rows.jsonl"; }

std::vector<MtsRow> read_journal(const std::string& path) {
  std::vector<MtsRow> rows;
  std::ifstream in(path);
  std::string line;
  int number = 0;
  while (std::getline(in, line)) {
    ++number;
    if (line.empty()) continue;
    const auto j = nlohmann::json::parse(line, nullptr, false);
    if (j.is_discarded()) {
      // a line cut short by a kill: everything before it is whole
      fmt::print(stderr, "depthprec: {}:{}: incomplete row left out (it will be recomputed)\n", path, number);
      break;
    }
    rows.push_back(row_from_json(j));
  }
  return rows;
}

void parse_shard(const std::string& s, int& index, int& count) {
  int i = 0, n = 0;
  char tail = 0;
  if (std::sscanf(s.c_str(), "%d/%d%c", &i, &n, &tail) != 2 || n < 1 || i < 1 || i > n)
    throw Error(ExitCode::usage, fmt::format("--shard '{}': expected i/N with 1 <= i <= N, e.g. 2/8", s));
  index = i - 1;
  count = n;
}

void run(const MtsOptions& o, const GlobalOptions& global, bool wide) {
  const Scene scene = o.scene.load();
  check_writable(o.out.output);
  RunControl control;
  if (!o.shard.empty()) parse_shard(o.shard, control.shard_index, control.shard_count);
  std::vector<MtsRow> earlier;
  std::unique_ptr<std::ofstream> journal;
  std::string jpath;
  if (!o.out.output.empty()) {
    jpath = journal_path(o.out.output);
    const bool exists = std::ifstream(jpath).good();
    if (o.resume) {
      if (exists) earlier = read_journal(jpath);
      for (const auto& r : earlier) control.done.insert(row_key(r.pair, r.z));
    } else if (exists) {
      throw Error(ExitCode::output,
                  fmt::format("{} holds the finished rows of an interrupted run: continue it with "
                              "--resume, or delete it to start over",
                              jpath));
    }
    journal = std::make_unique<std::ofstream>(jpath, std::ios::app);
    if (!*journal) throw OutputError(fmt::format("cannot write the row journal '{}'", jpath));
    control.on_row = [&journal](const MtsRow& r) {
      *journal << row_to_json(r, true).dump() << '\n';
      journal->flush();
    };
  } else if (o.resume) {
    throw Error(ExitCode::usage, "--resume needs --output FILE: the journal of finished rows lives beside it");
  }
  std::vector<MtsRow> finished = earlier;
  size_t total = 0;
  for (size_t k = 0; k < scene.evaluate.size() * scene.distances.size(); ++k)
    if (static_cast<int>(k % static_cast<size_t>(control.shard_count)) == control.shard_index) ++total;
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
    if (journal)
      throw Error(ExitCode::interrupted,
                  fmt::format("interrupted: {} finished rows kept in {}; the same command with "
                              "--resume continues",
                              finished.size(), jpath));
    sort_rows(scene, finished);
    RunInfo partial;
    partial.device = rt.description();
    partial.variants = scene_variants(scene);
    partial.timing = !o.out.no_timing;
    partial.kind = wide ? "table" : "mts";
    write_output("", wide ? render_table(scene, finished, partial, o.out.format_out)
                          : render_rows(scene, finished, partial, o.out.format_out));
    throw Error(ExitCode::interrupted,
                fmt::format("interrupted: the {} finished rows are above", finished.size()));
  }
  std::vector<MtsRow> rows = earlier;
  rows.insert(rows.end(), result.rows.begin(), result.rows.end());
  sort_rows(scene, rows);
  result.info.fragment_pairs = 0;
  for (const auto& r : rows) result.info.fragment_pairs += r.fragment_pairs;
  result.info.timing = !o.out.no_timing;
  result.info.kind = wide ? "table" : "mts";
  result.info.shard = o.shard;
  const std::string text = wide ? render_table(scene, rows, result.info, o.out.format_out)
                                : render_rows(scene, rows, result.info, o.out.format_out);
  write_output(o.out.output, text);
  if (journal) {
    journal.reset();
    std::remove(jpath.c_str());
  }
}

struct MergeOptions {
  std::vector<std::string> files;
  OutputOptions out;
};

void run_merge(const MergeOptions& o) {
  if (o.files.empty()) throw Error(ExitCode::usage, "merge: name the JSON outputs of the shards");
  check_writable(o.out.output);
  nlohmann::json scene_json;
  std::string kind, device, source;
  std::map<std::string, MtsRow> rows;
  for (const auto& f : o.files) {
    std::ifstream in(f);
    if (!in) throw InputError(fmt::format("merge: cannot read '{}'", f));
    const auto j = nlohmann::json::parse(in, nullptr, false);
    if (j.is_discarded() || !j.is_object() || !j.contains("rows") || !j.contains("scene"))
      throw InputError(fmt::format("merge: '{}' is not a JSON output of mts or table (--format-out json)", f));
    if (scene_json.is_null()) {
      scene_json = j["scene"];
      kind = j.value("kind", "mts");
      device = j.value("device", "");
      source = j.value("scene_source", "merged shards");
    } else if (j["scene"] != scene_json) {
      throw InputError(fmt::format("merge: '{}' ran another scene than '{}'", f, o.files.front()));
    }
    for (const auto& r : j["rows"]) {
      MtsRow row = row_from_json(r);
      const std::string key = row_key(row.pair, row.z);
      if (rows.count(key) && row_to_json(rows[key], false) != row_to_json(row, false))
        throw InputError(fmt::format("merge: '{}' disagrees with an earlier file on {}", f, key));
      rows[key] = row;
    }
  }
  const Scene scene = scene_from_json(scene_json, source);
  std::vector<MtsRow> all;
  for (auto& [k, r] : rows) all.push_back(r);
  sort_rows(scene, all);
  RunInfo info;
  info.device = device;
  info.variants = scene_variants(scene);
  info.timing = !o.out.no_timing;
  info.kind = kind;
  for (const auto& r : all) info.fragment_pairs += r.fragment_pairs;
  const std::string text = kind == "table" ? render_table(scene, all, info, o.out.format_out)
                                           : render_rows(scene, all, info, o.out.format_out);
  write_output(o.out.output, text);
}

void add_batch_options(CLI::App* cmd, MtsOptions& o) {
  cmd->add_flag("--resume", o.resume,
                "Continue an interrupted run: rows in FILE.rows.jsonl (beside --output FILE) are kept, "
                "the rest computed");
  cmd->add_option("--shard", o.shard,
                  "Compute part i of N (i/N): rows k with k mod N = i - 1, k = pair index x distances + "
                  "distance index. Join the parts' JSON outputs with `depthprec merge`");
}

}  // namespace

void add_mts_commands(CLI::App& app, GlobalOptions& global) {
  auto mts = std::make_shared<MtsOptions>();
  auto* cmd = app.add_subcommand(
      "mts",
      "Minimum triangle separation (Gilg et al. 2021, SPEC 5): per technique, storage format,\n"
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
  add_batch_options(cmd, *mts);
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
  add_batch_options(tcmd, *table);
  tcmd->callback([table, &global]() { run(*table, global, true); });

  auto merge = std::make_shared<MergeOptions>();
  auto* mcmd = app.add_subcommand(
      "merge",
      "Join the JSON outputs of `mts` or `table` shards (--shard i/N --format-out json) of one\n"
      "scene into one output, rows in scene order.\n"
      "Example:\n"
      "  depthprec merge part1.json part2.json part3.json part4.json --format-out markdown");
  mcmd->add_option("files", merge->files, "JSON outputs of the shards")->required();
  merge->out.add_to(*mcmd);
  mcmd->callback([merge]() { run_merge(*merge); });
}

}  // namespace depthprec::cli
