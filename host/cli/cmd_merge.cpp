// merge: joins the JSON outputs of a batch's shards (--shard i/N --format-out json) into the
// output one whole run would have written.
#include <fmt/format.h>

#include <fstream>
#include <map>
#include <nlohmann/json.hpp>

#include "host/base/errors.h"
#include "host/base/read_file.h"
#include "host/batch/batch.h"
#include "host/cli/commands.h"
#include "host/cli/record_batch.h"
#include "host/cli/scene_options.h"
#include "host/mts/mts_run.h"
#include "host/mts/row_json.h"
#include "host/output/output_guard.h"
#include "host/output/text_table.h"

namespace depthprec::cli {

namespace {

struct MergeOptions {
  std::vector<std::string> files;
  OutputOptions out;
};

nlohmann::json read_json(const std::string& f) {
  std::string text;
  try {
    text = read_input_file(f, "shard");
  } catch (const InputError& e) {
    throw InputError(fmt::format("merge: {}", e.what()));
  }
  auto j = nlohmann::json::parse(text, nullptr, false);
  if (j.is_discarded() || !j.is_object())
    throw InputError(
        fmt::format("merge: '{}' is not a JSON output of a batch command (--format-out json)", f));
  return j;
}

// Each file's shard ("i/N" in its header; none: the whole batch, 1/1), checked to be the N parts
// of one batch, each once: a missing or repeated part would merge into a table with rows
// silently absent. Returns the shard index (1-based) of each file.
std::vector<int> check_shards(const MergeOptions& o, const std::vector<nlohmann::json>& docs) {
  std::vector<int> index(docs.size());
  std::map<int, std::string> seen;  // shard index -> file
  int count = 0;
  for (size_t k = 0; k < docs.size(); ++k) {
    const std::string& f = o.files[k];
    const std::string shard = docs[k].value("shard", "1/1");
    Shard part;
    try {
      part = Shard::parse(shard);
    } catch (const Error&) {
      throw InputError(fmt::format("merge: '{}' has a bad shard '{}'", f, shard));
    }
    if (k == 0)
      count = part.count;
    else if (part.count != count)
      throw InputError(fmt::format("merge: '{}' is shard {} but '{}' is one of {} shards", f, shard,
                                   o.files.front(), count));
    index[k] = part.index + 1;
    const auto [it, fresh] = seen.emplace(index[k], f);
    if (!fresh)
      throw InputError(
          fmt::format("merge: shard {} given twice ('{}' and '{}')", shard, it->second, f));
  }
  for (int i = 1; i <= count; ++i)
    if (!seen.count(i))
      throw InputError(fmt::format("merge: shard {}/{} is missing (given {} of {})", i, count,
                                   seen.size(), count));
  return index;
}

void merge_rows(const MergeOptions& o, const std::vector<nlohmann::json>& docs) {
  check_shards(o, docs);
  nlohmann::json scene_json;
  std::string kind, device, source;
  RenderedWith rendered;
  std::map<std::string, MtsRow> rows;
  for (size_t k = 0; k < docs.size(); ++k) {
    const std::string& f = o.files[k];
    const nlohmann::json& j = docs[k];
    if (!j.contains("rows") || !j.contains("scene"))
      throw InputError(fmt::format(
          "merge: '{}' is no JSON output merge joins (--format-out json of mts, table, "
          "render, compare, lj-table, tradeoff, cost, pipelines, advise, world or bias)",
          f));
    if (scene_json.is_null()) {
      scene_json = j["scene"];
      kind = j.value("kind", "mts");
      device = j.value("device", "");
      source = j.value("scene_source", "merged shards");
      if (j.contains("gl_renderer"))  // shards of `render`: what rendered them
        rendered = {j["gl_renderer"].get<std::string>(), j.value("gl_version", ""),
                    j.value("egl_platform", ""),
                    j.value("depth_buffers", std::map<std::string, std::string>{})};
    }
    // Shards of one batch: the same program version, command, scene and renderer.
    const auto identity = [](const nlohmann::json& d) {
      nlohmann::json id = {{"version", d.value("version", "")},
                           {"kind", d.value("kind", "mts")},
                           {"scene", d["scene"]}};
      if (d.contains("gl_renderer")) id["gl_renderer"] = d["gl_renderer"];
      return id;
    };
    const std::string diff = first_difference(identity(docs.front()), identity(j));
    if (!diff.empty()) {
      throw InputError(
          fmt::format("merge: '{}' is not a shard of the batch '{}' is ({}: the "
                      "first file's value, then this one's)",
                      f, o.files.front(), diff));
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
  info.rendered = rendered;
  if (rendered.empty()) info.variants = scene_variants(scene);
  info.timing = !o.out.no_timing;
  info.kind = kind;
  for (const auto& r : all) info.fragment_pairs += r.fragment_pairs;
  const std::string text = kind == "table" ? render_table(scene, all, info, o.out.format_out)
                                           : render_rows(scene, all, info, o.out.format_out);
  write_output(o.out.output, text);
}

// The record batches merge joins: how each renders, and what its JSON derives from the records
// (records_json's `derived`), which merge derives again rather than compares between shards.
struct RecordKind {
  RecordRenderer render;
  std::vector<std::string> derived;
};
const std::map<std::string, RecordKind>& record_kinds() {
  static const std::map<std::string, RecordKind> kinds = {
      {"lj-table", {render_lj_table_output, {}}},
      {"tradeoff", {render_tradeoff_output, {"levels"}}},
      {"cost", {render_cost_output, {}}},
      {"pipelines", {render_pipelines_output, {"summary"}}},
      {"compare", {render_compare_output, {"summary", "pairs"}}},
      {"advise", {render_advise_output, {"ranking"}}},
      {"world", {render_world_output, {}}},
      {"bias", {render_bias_output, {}}},
      {"profiles", {render_profiles_output, {}}}};
  return kinds;
}

// Shard i/N holds the units k = i - 1, i - 1 + N, ... in order, so the whole batch's records
// interleave the shards'.
void merge_records(const MergeOptions& o, const std::string& kind,
                   const std::vector<nlohmann::json>& docs) {
  const RecordKind& batch = record_kinds().at(kind);
  std::map<int, std::vector<nlohmann::json>> parts;  // shard index -> records
  nlohmann::json header;
  for (size_t k = 0; k < docs.size(); ++k) {
    const nlohmann::json& j = docs[k];
    if (j.value("kind", "") != kind || !j.contains("records"))
      throw InputError(
          fmt::format("merge: '{}' is not a {} output (--format-out json)", o.files[k], kind));
  }
  const std::vector<int> index = check_shards(o, docs);
  const int count = static_cast<int>(docs.size());
  for (size_t k = 0; k < docs.size(); ++k) {
    const nlohmann::json& j = docs[k];
    nlohmann::json h = j;
    // What the records derive is derived again; times measured by one shard's process do not
    // describe the merged batch.
    std::vector<std::string> drop = {"records", "shard", "device", "emulated_seconds",
                                     "rendered_seconds"};
    drop.insert(drop.end(), batch.derived.begin(), batch.derived.end());
    for (const auto& key : drop) h.erase(key);
    if (header.is_null()) {
      header = h;
      header["device"] = j.value("device", "");
    } else {
      nlohmann::json mine = header;
      mine.erase("device");
      if (h != mine)
        throw InputError(fmt::format(
            "merge: '{}' is not a shard of the batch '{}' is ({}: the first file's value, then "
            "this one's)",
            o.files[k], o.files.front(), first_difference(mine, h)));
    }
    parts[index[k]] = j["records"].get<std::vector<nlohmann::json>>();
  }
  std::vector<nlohmann::json> records;
  for (size_t pos = 0;; ++pos) {
    bool any = false;
    for (int i = 1; i <= count; ++i)
      if (pos < parts[i].size()) {
        records.push_back(parts[i][pos]);
        any = true;
      }
    if (!any) break;
  }
  write_output(o.out.output, for_terminal(batch.render(header, records, o.out), o.out.format_out));
}

void run_merge(const MergeOptions& o) {
  if (o.files.empty()) throw Error(ExitCode::usage, "merge: name the JSON outputs of the shards");
  std::vector<NamedInput> inputs;
  for (const auto& f : o.files) inputs.push_back({"one of the files to merge", f});
  check_output_spares_inputs("-o", o.out.output, inputs);
  check_writable(o.out.output);
  std::vector<nlohmann::json> docs;
  for (const auto& f : o.files) docs.push_back(read_json(f));
  const std::string kind = docs.front().value("kind", "mts");
  if (record_kinds().count(kind))
    merge_records(o, kind, docs);
  else
    merge_rows(o, docs);
}

}  // namespace

void add_merge_command(CLI::App& app) {
  auto merge = std::make_shared<MergeOptions>();
  auto* mcmd = app.add_subcommand(
      "merge",
      "Join the JSON outputs of the shards of a batch (--shard i/N --format-out json) into the\n"
      "output one whole run would write, in any --format-out: the shards of `mts`, `table`,\n"
      "`render`, `compare`, `lj-table`, `tradeoff`, `cost`, `pipelines`, `advise`, `world`,\n"
      "`bias`, and of `mts --profiles` and `table --profiles`.\n"
      "Example:\n"
      "  depthprec merge part1.json part2.json part3.json part4.json --format-out markdown");
  mcmd->add_option("files", merge->files, "JSON outputs of the shards")->required();
  merge->out.add_to(*mcmd);
  mcmd->callback([merge]() {
    // Files a user or a crashed run hands merge may hold any JSON: a field of the wrong type is
    // bad input, never an internal error.
    try {
      run_merge(*merge);
    } catch (const nlohmann::json::exception& e) {
      throw InputError(
          fmt::format("merge: a file is not a JSON output it can merge: {}", e.what()));
    }
  });
}

}  // namespace depthprec::cli
