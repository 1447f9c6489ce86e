// The views `audit` looks from (docs/audit.md "What it computes"), built once from the command
// line's own words and the file: the camera (--camera NAME, --eye/--target, or the file's only
// camera), the image, the jittered or listed views, and the near and far planes a file camera
// implies, each with where it came from so messages can name it.
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include "host/audit/audit_setup.h"
#include "host/cli/scene_options.h"
#include "host/model/scene_geometry.h"

namespace depthprec::cli {

// The options that say where the audit looks from, as the user typed them.
struct ViewOptions {
  std::string eye, target, up = "0,1,0", size = "1280x720", camera, path;
  double fov_y = 0;
  // Eight views by default: on the test scenes one view missed whole set-ups that fight
  // (drone_road standard/unorm24, rug_tiles reversed/float32), four found them, eight found every
  // set-up sixteen did, for about 0.5 s more than one view at 1280x720 (docs/audit.md).
  int frames = 8;
  double jitter = NAN;  // unset: 10^-4 of the distance from the eye to the geometry's centre
  bool fov_given = false, jitter_given = false, frames_given = false, up_given = false;
};

struct AuditViews {
  AuditCamera camera;               // the camera as given
  std::vector<AuditCamera> frames;  // frame 0 first: the camera, or the --path file's first
  int width = 0, height = 0;
  double jitter = 0;  // the largest move of the jittered views; 0 with one view or --path
  // Where near and far come from: "command line", "camera" (the file's) or "scene".
  std::string near_source = "scene", far_source = "scene";
  std::string description;  // the camera, or the first of the --path views
};

// --eye, --target, --up, --fov-y, --camera, --size, --frames, --jitter and --path on cmd.
void add_view_options(CLI::App& cmd, ViewOptions& options);
// After parsing: which of the options with a default the user gave.
void note_given(const CLI::App& cmd, ViewOptions& options);

// The options' own forms (--size, --frames, --jitter, --fov-y, which go together), checked before
// any file is read; Error with ExitCode::usage naming the option.
void check_view_options(const ViewOptions& options);

// The views of `file`'s geometry; where the command line gives no near or far (--near, --far,
// --set) a file camera's znear and zfar go into scene.implied, named as the camera's.
AuditViews audit_views(const ViewOptions& options, const std::string& file,
                       const SceneGeometry& geometry, SceneOptions& scene);

}  // namespace depthprec::cli
