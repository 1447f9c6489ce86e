#include "host/cli/audit_views.h"

#include <fmt/format.h>

#include <cstdio>
#include <sstream>

#include "host/audit/audit.h"
#include "host/base/errors.h"
#include "host/base/read_file.h"

namespace depthprec::cli {

namespace {

std::array<double, 3> parse_vec3(const std::string& option, const std::string& text) {
  std::array<double, 3> v{};
  char tail = 0;
  if (std::sscanf(text.c_str(), "%lf,%lf,%lf%c", &v[0], &v[1], &v[2], &tail) != 3)
    throw Error(
        ExitCode::usage,
        fmt::format("{} '{}': expected X,Y,Z (three numbers, commas between)", option, text));
  return v;
}

void parse_size(const std::string& size, int& w, int& h) {
  char tail = 0;
  std::string lower = size;  // 1280X720 as well
  for (char& c : lower) c = c == 'X' ? 'x' : c;
  if (std::sscanf(lower.c_str(), "%dx%d%c", &w, &h, &tail) != 2 || w < 1 || h < 1 || w > 16384 ||
      h > 16384)
    throw Error(ExitCode::usage,
                fmt::format("--size '{}': expected WxH in pixels, each 1 to 16384", size));
  if (static_cast<uint64_t>(w) * h > (1ull << 26))
    throw Error(ExitCode::usage,
                fmt::format("--size {}: {} pixels, more than the audit takes (67,108,864, e.g. "
                            "8192x8192: 16 bytes a pixel)",
                            size, static_cast<uint64_t>(w) * h));
}

// The camera: --camera NAME from the file, else --eye/--target; the file's only camera when
// neither is given. from_file: the file camera used, or null.
AuditCamera camera_of(const ViewOptions& o, const std::string& file, const SceneGeometry& g, int w,
                      int h, const GltfCamera** from_file) {
  *from_file = nullptr;
  if (!o.eye.empty()) {
    const double fov = o.fov_given ? o.fov_y : 60.0;
    return look_at_camera(parse_vec3("--eye", o.eye), parse_vec3("--target", o.target),
                          parse_vec3("--up", o.up), fov, w, h);
  }
  // A camera is named by its own name or its node's (Blender exports "Camera" on a node and
  // "Camera_data" on the camera; users know the node).
  std::string names;
  std::vector<const GltfCamera*> perspective;
  for (const GltfCamera& c : g.cameras) {
    names += (names.empty() ? "" : ", ") + c.name +
             (!c.node.empty() && c.node != c.name ? " (node " + c.node + ")" : "") +
             (c.orthographic ? " (orthographic)" : "");
    if (!c.orthographic) perspective.push_back(&c);
  }
  if (o.camera.empty() && perspective.size() != 1)
    throw InputError(fmt::format(
        "{}: {}; give --camera NAME or --eye and --target", file,
        perspective.empty()
            ? (g.cameras.empty() ? std::string("no camera in the file")
                                 : "no perspective camera (the file has: " + names + ")")
            : "several cameras (" + names + ")"));
  for (const GltfCamera& c : g.cameras) {
    if (!o.camera.empty() && c.name != o.camera && c.node != o.camera) continue;
    if (c.orthographic) {
      if (!o.camera.empty())
        throw InputError(fmt::format(
            "{}: camera '{}' is orthographic; the audit takes a perspective camera (give "
            "--eye and --target, or another camera: {})",
            file, o.camera, names));
      continue;
    }
    *from_file = &c;
    AuditCamera cam = gltf_view(c, w, h);
    if (o.fov_given) cam.fov_y_deg = o.fov_y;
    if (!(cam.fov_y_deg > 0 && cam.fov_y_deg < 180))
      throw InputError(
          fmt::format("{}: camera '{}' has yfov {} radians; a perspective camera's "
                      "is above 0 and below pi",
                      file, c.name, c.yfov));
    return cam;
  }
  throw InputError(fmt::format("{}: no camera named '{}' (the file has: {})", file, o.camera,
                               names.empty() ? "none" : names));
}

// The views of --path FILE: one per line, "ex,ey,ez,tx,ty,tz" (eye, then target; # starts a
// comment), each with --up and the camera's field of view.
std::vector<AuditCamera> path_frames(const ViewOptions& o, const AuditCamera& like) {
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

bool sets_key(const SceneOptions& scene, const std::string& key) {
  for (const std::string& s : scene.sets)
    if (s.rfind(key + "=", 0) == 0) return true;
  return false;
}

}  // namespace

void add_view_options(CLI::App& cmd, ViewOptions& o) {
  cmd.add_option("--eye", o.eye, "Camera position X,Y,Z");
  cmd.add_option("--target", o.target, "Point the camera looks at X,Y,Z");
  cmd.add_option("--up", o.up, "Up direction X,Y,Z (default 0,1,0)");
  cmd.add_option("--fov-y", o.fov_y,
                 "Vertical field of view, degrees (default: the camera's, else 60)");
  cmd.add_option("--camera", o.camera, "A perspective camera of the file, by name");
  cmd.add_option("--size", o.size, "Image WxH in pixels (default 1280x720)");
  cmd.add_option("--frames", o.frames,
                 "Views: the camera, then frames - 1 with eye and target moved by up to --jitter "
                 "(default 8; 1 for the given view alone)");
  cmd.add_option("--jitter", o.jitter,
                 "Largest camera move of --frames, metres (default: 10^-4 of the eye's distance to "
                 "the geometry's centre)");
  cmd.add_option("--path", o.path,
                 "Views from a file, one per line: ex,ey,ez,tx,ty,tz (eye, target); the first is "
                 "the PNG's and the rendering's");
}

void note_given(const CLI::App& cmd, ViewOptions& o) {
  o.jitter_given = cmd.count("--jitter") > 0;
  o.fov_given = cmd.count("--fov-y") > 0;
  o.frames_given = cmd.count("--frames") > 0;
  o.up_given = cmd.count("--up") > 0;
}

void check_view_options(const ViewOptions& o) {
  int w = 0, h = 0;
  parse_size(o.size, w, h);
  if (o.frames < 1 || o.frames > 1000)
    throw Error(ExitCode::usage, fmt::format("--frames {}: 1 to 1000", o.frames));
  if (o.jitter_given && (!(o.jitter >= 0) || !std::isfinite(o.jitter)))
    throw Error(ExitCode::usage, "--jitter: a distance in metres, 0 or more");
  if (o.fov_given && !(o.fov_y > 0 && o.fov_y < 180))
    throw Error(ExitCode::usage,
                fmt::format("--fov-y {}: degrees, above 0 and below 180", o.fov_y));
  if (!o.path.empty() && (!o.eye.empty() || !o.target.empty()))
    throw Error(ExitCode::usage, "--path gives the views: not with --eye and --target");
  if (!o.path.empty() && o.frames_given)
    throw Error(ExitCode::usage, "--path gives the views; --frames adds jittered ones: not both");
  if (!o.camera.empty() && (!o.eye.empty() || !o.target.empty()))
    throw Error(ExitCode::usage, "give either --camera or --eye and --target, not both");
  if (o.eye.empty() != o.target.empty())
    throw Error(ExitCode::usage, "--eye and --target go together");
  // A file's camera has its own up (its node's rotation): an --up beside it would be dropped.
  if (o.up_given && o.eye.empty() && o.path.empty())
    throw Error(ExitCode::usage,
                "--up orients the views of --eye and --target or of --path; the file's camera has "
                "its own up: drop --up or give the view");
}

AuditViews audit_views(const ViewOptions& o, const std::string& file, const SceneGeometry& g,
                       SceneOptions& scene) {
  AuditViews v;
  parse_size(o.size, v.width, v.height);
  const GltfCamera* file_camera = nullptr;
  v.camera = camera_of(o, file, g, v.width, v.height, &file_camera);
  // The views' moves scale with the scene: a ten-thousandth of the eye's distance to the centre
  // of what it looks at moves depths by a few storage codes at most set-ups' resolutions.
  double jitter = o.jitter;
  if (!o.jitter_given) {
    const auto c = bounding_box_centre(g);
    const auto& e = v.camera.eye;
    jitter = 1e-4 * std::hypot(c[0] - e[0], c[1] - e[1], c[2] - e[2]);
  }
  v.frames =
      o.path.empty() ? jittered_frames(v.camera, o.frames, jitter) : path_frames(o, v.camera);
  v.jitter = o.path.empty() && v.frames.size() > 1 ? jitter : 0.0;
  v.description = o.path.empty() ? v.camera.description
                                 : v.frames[0].description + " (first of " +
                                       std::to_string(v.frames.size()) + " views)";
  // The file camera's planes where the command line gives none, named as the camera's, so notes
  // and errors about them say where they came from.
  if (!scene.near.empty() || sets_key(scene, "near")) {
    v.near_source = "command line";
  } else if (file_camera && file_camera->znear > 0) {
    v.near_source = "camera";
    scene.implied.push_back({fmt::format("near={}", file_camera->znear),
                             fmt::format("the file camera's znear ({})", file_camera->znear)});
  }
  if (!scene.far.empty() || sets_key(scene, "far")) {
    v.far_source = "command line";
  } else if (file_camera) {
    v.far_source = "camera";
    scene.implied.push_back(
        file_camera->zfar > 0
            ? std::pair{fmt::format("far={}", file_camera->zfar),
                        fmt::format("the file camera's zfar ({})", file_camera->zfar)}
            : std::pair{std::string("far=inf"),
                        std::string("the file camera's missing zfar (no far plane)")});
  }
  return v;
}

}  // namespace depthprec::cli
