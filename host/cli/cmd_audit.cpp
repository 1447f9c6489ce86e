// audit: does a user's scene z-fight, and where (docs/audit.md). A glTF file and a camera; per
// set-up the emulated pipeline on every pixel (kernels/audit.cl), the fighting pairs, their
// fixes, a PNG of the view with the fights marked and one of the margin. This file reads the
// command line; audit_views.* settles where it looks from, audit_session.* runs the set-ups.
#include <fmt/format.h>

#include <algorithm>

#include "host/cli/audit_png_paths.h"
#include "host/cli/audit_session.h"
#include "host/cli/commands.h"
#include "host/cli/gltf_inputs.h"
#include "host/output/output_guard.h"
#include "host/output/progress.h"
#include "host/output/report.h"

namespace depthprec::cli {

namespace {

struct AuditOptions {
  std::string file;
  SceneOptions scene;
  OutputOptions out;
  ViewOptions views;
  std::string png, source = "emulated", gl_device = "auto";
  uint64_t max_triangles = 1ull << 22;  // about 2.4 GB at 560 bytes a triangle
  bool no_fixes = false, reference = false;
};

void run_audit(AuditOptions o, const GlobalOptions& g) {
  // The glTF file, and the buffers and images it names: a report written over its .bin is the
  // user's geometry gone.
  std::vector<NamedInput> inputs = {{"the --path file", o.views.path},
                                    {"the glTF file", o.file},
                                    {"the scene file", o.scene.scene_file}};
  for (NamedInput& in : gltf_inputs(o.file)) inputs.push_back(std::move(in));
  check_output_spares_inputs("-o", o.out.output, inputs);
  SessionOptions run_options{o.file,      o.source,
                             o.gl_device, png_prefix(o.png, o.file),
                             !o.no_fixes, !g.quiet && stderr_is_terminal()};
  check_view_options(o.views);
  if (o.source != "emulated" && o.source != "rendered")
    throw Error(ExitCode::usage, "--source: emulated or rendered");
  const SceneGeometry geometry = load_gltf(o.file, o.max_triangles);
  const AuditViews views = audit_views(o.views, o.file, geometry, o.scene);
  Scene scene = o.scene.load();
  // The scene's own pairs less layered, whose depth range depends on the distance; named with
  // -t, audit_setup refuses it with the reason.
  if (o.scene.techniques.empty())
    scene.evaluate.erase(
        std::remove_if(scene.evaluate.begin(), scene.evaluate.end(),
                       [](const EvalPair& p) { return p.technique == Technique::layered; }),
        scene.evaluate.end());
  check_writable(o.out.output);
  check_png_names(run_options.png, scene.evaluate, inputs);
  std::unique_ptr<OpenClRuntime> rt;
  if (!o.reference || !o.no_fixes) rt = std::make_unique<OpenClRuntime>(g.device);
  AuditRequest req;
  req.frames = views.frames;
  req.reference = o.reference;
  AuditReport report;
  report.geometry = &geometry;
  report.header = audit_header(run_options, geometry, views, scene, rt ? rt->description() : "");
  const bool complete = run_setups(rt.get(), scene, geometry, req, run_options, report);
  const size_t finished = report.setups.size(), planned = scene.evaluate.size();
  if (!complete && finished == 0)
    throw Error(ExitCode::interrupted,
                "interrupted before the first set-up finished: nothing written");
  if (!complete)
    report.header["interrupted"] = {{"finished_setups", finished}, {"setups", planned}};
  const bool timing = !o.out.no_timing;
  write_output(o.out.output, o.out.format_out == "json"
                                 ? audit_json(report, timing).dump(2) + "\n"
                                 : audit_text(report, o.out.format_out, timing));
  if (!complete)
    throw Error(
        ExitCode::interrupted,
        fmt::format("interrupted after {} of {} set-ups: the finished ones are {}", finished,
                    planned, o.out.output.empty() ? "above" : "in " + o.out.output));
}

}  // namespace

void add_audit_command(CLI::App& app, GlobalOptions& global) {
  auto o = std::make_shared<AuditOptions>();
  auto* cmd = app.add_subcommand(
      "audit",
      "Does a scene z-fight, and where: the triangles of a glTF 2.0 file (.gltf, .glb) drawn in\n"
      "the file's order through the emulated pipeline of each set-up, every pixel's stored\n"
      "winner against the exact front surface (binary64). Reports the fighting pixels, the\n"
      "pairs of surfaces that fight with their separation along the ray and the set-up's MTS\n"
      "there, and each pair's cheapest fixes: a farther near plane, a depth bias, another\n"
      "set-up, the offset. --png writes the view with the fights marked and the margin.\n"
      "Examples (data/audit/ holds scenes made by scripts/make_audit_scenes.py):\n"
      "  depthprec audit data/audit/decal_wall.gltf -t standard -f unorm24 --png decal\n"
      "  depthprec audit data/audit/decal_wall.glb -t reversed -f float32\n"
      "  depthprec audit data/audit/intersecting_boxes.gltf --eye 6,5,0 --target 0,0,-20 "
      "--fov-y 40 --size 640x360\n"
      "  depthprec audit data/audit/decal_wall.gltf -t standard -f unorm24 --profile llvmpipe "
      "--source rendered");
  cmd->add_option("file", o->file, "The glTF 2.0 scene (.gltf or .glb)")->required();
  cmd->add_option("--scene", o->scene.scene_file,
                  "Scene file (JSON) of the MTS measurement and pipeline (default: embedded)");
  cmd->add_option("--set", o->scene.sets, "Override a scene field: key=value (repeatable)");
  cmd->add_option("-t,--technique", o->scene.techniques, "Technique(s)")->delimiter(',');
  cmd->add_option("-f,--format", o->scene.formats, "Storage format(s)")->delimiter(',');
  cmd->add_option("--depth-range", o->scene.depth_ranges, "gl and/or zero_to_one")->delimiter(',');
  cmd->add_option("--near", o->scene.near,
                  "Near plane (default: the glTF camera's, else the scene's, 1)");
  cmd->add_option("--far", o->scene.far,
                  "Far plane, inf for none (default: the glTF camera's, else the scene's, 1e9)");
  cmd->add_option("--profile", o->scene.profile, "Implementation profile: ideal, llvmpipe, ...");
  add_view_options(*cmd, o->views);
  cmd->add_option("--png", o->png,
                  "Write PREFIX-<technique>-<format>-<range>.png and ...-margin.png; a directory "
                  "(ends with / or exists) gets <glTF name>-<technique>-<format>-<range>.png "
                  "inside it. Its directory must exist");
  cmd->add_option("--source", o->source,
                  "emulated, or rendered: the winners drawn by the system's OpenGL");
  add_gl_device_option(cmd, o->gl_device);
  cmd->add_option(
      "--max-triangles", o->max_triangles,
      "Refuse larger scenes (default 4194304: about 560 bytes of memory a triangle, 2.4 GB)");
  cmd->add_flag("--no-fixes", o->no_fixes, "Leave out the fixes (and their MTS measurements)");
  cmd->add_flag("--reference", o->reference,
                "Run the per-pixel pass in the host reference, one thread, instead of OpenCL: no "
                "kernel to build, so quicker for a small image, far slower for a large one");
  o->out.add_to(*cmd);
  cmd->callback([o, &global, cmd]() {
    note_given(*cmd, o->views);
    run_audit(*o, global);
  });
}

}  // namespace depthprec::cli
