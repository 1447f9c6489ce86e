// One audit run after its inputs are settled (host/cli/cmd_audit.cpp): every set-up's pixels, its
// rendering where asked, its fixes and PNGs, in order, with a progress line and Ctrl-C kept to the
// set-ups finished (docs/audit.md "Output").
#pragma once

#include <string>

#include "host/cli/audit_views.h"
#include "host/output/audit_output.h"

namespace depthprec {
class OpenClRuntime;
}

namespace depthprec::cli {

struct SessionOptions {
  std::string file;       // the glTF file, as named
  std::string source;     // emulated or rendered
  std::string gl_device;  // --gl-device
  std::string png;        // the PNG prefix (png_prefix), "" for none
  bool fixes = true, progress = false;
};

// The report's header: the file, its size, the views, the planes and where they came from.
nlohmann::json audit_header(const SessionOptions& options, const SceneGeometry& geometry,
                            const AuditViews& views, const Scene& scene, const std::string& device);

// Audits every set-up of scene into report.setups (and report.rendered, report.pngs); runtime may
// be null when the request asks for the reference and no fixes. Returns false when Ctrl-C or
// SIGTERM stopped it between stages (the set-ups finished by then are in the report).
bool run_setups(OpenClRuntime* runtime, const Scene& scene, const SceneGeometry& geometry,
                const AuditRequest& request, const SessionOptions& options, AuditReport& report);

}  // namespace depthprec::cli
