// readback: the eye distance a shader reconstructs from the stored depth, per pair and distance,
// against the true one (host/analysis/readback.h). Exact mappings and binary32 inverses on the
// host; no device.
#include <fmt/format.h>

#include <chrono>
#include <nlohmann/json.hpp>

#include "host/analysis/readback.h"
#include "host/base/json_number.h"
#include "host/cli/commands.h"
#include "host/output/json_header.h"
#include "host/output/output_guard.h"
#include "host/output/report.h"
#include "host/output/text_table.h"

namespace depthprec::cli {

namespace {

struct ReadbackOptions {
  SceneOptions scene;
  OutputOptions out;
};

nlohmann::json row_json(const ReadbackRow& r) {
  nlohmann::json j = r.pair.fields();
  j.update({{"inverse", to_string(r.inverse)},
            {"z", json_number(r.distance)},
            {"code", r.code},
            {"depth", json_number(r.depth)},
            {"read", json_number(r.read)},
            {"error", json_number(r.error())},
            {"relative_error", json_number(r.relative_error())},
            {"storage_error", json_number(r.storage_error())},
            {"arithmetic_error", json_number(r.arithmetic_error())},
            {"code_gap", json_number(r.code_gap)},
            {"dominant", r.dominant()}});
  return j;
}

std::string render(const Scene& scene, const std::vector<ReadbackRow>& rows, double seconds,
                   const OutputOptions& out) {
  const bool timing = !out.no_timing;
  if (out.format_out == "json") {
    nlohmann::json j = output_header("readback", "");
    j.erase("device");  // exact mappings and binary32 inverses on the host: no device
    j.update({{"scene_name", scene.name},
              {"near", json_number(scene.near)},
              {"far", json_number(scene.far)},
              {"rows", nlohmann::json::array()}});
    if (timing) j["seconds"] = json_number(seconds);
    for (const auto& r : rows) j["rows"].push_back(row_json(r));
    return j.dump(2) + "\n";
  }
  const std::vector<Column> cols = {{"technique", true},
                                    {"format", true},
                                    {"depth_range", true},
                                    {"inverse", true},
                                    {"z"},
                                    {"code"},
                                    {"read"},
                                    {"error"},
                                    {"rel_error"},
                                    {"storage_error"},
                                    {"arithmetic_error"},
                                    {"code_gap"},
                                    {"dominant", true}};
  Cells cells;
  const auto num = [&out](double v) { return number_cell(v, out.format_out); };
  for (const auto& r : rows)
    cells.push_back({info(r.pair.technique).name, r.pair.format, to_string(r.pair.depth_range),
                     to_string(r.inverse), num(r.distance), std::to_string(r.code), num(r.read),
                     num(r.error()), num(r.relative_error()), num(r.storage_error()),
                     num(r.arithmetic_error()), num(r.code_gap), r.dominant()});
  const std::string caption = fmt::format(
      "Eye distance read back from the stored depth (scene {}, near {}, far {}): the code of the "
      "exact depth of z, read as binary32, through each inverse in binary32 (read, error = read - "
      "z, rel_error = |error| / z) and exactly (storage_error); arithmetic_error = read - exact, "
      "code_gap = the distance to the farther neighbouring code (resolve's resolution)",
      scene.name, human(scene.near), human(scene.far));
  std::string text = captioned(caption, cols, cells, out.format_out);
  if (timing && out.format_out != "csv") text += fmt::format("computed in {:.3g} s\n", seconds);
  return for_terminal(text, out.format_out);
}

void run_readback(const ReadbackOptions& o) {
  check_output_spares_inputs("-o", o.out.output, {{"the scene file", o.scene.scene_file}});
  const Scene scene = o.scene.load();
  check_writable(o.out.output);
  const auto start = std::chrono::steady_clock::now();
  std::vector<ReadbackRow> rows;
  for (const EvalPair& pair : scene.evaluate)
    for (const double z : scene.distances)
      for (const ReadbackRow& r : readback(scene, pair, z)) rows.push_back(r);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  write_output(o.out.output, render(scene, rows, seconds, o.out));
}

}  // namespace

void add_readback_command(CLI::App& app) {
  auto o = std::make_shared<ReadbackOptions>();
  auto* cmd = app.add_subcommand(
      "readback",
      "Per technique x format and distance: the eye distance a shader reconstructs from the\n"
      "stored depth with the inverse engines write (three.js perspectiveDepthToViewZ and Godot's\n"
      "INV_PROJECTION_MATRIX for projections, n + d(f - n), exp2(d log2(f + 1)) - 1, Cesium's\n"
      "exp2(d log2(f - n + 1)) - 1 + n), in binary32, against the true distance; the same code\n"
      "through an exact inverse says whether storage or the inverse's arithmetic dominates.\n"
      "The stored depth is the code of the exact depth. Exact mappings on the host; no device.\n"
      "Examples:\n"
      "  depthprec readback -t standard -f unorm24 --near 0.1 --far 1e4 --distances 5000\n"
      "  depthprec readback -t reversed,linear,log_threejs,log_cesium -f float32 --distances "
      "1,100,1e4,1e6\n"
      "  depthprec readback --distances 2,1024,1048576 --format-out csv -o readback.csv");
  o->scene.add_to(*cmd, true);
  refuse_unused(*cmd,
                {"--kernel", "--frames", "--rel-precision", "--profile", "--fov",
                 "--matrix-precision", "--compose", "--divide", "--denormals"},
                "readback maps depths exactly on the host (no kernel, frames, search or "
                "emulated pipeline)");
  o->out.add_to(*cmd);
  cmd->callback([o]() { run_readback(*o); });
}

}  // namespace depthprec::cli
