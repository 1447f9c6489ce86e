// audit: does a user's scene z-fight, and where (docs/audit.md). A glTF file and a camera; per
// set-up the emulated pipeline on every pixel (kernels/audit.cl), the fighting pairs, their
// fixes, a PNG of the view with the fights marked and one of the margin.
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>

#include "host/audit/audit_fixes.h"
#include "host/base/interrupt.h"
#include "host/base/read_file.h"
#include "host/cli/audit_png_paths.h"
#include "host/cli/commands.h"
#include "host/cli/gltf_inputs.h"
#include "host/model/scene_geometry.h"
#include "host/output/audit_images.h"
#include "host/output/audit_output.h"
#include "host/output/json_header.h"
#include "host/output/output_guard.h"
#include "host/output/png_image.h"
#include "host/output/progress.h"
#include "host/output/report.h"
#include "host/render/render_audit.h"

namespace depthprec::cli {

namespace {

struct AuditOptions {
  std::string file;
  SceneOptions scene;
  OutputOptions out;
  std::string eye, target, up = "0,1,0", size = "1280x720", camera, png, source = "emulated", path;
  std::string gl_device = "auto";
  double fov_y = 0;
  // Eight views by default: on the test scenes one view missed whole set-ups that fight (drone_road
  // standard/unorm24, rug_tiles reversed/float32), four found them, eight found every set-up
  // sixteen did, for about 0.5 s more than one view at 1280x720 (docs/audit.md "Views").
  int frames = 8;
  double jitter = NAN;  // unset: 10^-4 of the distance from the eye to the geometry's centre
  uint64_t max_triangles = 1ull << 22;  // about 2.4 GB at 560 bytes a triangle
  bool no_fixes = false, reference = false;
  bool jitter_given = false, fov_given = false, frames_given = false;
};

std::array<double, 3> parse_vec3(const std::string& option, const std::string& text) {
  std::array<double, 3> v{};
  char tail = 0;
  if (std::sscanf(text.c_str(), "%lf,%lf,%lf%c", &v[0], &v[1], &v[2], &tail) != 3)
    throw Error(
        ExitCode::usage,
        fmt::format("{} '{}': expected X,Y,Z (three numbers, commas between)", option, text));
  return v;
}

// The camera: --camera NAME from the file, else --eye/--target; the file's only camera when
// neither is given.
AuditCamera camera_of(const AuditOptions& o, const SceneGeometry& g, int w, int h,
                      const GltfCamera** from_file) {
  *from_file = nullptr;
  if (!o.camera.empty() && (!o.eye.empty() || !o.target.empty()))
    throw Error(ExitCode::usage, "give either --camera or --eye and --target, not both");
  if (o.eye.empty() != o.target.empty())
    throw Error(ExitCode::usage, "--eye and --target go together");
  if (!o.eye.empty()) {
    const double fov = o.fov_given ? o.fov_y : 60.0;
    return look_at_camera(parse_vec3("--eye", o.eye), parse_vec3("--target", o.target),
                          parse_vec3("--up", o.up), fov, w, h);
  }
  std::string names;
  for (const GltfCamera& c : g.cameras) names += (names.empty() ? "" : ", ") + c.name;
  if (o.camera.empty() && g.cameras.size() != 1)
    throw InputError(fmt::format("{}: {}; give --camera NAME or --eye and --target", o.file,
                                 g.cameras.empty() ? "no perspective camera in the file"
                                                   : "several cameras (" + names + ")"));
  for (const GltfCamera& c : g.cameras)
    if (o.camera.empty() || c.name == o.camera) {
      *from_file = &c;
      AuditCamera cam = gltf_view(c, w, h);
      if (o.fov_given) cam.fov_y_deg = o.fov_y;
      if (!(cam.fov_y_deg > 0 && cam.fov_y_deg < 180))
        throw InputError(
            fmt::format("{}: camera '{}' has yfov {} radians; a perspective camera's "
                        "is above 0 and below pi",
                        o.file, c.name, c.yfov));
      return cam;
    }
  throw InputError(fmt::format("{}: no camera named '{}' (the file has: {})", o.file, o.camera,
                               names.empty() ? "none" : names));
}

// The views of --path FILE: one per line, "ex,ey,ez,tx,ty,tz" (eye, then target; # starts a
// comment), each with --up and the camera's field of view.
std::vector<AuditCamera> path_frames(const AuditOptions& o, const AuditCamera& like) {
  std::vector<AuditCamera> out;
  std::istringstream in(read_input_file(o.path, "--path file"));
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    line = line.substr(0, line.find('#'));
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    double v[6];
    char tail = 0;
    if (std::sscanf(line.c_str(), " %lf , %lf , %lf , %lf , %lf , %lf %c", &v[0], &v[1], &v[2],
                    &v[3], &v[4], &v[5], &tail) != 6)
      throw InputError(fmt::format("{}:{}: expected ex,ey,ez,tx,ty,tz (eye, then target), got '{}'",
                                   o.path, number, line));
    AuditCamera c = look_at_camera({v[0], v[1], v[2]}, {v[3], v[4], v[5]}, parse_vec3("--up", o.up),
                                   like.fov_y_deg, like.width, like.height);
    c.description = fmt::format("{} line {}: {}", o.path, number, c.description);
    out.push_back(c);
  }
  if (out.empty()) throw InputError(o.path + ": no views (one line ex,ey,ez,tx,ty,tz per view)");
  return out;
}

void run_audit(AuditOptions o, const GlobalOptions& g) {
  // The glTF file, and the buffers and images it names: a report written over its .bin is the
  // user's geometry gone.
  std::vector<NamedInput> inputs = {{"the --path file", o.path},
                                    {"the glTF file", o.file},
                                    {"the scene file", o.scene.scene_file}};
  for (NamedInput& in : gltf_inputs(o.file)) inputs.push_back(std::move(in));
  check_output_spares_inputs("-o", o.out.output, inputs);
  const std::string png = png_prefix(o.png, o.file);
  int w = 0, h = 0;
  char tail = 0;
  if (std::sscanf(o.size.c_str(), "%dx%d%c", &w, &h, &tail) != 2 || w < 1 || h < 1 || w > 16384 ||
      h > 16384)
    throw Error(ExitCode::usage,
                fmt::format("--size '{}': expected WxH in pixels, each 1 to 16384", o.size));
  if (o.frames < 1 || o.frames > 1000)
    throw Error(ExitCode::usage, fmt::format("--frames {}: 1 to 1000", o.frames));
  if (o.jitter_given && (!(o.jitter >= 0) || !std::isfinite(o.jitter)))
    throw Error(ExitCode::usage, "--jitter: a distance in metres, 0 or more");
  if (o.fov_given && !(o.fov_y > 0 && o.fov_y < 180))
    throw Error(ExitCode::usage,
                fmt::format("--fov-y {}: degrees, above 0 and below 180", o.fov_y));
  if (!o.path.empty() && (!o.eye.empty() || !o.target.empty()))
    throw Error(ExitCode::usage, "--path gives the views: not with --eye and --target");
  if (static_cast<uint64_t>(w) * h > (1ull << 26))
    throw Error(ExitCode::usage,
                fmt::format("--size {}: {} pixels, more than the audit takes (67,108,864, e.g. "
                            "8192x8192: 16 bytes a pixel)",
                            o.size, static_cast<uint64_t>(w) * h));
  if (o.source != "emulated" && o.source != "rendered")
    throw Error(ExitCode::usage, "--source: emulated or rendered");
  const SceneGeometry geometry = load_gltf(o.file, o.max_triangles);
  const GltfCamera* file_camera = nullptr;
  const AuditCamera camera = camera_of(o, geometry, w, h, &file_camera);
  // The views' moves scale with the scene: a ten-thousandth of the eye's distance to the centre
  // of what it looks at moves depths by a few storage codes at most set-ups' resolutions.
  if (!o.jitter_given) {
    const auto c = bounding_box_centre(geometry);
    o.jitter = 1e-4 * std::hypot(c[0] - camera.eye[0], c[1] - camera.eye[1], c[2] - camera.eye[2]);
  }
  // The glTF camera's planes where the command line (--near, --far or --set) gives none.
  const auto set_in_scene = [&o](const std::string& key) {
    for (const std::string& s : o.scene.sets)
      if (s.rfind(key + "=", 0) == 0) return true;
    return false;
  };
  // Each goes in named as the file camera's, so notes and errors about it say where it came
  // from; the report says it too (near_source, far_source: command line, camera or scene).
  std::string near_source = "scene", far_source = "scene";
  if (!o.scene.near.empty() || set_in_scene("near")) {
    near_source = "command line";
  } else if (file_camera && file_camera->znear > 0) {
    near_source = "camera";
    o.scene.implied.push_back({fmt::format("near={}", file_camera->znear),
                               fmt::format("the file camera's znear ({})", file_camera->znear)});
  }
  if (!o.scene.far.empty() || set_in_scene("far")) {
    far_source = "command line";
  } else if (file_camera) {
    far_source = "camera";
    o.scene.implied.push_back(
        file_camera->zfar > 0
            ? std::pair{fmt::format("far={}", file_camera->zfar),
                        fmt::format("the file camera's zfar ({})", file_camera->zfar)}
            : std::pair{std::string("far=inf"),
                        std::string("the file camera's missing zfar (no far plane)")});
  }
  Scene scene = o.scene.load();
  // The scene's own pairs less layered, whose depth range depends on the distance; named with
  // -t, audit_setup refuses it with the reason.
  if (o.scene.techniques.empty())
    scene.evaluate.erase(
        std::remove_if(scene.evaluate.begin(), scene.evaluate.end(),
                       [](const EvalPair& p) { return p.technique == Technique::layered; }),
        scene.evaluate.end());
  check_writable(o.out.output);
  check_png_names(png, scene.evaluate, inputs);
  std::unique_ptr<OpenClRuntime> rt;
  if (!o.reference || !o.no_fixes) rt = std::make_unique<OpenClRuntime>(g.device);
  AuditRequest req;
  if (!o.path.empty() && o.frames_given)
    throw Error(ExitCode::usage, "--path gives the views; --frames adds jittered ones: not both");
  req.frames =
      o.path.empty() ? jittered_frames(camera, o.frames, o.jitter) : path_frames(o, camera);
  req.reference = o.reference;
  AuditReport report;
  report.geometry = &geometry;
  report.header = output_header("audit", rt ? rt->description() : "");
  report.header.update(
      {{"file", o.file},
       {"triangles", geometry.triangles},
       {"draws", geometry.draws.size()},
       {"camera", o.path.empty() ? camera.description
                                 : req.frames[0].description + " (first of " +
                                       std::to_string(req.frames.size()) + " views)"},
       {"fov_y_deg", camera.fov_y_deg},
       {"width", w},
       {"height", h},
       {"frames", req.frames.size()},
       {"jitter", o.path.empty() && req.frames.size() > 1 ? o.jitter : 0.0},
       {"near", scene.near},
       {"near_source", near_source},
       {"far", scene.far},
       {"far_source", far_source},
       {"source", o.source},
       {"scene_name", scene.name},
       {"scene", scene.json}});
  if (o.source == "rendered") report.rendered = nlohmann::json::array();
  // Ctrl-C or SIGTERM stops between a set-up's stages (a stage under way runs on); the set-ups
  // finished by then are written, said to be a part, and the exit is 130.
  install_interrupt_handlers();
  const auto stop_if_asked = [] {
    if (interrupt_requested()) throw Error(ExitCode::interrupted, "interrupted");
  };
  bool interrupted = false;
  std::unique_ptr<GlContext> gl;
  {
    Progress bar("audit", scene.evaluate.size(), !g.quiet && stderr_is_terminal(), "set-ups");
    try {
      for (const EvalPair& pair : scene.evaluate) {
        const std::string label = pair.label();
        stop_if_asked();
        bar.doing(label + ": pixels");
        SetupAudit audit = audit_setup_pair(rt.get(), scene, pair, geometry, req);
        nlohmann::json rendered;
        if (o.source == "rendered") {
          stop_if_asked();
          bar.doing(label + ": rendering");
          if (!gl) gl = std::make_unique<GlContext>(GlDeviceChoice::parse(o.gl_device));
          rendered = render_audit(*gl, scene, pair, geometry, req.frames[0], audit);
        }
        if (!o.no_fixes) {
          stop_if_asked();
          bar.doing(label + ": fixes");
          FixRequest fix;
          fix.alternatives = default_alternatives(scene, pair);
          add_fixes(rt.get(), audit_scene(scene, req.frames[0]), scene, geometry, req.frames, audit,
                    fix);
        }
        // no stop before the PNGs: they take milliseconds, and the set-up's work is done
        if (!png.empty()) {
          write_png(png_name(png, pair, ""), w, h, fight_image(audit));
          write_png(png_name(png, pair, "-margin"), w, h, margin_image(audit));
          report.pngs.push_back(png_name(png, pair, ""));
          report.margin_pngs.push_back(png_name(png, pair, "-margin"));
        }
        // finished: what follows for this set-up cannot fail
        if (o.source == "rendered") report.rendered.push_back(std::move(rendered));
        report.setups.push_back(std::move(audit));
        bar.advance();
      }
    } catch (...) {
      // A signal can also break what a stage was doing (a kernel build inside PoCL's compiler
      // fails when SIGINT lands in it): once a stop is asked, any failure is the interruption.
      if (!interrupt_requested()) throw;
      interrupted = true;
    }
  }
  const size_t finished = report.setups.size(), planned = scene.evaluate.size();
  if (interrupted && finished == 0)
    throw Error(ExitCode::interrupted,
                "interrupted before the first set-up finished: nothing written");
  if (interrupted)
    report.header["interrupted"] = {{"finished_setups", finished}, {"setups", planned}};
  const bool timing = !o.out.no_timing;
  write_output(o.out.output, o.out.format_out == "json"
                                 ? audit_json(report, timing).dump(2) + "\n"
                                 : audit_text(report, o.out.format_out, timing));
  if (interrupted)
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
      "  depthprec audit data/audit/decal_wall.glb -t reversed -f float32 --depth-range "
      "zero_to_one\n"
      "  depthprec audit data/audit/intersecting_boxes.gltf --eye 6,5,0 --target 0,0,-20 --fov-y "
      "40 "
      "--size 640x360\n"
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
  cmd->add_option("--eye", o->eye, "Camera position X,Y,Z");
  cmd->add_option("--target", o->target, "Point the camera looks at X,Y,Z");
  cmd->add_option("--up", o->up, "Up direction X,Y,Z (default 0,1,0)");
  cmd->add_option("--fov-y", o->fov_y,
                  "Vertical field of view, degrees (default: the camera's, "
                  "else 60)");
  cmd->add_option("--camera", o->camera, "A perspective camera of the file, by name");
  cmd->add_option("--size", o->size, "Image WxH in pixels (default 1280x720)");
  cmd->add_option("--frames", o->frames,
                  "Views: the camera, then frames - 1 with eye and target moved by up to --jitter "
                  "(default 8; 1 for the given view alone)");
  cmd->add_option(
      "--jitter", o->jitter,
      "Largest camera move of --frames, metres (default: 10^-4 of the eye's distance to "
      "the geometry's centre)");
  cmd->add_option("--path", o->path,
                  "Views from a file, one per line: ex,ey,ez,tx,ty,tz (eye, target); the first is "
                  "the PNG's and the fixes'");
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
    o->jitter_given = cmd->count("--jitter") > 0;
    o->fov_given = cmd->count("--fov-y") > 0;
    o->frames_given = cmd->count("--frames") > 0;
    run_audit(*o, global);
  });
}

}  // namespace depthprec::cli
