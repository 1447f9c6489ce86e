// What the audit's tests in several files share: the test scenes' folder, a scene's camera "main",
// and the audit command's JSON.
#pragma once

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>
#include <string>

#include "host/audit/audit_setup.h"
#include "tests/support/run_cli.h"

namespace depthprec::test {

// data/audit/, where scripts/make_audit_scenes.py writes the test scenes.
inline std::string audit_dir() {
  return std::string(DEPTHPREC_SOURCE_DIR) + "/data/audit/";
}

// The file camera "main" every test scene has, at w x h.
inline AuditCamera main_camera(const SceneGeometry& g, int w, int h) {
  for (const GltfCamera& c : g.cameras)
    if (c.name == "main") return gltf_view(c, w, h);
  FAIL("no camera main");
  return {};
}

// `depthprec audit ARGS` as JSON, without timings; the run must succeed.
inline nlohmann::json audit_json(const std::string& args) {
  const auto r = run_cli("audit " + args + " --format-out json --no-timing -q");
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  return nlohmann::json::parse(r.output);
}

}  // namespace depthprec::test
