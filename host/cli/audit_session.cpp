#include "host/cli/audit_session.h"

#include "host/audit/audit_fixes.h"
#include "host/base/errors.h"
#include "host/base/interrupt.h"
#include "host/cli/audit_png_paths.h"
#include "host/output/audit_images.h"
#include "host/output/json_header.h"
#include "host/output/png_image.h"
#include "host/output/progress.h"
#include "host/render/render_audit.h"

namespace depthprec::cli {

nlohmann::json audit_header(const SessionOptions& o, const SceneGeometry& geometry,
                            const AuditViews& views, const Scene& scene,
                            const std::string& device) {
  nlohmann::json h = output_header("audit", device);
  h.update({{"file", o.file},
            {"triangles", geometry.triangles},
            {"draws", geometry.draws.size()},
            {"camera", views.description},
            {"fov_y_deg", views.camera.fov_y_deg},
            {"width", views.width},
            {"height", views.height},
            {"frames", views.frames.size()},
            {"jitter", views.jitter},
            {"near", scene.near},
            {"near_source", views.near_source},
            {"far", scene.far},
            {"far_source", views.far_source},
            {"source", o.source},
            {"scene_name", scene.name},
            {"scene", scene.json}});
  return h;
}

bool run_setups(OpenClRuntime* rt, const Scene& scene, const SceneGeometry& geometry,
                const AuditRequest& req, const SessionOptions& o, AuditReport& report) {
  if (o.source == "rendered") report.rendered = nlohmann::json::array();
  // Ctrl-C or SIGTERM stops between a set-up's stages (a stage under way runs on); the set-ups
  // finished by then stay in the report.
  install_interrupt_handlers();
  const auto stop_if_asked = [] {
    if (interrupt_requested()) throw Error(ExitCode::interrupted, "interrupted");
  };
  const int w = req.frames.at(0).width, h = req.frames.at(0).height;
  std::unique_ptr<GlContext> gl;
  Progress bar("audit", scene.evaluate.size(), o.progress, "set-ups");
  try {
    for (const EvalPair& pair : scene.evaluate) {
      const std::string label = pair.label();
      stop_if_asked();
      bar.doing(label + ": pixels");
      SetupAudit audit = audit_setup_pair(rt, scene, pair, geometry, req);
      nlohmann::json rendered;
      if (o.source == "rendered") {
        stop_if_asked();
        bar.doing(label + ": rendering");
        if (!gl) gl = std::make_unique<GlContext>(GlDeviceChoice::parse(o.gl_device));
        rendered = render_audit(*gl, scene, pair, geometry, req.frames[0], audit);
      }
      if (o.fixes) {
        stop_if_asked();
        bar.doing(label + ": fixes");
        FixRequest fix;
        fix.alternatives = default_alternatives(scene, pair);
        add_fixes(rt, audit_scene(scene, req.frames[0]), scene, geometry, req.frames, audit, fix);
      }
      // no stop before the PNGs: they take milliseconds, and the set-up's work is done
      if (!o.png.empty()) {
        write_png(png_name(o.png, pair, ""), w, h, fight_image(audit));
        write_png(png_name(o.png, pair, "-margin"), w, h, margin_image(audit));
        report.pngs.push_back(png_name(o.png, pair, ""));
        report.margin_pngs.push_back(png_name(o.png, pair, "-margin"));
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
    return false;
  }
  return true;
}

}  // namespace depthprec::cli
