// shadow: the smallest shadow-map biases per cascade of a directional light that leave no acne
// on any receiver up to a slope limit, proven and witnessed, the shadow gap each costs and the
// same in the engines' settings (host/shadow/, docs/shadow.md).
#include <fmt/format.h>

#include <memory>
#include <nlohmann/json.hpp>

#include "host/base/errors.h"
#include "host/cli/commands.h"
#include "host/cli/scene_options.h"
#include "host/output/progress.h"
#include "host/output/report.h"
#include "host/output/shadow_output.h"
#include "host/output/text_table.h"
#include "host/render/gl_context.h"
#include "host/render/render_shadow.h"
#include "host/runtime/opencl_runtime.h"
#include "host/shadow/shadow_options.h"

namespace depthprec::cli {

namespace {

struct ShadowCliOptions {
  OutputOptions out;
  ShadowOptions shadow;
  std::string source = "emulated", gl_device = GlDeviceChoice{}.text;
};

void run_shadow(const ShadowCliOptions& o, const GlobalOptions& g) {
  const ShadowRequest r = shadow_request(o.shadow, o.source != "bound");
  check_writable(o.out.output);
  std::unique_ptr<OpenClRuntime> rt;
  if (r.emulate) rt = std::make_unique<OpenClRuntime>(g.device);
  std::unique_ptr<GlContext> gl;
  if (o.source == "rendered") gl = std::make_unique<GlContext>(GlDeviceChoice::parse(o.gl_device));
  nlohmann::json header = shadow_header(r);
  header["command"] = g.command_line;
  if (rt) header["device"] = rt->description();
  if (gl) header["renderer"] = gl->description();
  std::vector<nlohmann::json> records;
  {
    // On a terminal only, as every command's progress: logs and pipes stay clean.
    Progress bar("shadow", r.setup.cascades.size(), !g.quiet && stderr_is_terminal(),
                 r.setup.light == LightType::spot ? "receiver distances" : "cascades");
    for (size_t i = 0; i < r.setup.cascades.size(); ++i) {
      nlohmann::json rec = shadow_record(rt.get(), r, i);
      if (gl) rec["rendered"] = rendered_shadow_check(r, i, rec);
      records.push_back(rec);
      bar.advance();
    }
  }
  write_output(o.out.output, for_terminal(render_shadow_output(header, records, o.out.format_out),
                                          o.out.format_out));
  for (const auto& rec : records) {
    if (rec.contains("witnessed") && !rec["witnessed"].value("bound_clean", true))
      throw Error(ExitCode::internal,
                  fmt::format("shadow: cascade {}: the emulation found acne at the proven bias: "
                              "the bound is wrong (please report it with this command line)",
                              rec.value("cascade", 0)));
    if (rec.contains("rendered") && !rec["rendered"].value("clean_at_bound", true))
      throw Error(ExitCode::internal,
                  fmt::format("shadow: cascade {}: the rendered shadow pass shows acne at the "
                              "proven bias: the bound does not hold for this driver",
                              rec.value("cascade", 0)));
  }
}

}  // namespace

void add_shadow_command(CLI::App& app, GlobalOptions& global) {
  auto o = std::make_shared<ShadowCliOptions>();
  CLI::App* cmd = app.add_subcommand(
      "shadow",
      "The smallest shadow-map biases per cascade (constant, slope, normal offset) that leave\n"
      "no acne, the gap each costs, and each engine's settings (docs/shadow.md).\n"
      "Examples:\n"
      "  depthprec shadow\n"
      "      four cascades split at 10/40/150/600 m, 2048^2 float32, 3x3 PCF, slopes to 80 deg\n"
      "  depthprec shadow --format unorm16 --filter nearest --splits 20,60 --engines unity,bevy\n"
      "  depthprec shadow --extent 50 --light-near -100 --light-far 25 --source bound\n"
      "  depthprec shadow --light spot --spot-angle 60 --light-near 0.1 --light-far 50 "
      "--distances 2,10\n"
      "  depthprec shadow --splits 10,40 --source rendered --planes 64\n"
      "      checks the bias on the system's OpenGL: no acne at it, acne at 90 % of it");
  cmd->add_option("--light", o->shadow.light,
                  "directional (cascades; default) or spot (one perspective map)");
  cmd->add_option("--spot-angle", o->shadow.spot_angle, "A spot light's full cone, degrees (60)");
  cmd->add_option("--distances", o->shadow.distances,
                  "A spot light's receiver distances along its axis, metres (default 5,20,50)")
      ->delimiter(',');
  cmd->add_option("--splits", o->shadow.splits,
                  "Camera distances where cascades end, metres (default 10,40,150,600)")
      ->delimiter(',');
  cmd->add_option("--camera-near", o->shadow.camera_near, "Where the first cascade starts, metres");
  cmd->add_option("--fov", o->shadow.fov,
                  "The camera's vertical field of view, degrees (default 60)");
  cmd->add_option("--aspect", o->shadow.aspect, "The camera's aspect, width/height (default 16/9)");
  cmd->add_option("--caster-padding", o->shadow.caster_padding,
                  "Metres the light's box reaches beyond each cascade's sphere toward the light "
                  "(default 0: pancaking)");
  cmd->add_option("--extent", o->shadow.extent,
                  "Cascades as light boxes: each square's side, metres")
      ->delimiter(',');
  cmd->add_option("--light-near", o->shadow.light_near,
                  "Each box's near side, metres along the light")
      ->delimiter(',');
  cmd->add_option("--light-far", o->shadow.light_far, "Each box's far side, metres along the light")
      ->delimiter(',');
  cmd->add_option("--resolution", o->shadow.resolution,
                  "Texels per side of each cascade (default 2048)");
  cmd->add_option("--format", o->shadow.format, "unorm16, unorm24 or float32 (default float32)");
  cmd->add_flag("--reversed", o->shadow.reversed, "Reversed depth: nearer the light is larger");
  cmd->add_option("--filter", o->shadow.filter,
                  "nearest, pcf2x2, pcfN (N x N hardware comparisons) or tentN (default pcf3)");
  cmd->add_option("--api", o->shadow.api, "gl, d3d or vulkan: whose raster bias rule (default gl)");
  cmd->add_option("--r-unorm", o->shadow.r_unorm, "pow2, step, double_step or double_pow2");
  cmd->add_option("--slope", o->shadow.slope, "The raster slope: max or sqrt (default max)");
  cmd->add_option("--slope-max", o->shadow.slope_max,
                  "The largest angle between a receiver's normal and the light, degrees (default "
                  "80)");
  cmd->add_option("--world-position", o->shadow.world_position,
                  "The cascades' centre, metres: X,Y,Z")
      ->delimiter(',');
  cmd->add_option("--light-elevation", o->shadow.light_elevation,
                  "The light above the horizon, degrees (52)");
  cmd->add_option("--light-azimuth", o->shadow.light_azimuth,
                  "The light's azimuth, degrees (default 30)");
  cmd->add_option("--engines", o->shadow.engines,
                  "Engines to convert to (default all): " + engine_names())
      ->delimiter(',');
  cmd->add_option("--bound-model", o->shadow.bound_model,
                  "What the proof allows the GPU: " + bound_model_names() + " (default binary32)");
  cmd->add_option("--source", o->source,
                  "bound (the proof alone), emulated (also the emulation's witnessed minimum; "
                  "default) or rendered (also a shadow pass on the system's OpenGL)")
      ->check(CLI::IsMember({"bound", "emulated", "rendered"}));
  cmd->add_option("--planes", o->shadow.planes,
                  "Receiver planes the emulation samples (default 2048)");
  cmd->add_option("--grid", o->shadow.grid, "Receiver points per texel side (default 8)");
  cmd->add_option("--seed", o->shadow.seed, "The sampling's seed (default 1)");
  add_gl_device_option(cmd, o->gl_device);
  o->out.add_to(*cmd);
  cmd->callback([o, &global, cmd]() {
    o->shadow.spot_angle_given = cmd->count("--spot-angle") > 0;
    run_shadow(*o, global);
  });
}

}  // namespace depthprec::cli
