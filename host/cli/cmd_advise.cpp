// advise: which set-ups meet the separation a scene's content needs, and the smallest near plane
// each affords (host/analysis/advise.h). A record batch: one record per pair, so it journals,
// resumes, shards and merges as cost does.
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

#include "host/analysis/advise.h"
#include "host/analysis/advise_bound.h"
#include "host/base/errors.h"
#include "host/base/json_number.h"
#include "host/cli/commands.h"
#include "host/cli/record_batch.h"
#include "host/cli/scene_options.h"
#include "host/output/output_guard.h"
#include "host/output/report.h"
#include "host/output/text_table.h"

namespace depthprec::cli {

namespace {

struct AdviseOptions {
  SceneOptions scene;
  OutputOptions out;
  BatchOptions batch;
  std::vector<double> range;
  double separation = 0, relative = 0;
};

AdviseRequest request_of(const AdviseOptions& o) {
  if (o.range.size() != 2)
    throw Error(ExitCode::usage, "advise: --range takes the nearest and farthest content: A,B");
  if ((o.separation > 0) == (o.relative > 0) || o.separation < 0 || o.relative < 0)
    throw InputError(
        "advise: give the separation the content needs as --separation S (scene units, > 0) or "
        "--relative R (S = R * z, > 0), exactly one");
  AdviseRequest r;
  r.z_min = o.range[0];
  r.z_max = o.range[1];
  r.relative = o.relative > 0;
  r.separation = r.relative ? o.relative : o.separation;
  return r;
}

// What advise computes rather than reads: the near plane (its answer) and the distances checked
// (those of --range). Given anyway, they would be ignored; refused, so no one believes them used.
void refuse_computed_options(const SceneOptions& s) {
  std::string near = s.near.empty() ? "" : "--near " + s.near, distances;
  if (!s.distances.empty())
    distances = "--distances " + fmt::format("{}", fmt::join(s.distances, ","));
  for (const auto& set : s.sets) {
    if (set.rfind("near=", 0) == 0) near = "--set " + set;
    if (set.rfind("distances=", 0) == 0) distances = "--set " + set;
  }
  if (!near.empty())
    throw Error(ExitCode::usage,
                fmt::format("advise: {}: the near plane is what advise finds (the smallest that "
                            "holds, searched from {} x the nearest content up to it); drop {}",
                            near, human(AdviseRequest{}.near_floor_ratio), near));
  if (!distances.empty())
    throw Error(ExitCode::usage,
                fmt::format("advise: {}: advise checks the distances of --range itself (A, 2A, "
                            "4A, ..., B); drop {}",
                            distances, distances));
}

void run_advise(const AdviseOptions& o, const GlobalOptions& g) {
  refuse_computed_options(o.scene);
  check_output_spares_inputs("-o", o.out.output, {{"the scene file", o.scene.scene_file}});
  const AdviseRequest r = request_of(o);
  const Scene scene = o.scene.load();
  validate(r, scene);
  check_planes_cover_kernel(scene);
  check_writable(o.out.output);
  run_record_batch(
      "advise", o.out, o.batch, g,
      [&scene, &r](OpenClRuntime& rt, nlohmann::json& header) {
        header["scene"] = scene.json;
        header["scene_name"] = scene.name;
        header["content_near"] = r.z_min;
        header["content_far"] = r.z_max;
        header["separation"] = r.separation;
        header["separation_is_relative"] = r.relative;
        header["distances_checked"] = advise_distances(r);
        return pair_units(scene, [&rt, &scene, &r](const EvalPair& pair) {
          // The sampled answer, and beside it the guaranteed MTS's.
          nlohmann::json rec = advise_record(rt, scene, pair, r);
          rec.update(bound_answer(scene, pair, r));
          return rec;
        });
      },
      render_advise_output);
}

}  // namespace

std::string render_advise_output(const nlohmann::json& header,
                                 const std::vector<nlohmann::json>& records,
                                 const OutputOptions& out) {
  // Ranked: the nearest affordable near plane first; set-ups that cannot meet it last.
  std::vector<const nlohmann::json*> ranked;
  for (const auto& r : records) ranked.push_back(&r);
  // Ranked by the near plane the guaranteed MTS allows, then by the sampled one.
  const auto near_of = [](const nlohmann::json* r, const char* key) {
    return r->contains(key) ? r->at(key).get<double>() : INFINITY;
  };
  std::stable_sort(ranked.begin(), ranked.end(), [&](const auto* a, const auto* b) {
    return std::make_pair(near_of(a, "near_bound"), near_of(a, "smallest_near")) <
           std::make_pair(near_of(b, "near_bound"), near_of(b, "smallest_near"));
  });
  if (out.format_out == "json") {
    nlohmann::json ranking = nlohmann::json::array();
    for (const auto* r : ranked) ranking.push_back(pair_label(*r));
    return records_json(header, records, !out.no_timing, {{"ranking", ranking}});
  }
  const bool csv = out.format_out == "csv";
  const std::string none = csv ? "" : "-";
  const auto num = [&](const nlohmann::json& r, const char* k) {
    return r.contains(k) ? number_cell(r.at(k).get<double>(), out.format_out) : none;
  };
  // The far plane's limit: text marks one that holds even at the ceiling with ">=", CSV says so
  // in a column of its own.
  const auto far = [&](const nlohmann::json& r) {
    if (!r.contains("largest_far")) return none;
    const std::string v = num(r, "largest_far");
    return !csv && r.value("far_holds_to_ceiling", false) ? ">= " + v : v;
  };
  const auto far_bound = [&](const nlohmann::json& r) {
    if (!r.contains("far_bound")) return none;
    const std::string v = num(r, "far_bound");
    return !csv && r.value("far_bound_to_ceiling", false) ? ">= " + v : v;
  };
  Cells cells;
  int rank = 1;
  for (const auto* r : ranked) {
    cells.push_back(
        {r->contains("near_bound") || r->contains("smallest_near") ? std::to_string(rank++) : none,
         r->at("technique").get<std::string>(), r->at("format").get<std::string>(),
         r->at("depth_range").get<std::string>(), num(*r, "near_bound"), far_bound(*r),
         num(*r, "smallest_near") + (!csv && r->value("far_tightened", false) ? " *" : ""),
         r->at("holds_from_floor").get<bool>() ? (csv ? "" : "(floor)") : num(*r, "next_near"),
         num(*r, "fails_at"), far(*r), std::to_string(r->at("near_steps").get<int>())});
    if (csv) {
      cells.back().push_back(r->contains("largest_far")
                                 ? (r->value("far_holds_to_ceiling", false) ? "true" : "false")
                                 : "");
      cells.back().push_back(r->value("far_tightened", false) ? "true" : "false");
    }
  }
  std::vector<Column> cols = {
      {"rank"},         {"technique", true}, {"format", true},  {"depth_range", true},
      {"near (bound)"}, {"far (bound)"},     {"smallest near"}, {"next down (fails)"},
      {"fails at z"},   {"largest far"},     {"steps"}};
  if (csv) {
    cols.push_back({"far holds to ceiling", true});
    cols.push_back({"far tightened", true});
  }
  const bool rel = header.value("separation_is_relative", false);
  const double s = header.value("separation", 0.0);
  return captioned(
      fmt::format("Set-ups for content at z from {} to {} that needs a separation of {} (scene "
                  "{}): the smallest near plane each affords -- from it up, planes that far apart "
                  "never fight at any of the {} distances checked (z, 2z, 4z, ..., the farthest); "
                  "the next near down fails at the distance named. (floor): even near = {} x the "
                  "nearest content holds; '-': not even a near plane next to the content does. "
                  "largest far: with that near plane, the farthest far plane that still holds "
                  "(techniques with a far plane; >=: even the ceiling tried holds). *: only with "
                  "the far plane pulled in to the farthest content, the scene's far plane fails. "
                  "near (bound), far (bound): the same under the guaranteed MTS (mts_bound within "
                  "the separation at every distance checked: no fight on any implementation of the "
                  "bound model, in any orientation; docs/bound.md)",
                  human(header.value("content_near", 0.0)), human(header.value("content_far", 0.0)),
                  rel ? fmt::format("{} x z", human(s)) : human(s),
                  header.value("scene_name", std::string("?")),
                  header.value("distances_checked", nlohmann::json::array()).size(),
                  human(AdviseRequest{}.near_floor_ratio)),
      cols, cells, out.format_out);
}

void add_advise_command(CLI::App& app, GlobalOptions& global) {
  auto o = std::make_shared<AdviseOptions>();
  auto* cmd = app.add_subcommand(
      "advise",
      "Which set-up meets the separation your content needs, and how close its near plane can\n"
      "come: for every pair of the scene (technique x format x depth range), a bisection over\n"
      "the near plane in which a near value holds when two planes the needed separation apart\n"
      "never fight on the emulated pipeline at any distance checked (the range's nearest z,\n"
      "doubling up to its farthest). Ranked by the smallest near plane under the guaranteed\n"
      "MTS, then by the smallest under the sampled one.\n"
      "Examples:\n"
      "  depthprec advise --range 1,10000 --separation 0.01\n"
      "  depthprec advise --range 10,1e5 --relative 1e-4 -t reversed,standard,log_fragment -f "
      "float32,unorm24");
  o->scene.add_to(*cmd, true);
  // advise finds the near plane and checks the distances of --range: run_advise refuses both
  // with what to do instead; --help leaves them out (an empty group hides an option).
  for (const char* name : {"--near", "--distances"}) cmd->get_option(name)->group("");
  cmd->add_option("--range", o->range,
                  "Nearest and farthest distance the content is at: A,B (scene units)")
      ->delimiter(',')
      ->required();
  cmd->add_option("--separation", o->separation,
                  "The separation the content needs, in scene units (e.g. 0.01 for 1 cm in m)");
  cmd->add_option("--relative", o->relative,
                  "The separation as a fraction of the distance instead: S = R * z");
  o->out.add_to(*cmd);
  o->batch.add_to(*cmd, "pairs (k in scene order)");
  cmd->callback([o, &global]() { run_advise(*o, global); });
}

}  // namespace depthprec::cli
