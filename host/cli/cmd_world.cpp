// world: how far from the world origin content can sit, per set-up and vertex transform
// (host/analysis/world_sweep.h). A record batch: one record per pair, so it journals, resumes,
// shards and merges as advise does.
#include <fmt/format.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "host/analysis/world_bound.h"
#include "host/analysis/world_sweep.h"
#include "host/base/errors.h"
#include "host/cli/commands.h"
#include "host/cli/record_batch.h"
#include "host/cli/scene_options.h"
#include "host/output/output_guard.h"
#include "host/output/report.h"
#include "host/output/text_table.h"

namespace depthprec::cli {

namespace {

struct WorldOptions {
  SceneOptions scene;
  OutputOptions out;
  BatchOptions batch;
  double distance = 100, separation = 0, relative = 0;
  std::vector<double> direction{1, 1, 1};
  std::vector<std::string> transforms{"absolute", "camera_relative"};
};

WorldRequest request_of(const WorldOptions& o) {
  if ((o.separation > 0) == (o.relative > 0) || o.separation < 0 || o.relative < 0)
    throw InputError(
        "world: give the separation the content needs as --separation S (scene units, > 0) or "
        "--relative R (S = R * z, > 0), exactly one");
  if (o.direction.size() != 3)
    throw Error(ExitCode::usage, "world: --direction takes three numbers: X,Y,Z");
  WorldRequest r;
  r.z = o.distance;
  r.separation = o.separation > 0 ? o.separation : o.relative * o.distance;
  r.direction = {o.direction[0], o.direction[1], o.direction[2]};
  r.transforms.clear();
  for (const auto& t : o.transforms) r.transforms.push_back(parse_transform(t));
  return r;
}

void run_world(const WorldOptions& o, const GlobalOptions& g) {
  check_output_spares_inputs("-o", o.out.output, {{"the scene file", o.scene.scene_file}});
  const WorldRequest r = request_of(o);
  const Scene scene = o.scene.load();
  if (!scene.at_world_origin())
    throw InputError("world: the scene's world_position is what world moves; leave it at [0,0,0]");
  validate(r, scene);
  check_planes_cover_kernel(scene);
  check_writable(o.out.output);
  run_record_batch(
      "world", o.out, o.batch, g,
      [&scene, &r](OpenClRuntime& rt, nlohmann::json& header) {
        header["scene"] = scene.json;
        header["scene_name"] = scene.name;
        header["z"] = r.z;
        header["separation"] = r.separation;
        header["direction"] = r.direction;
        nlohmann::json names = nlohmann::json::array();
        for (const Transform t : r.transforms) names.push_back(to_string(t));
        header["transforms"] = names;
        header["world_distance_limit"] = world_distance_limit(r);
        return pair_units(scene, [&rt, &scene, &r](const EvalPair& pair) {
          // The sampled answer, and beside it, per transform, the guaranteed MTS's.
          nlohmann::json rec = world_record(rt, scene, pair, r);
          for (const Transform t : r.transforms)
            rec["transforms"][to_string(t)].update(world_bound(scene, pair, r, t));
          return rec;
        });
      },
      render_world_output);
}

}  // namespace

// What the world table says, above it.
static std::string world_caption(const nlohmann::json& header) {
  const auto dir = header.value("direction", std::vector<double>{1, 1, 1});
  return fmt::format(
      "How far from the world origin content can sit (scene {}): camera and planes moved a "
      "world distance R along ({}, {}, {}); content at eye distance {} needs a separation of "
      "{}. What the vertex stage keeps of a world coordinate is a grid whose spacing is "
      "constant within a binade of the coordinate, and within one the MTS saws from about 0 "
      "to a full spacing as the planes' translation moves between grid points, so the limit "
      "is decided per binade. limit R: every position below it holds: the start of the first "
      "binade whose spacing reaches the separation, or of an earlier one whose sawtooth peak "
      "was measured to fail; >=: even {} (world_position's bound) holds; '-': not even the "
      "origin holds. limit R (bound): the same under the guaranteed MTS (every position below "
      "it has mts_bound within the separation: no fight on any implementation of the bound "
      "model, in any orientation; a binade's start, docs/mts.md). spacing: the grid's spacing "
      "there and the axis whose coordinate reaches "
      "it first (z: along this view; x or y: across it, which this view sees only through the "
      "planes' slope, but a camera turned toward that axis sees it in depth, so the limit "
      "stands for any view). mts below: the largest MTS measured below the limit. R fails: a "
      "position measured to fail, the view's depth coordinate at its sawtooth peak just past "
      "its own limit. mts at 0: the MTS at the origin (another transform's only where it "
      "differs). abs: absolute, cam-rel: camera_relative, rte: relative_to_eye",
      header.value("scene_name", std::string("?")), human(dir[0]), human(dir[1]), human(dir[2]),
      human(header.value("z", 0.0)), human(header.value("separation", 0.0)),
      human(header.value("world_distance_limit", 0.0)));
}

std::string render_world_output(const nlohmann::json& header,
                                const std::vector<nlohmann::json>& records,
                                const OutputOptions& out) {
  if (out.format_out == "json") return records_json(header, records, !out.no_timing, {});
  const bool csv = out.format_out == "csv";
  const std::string none = csv ? "" : "-";
  const auto num = [&](const nlohmann::json& j, const char* k) {
    return j.contains(k) ? number_cell(j.at(k).get<double>(), out.format_out) : none;
  };
  // Text: the limit, ">=" when even world_position's bound holds, and the spacing with its axis
  // in one cell; CSV: the numbers, the axis and what decided the limit in columns of their own.
  const auto limit = [&](const nlohmann::json& t) {
    const std::string v = num(t, "limit");
    return !csv && t.value("holds_to_bound", false) ? ">= " + v : v;
  };
  const auto limit_bound = [&](const nlohmann::json& t) {
    const std::string v = num(t, "limit_bound");
    return !csv && t.value("limit_bound_to_limit", false) ? ">= " + v : v;
  };
  const auto spacing = [&](const nlohmann::json& t) {
    const std::string v = num(t, "spacing");
    return csv || !t.contains("axis") ? v : v + " " + t.at("axis").get<std::string>();
  };
  const nlohmann::json transforms = header.value("transforms", nlohmann::json::array());
  std::vector<Column> cols = {{"technique", true}, {"format", true}, {"depth_range", true}};
  // Text names a transform briefly, and shows a transform's MTS at the origin only where it
  // differs from the first one's (absolute and camera_relative are one pipeline there), so the
  // transforms fit side by side.
  const auto brief = [&](const std::string& t) -> std::string {
    if (csv) return t + " ";
    return t == "absolute" ? "abs " : t == "camera_relative" ? "cam-rel " : "rte ";
  };
  const auto origin_column = [&](size_t k) {
    if (csv || k == 0) return true;
    for (const auto& rec : records) {
      const nlohmann::json& all = rec.at("transforms");
      if (all.at(transforms[k].get<std::string>()).at("mts_at_origin") !=
          all.at(transforms[0].get<std::string>()).at("mts_at_origin"))
        return true;
    }
    return false;
  };
  std::vector<bool> shows_origin;
  for (size_t k = 0; k < transforms.size(); ++k) {
    shows_origin.push_back(origin_column(k));
    const std::string t = brief(transforms[k].get<std::string>());
    if (shows_origin[k]) cols.push_back({(k == 0 && !csv ? "" : t) + "mts at 0"});
    cols.push_back({t + "limit R"});
    cols.push_back({t + "limit R (bound)"});
    cols.push_back({t + "spacing"});
    if (csv) cols.push_back({t + "axis", true});
    if (csv) cols.push_back({t + "limit from", true});
    cols.push_back({t + "mts below"});
    cols.push_back({t + (csv ? "fails at R" : "R fails")});
    if (csv) cols.push_back({t + "mts at fail"});
    if (csv) cols.push_back({t + "holds to bound", true});
  }
  Cells cells;
  for (const auto& rec : records) {
    cells.push_back({rec.at("technique").get<std::string>(), rec.at("format").get<std::string>(),
                     rec.at("depth_range").get<std::string>()});
    for (size_t k = 0; k < transforms.size(); ++k) {
      const nlohmann::json& t = rec.at("transforms").at(transforms[k].get<std::string>());
      auto& row = cells.back();
      if (shows_origin[k]) row.push_back(num(t, "mts_at_origin"));
      row.push_back(limit(t));
      row.push_back(limit_bound(t));
      row.push_back(spacing(t));
      if (csv) row.push_back(t.value("axis", ""));
      if (csv) row.push_back(t.value("limit_from", ""));
      row.push_back(num(t, "mts_below"));
      row.push_back(num(t, "fails_at"));
      if (csv) row.push_back(num(t, "mts_at_fail"));
      if (csv) row.push_back(t.value("holds_to_bound", false) ? "true" : "false");
    }
  }
  return captioned(world_caption(header), cols, cells, out.format_out);
}

void add_world_command(CLI::App& app, GlobalOptions& global) {
  auto o = std::make_shared<WorldOptions>();
  auto* cmd = app.add_subcommand(
      "world",
      "How far from the world origin your content can go: per pair of the scene and vertex\n"
      "transform (pipeline.transform: absolute, camera_relative, relative_to_eye), the world\n"
      "distance of camera and content below which content at eye distance --distance keeps the\n"
      "separation it needs everywhere on the emulated pipeline, and the spacing of the world\n"
      "coordinates there (docs/spec.md 2, \"World position\"). Absolute and camera-relative\n"
      "side by side by default.\n"
      "Examples:\n"
      "  depthprec world -t reversed -f float32 --distance 100 --separation 0.01\n"
      "  depthprec world -t standard -f unorm24 --far 1e5 --distance 500 --relative 1e-4 "
      "--transforms absolute,camera_relative,relative_to_eye");
  o->scene.add_to(*cmd, true);
  refuse_unused(*cmd, {"--distances"},
                "world measures content at one eye distance, --distance (the world distance is "
                "what it searches)");
  cmd->add_option("--distance", o->distance, "The content's eye distance z (scene units)")
      ->capture_default_str();
  cmd->add_option("--separation", o->separation,
                  "The separation the content needs, in scene units (e.g. 0.01 for 1 cm in m)");
  cmd->add_option("--relative", o->relative, "The separation as a fraction of z instead");
  cmd->add_option("--direction", o->direction,
                  "Direction of the move away from the origin: X,Y,Z (normalised)")
      ->delimiter(',')
      ->capture_default_str();
  cmd->add_option("--transforms", o->transforms,
                  "absolute, camera_relative, relative_to_eye (comma-separated)")
      ->delimiter(',')
      ->capture_default_str();
  o->out.add_to(*cmd);
  o->batch.add_to(*cmd, "pairs (k in scene order)");
  cmd->callback([o, &global]() { run_world(*o, global); });
}

}  // namespace depthprec::cli
