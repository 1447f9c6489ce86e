#include <fmt/format.h>

#include "host/cli/commands.h"
#include "host/cli/scene_options.h"
#include "host/mts_run.h"

namespace depthprec::cli {

namespace {

struct MtsOptions {
  SceneOptions scene;
  OutputOptions out;
};

void run(const MtsOptions& o, const GlobalOptions& global, const std::string& command, bool wide) {
  const Scene scene = o.scene.load();
  check_writable(o.out.output);
  OpenClRuntime rt(global.device);
  auto log = [&global](const std::string& line) {
    if (global.verbose) fmt::print(stderr, "{}\n", line);
  };
  MtsRun result = run_scene(rt, scene, log);
  result.info.command = command;
  result.info.timing = !o.out.no_timing;
  const std::string text = wide ? render_table(scene, result.rows, result.info, o.out.format_out)
                                : render_rows(scene, result.rows, result.info, o.out.format_out);
  write_output(o.out.output, text);
}

std::string joined(int argc, char** argv) {
  std::string s;
  for (int i = 0; i < argc; ++i) s += (i ? " " : "") + std::string(argv[i]);
  return s;
}

}  // namespace

void add_mts_commands(CLI::App& app, GlobalOptions& global, int argc, char** argv) {
  const std::string command = joined(argc, argv);
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
  cmd->callback([mts, &global, command]() { run(*mts, global, command, false); });

  auto table = std::make_shared<MtsOptions>();
  auto* tcmd = app.add_subcommand(
      "table",
      "The batch precision table: every pair of the scene (default: Gilg et al.'s 7 techniques\n"
      "x float32, unorm24), one row per distance, one column per pair, the vertex bound\n"
      "alongside. inf = unresolvable; * = flagged (details with --format-out json).\n"
      "Examples:\n"
      "  depthprec table\n"
      "  depthprec table --format-out markdown -o docs/gilg2021-table.md\n"
      "  depthprec table -t reversed,reversed_infinite -f float32,float24 --no-timing");
  table->scene.add_to(*tcmd, true);
  table->out.add_to(*tcmd);
  tcmd->callback([table, &global, command]() { run(*table, global, command, true); });
}

}  // namespace depthprec::cli
