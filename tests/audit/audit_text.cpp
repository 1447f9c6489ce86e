// The audit's text report on what a user's own files give it (docs/audit.md "Output"): the
// caption says where near and far come from, and a note says what a pair of one draw with itself
// is, since the tables name both sides alike.
#include <catch2/catch.hpp>
#include <regex>

#include "host/output/audit_output.h"

using namespace depthprec;
using Catch::Matchers::Contains;

namespace {

SceneGeometry one_draw_geometry() {
  SceneGeometry g;
  Draw d;
  d.node = "node 0";
  d.mesh = "mesh 0";
  d.world = mat_identity();
  d.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {0, 1, 1}};
  d.triangles = {{0, 1, 2}, {3, 4, 5}};
  g.draws = {d};
  g.triangles = 2;
  return g;
}

AuditReport report_of(const SceneGeometry& g, const std::string& near_source) {
  AuditReport r;
  r.geometry = &g;
  r.header = {{"file", "merged.glb"},
              {"camera", "eye (0, 0, 5) target (0, 0, 0) up (0, 1, 0)"},
              {"width", 64},
              {"height", 36},
              {"frames", 1},
              {"near", 1.0},
              {"far", 1e9},
              {"near_source", near_source},
              {"far_source", near_source}};
  SetupAudit s;
  s.pair = {Technique::standard, "unorm24", DepthRange::gl};
  r.setups = {s};
  return r;
}

// The text with its caption and notes unfolded: every run of spaces and line breaks one space.
std::string unfolded(const AuditReport& r) {
  return std::regex_replace(audit_text(r, "text", false), std::regex("\\s+"), " ");
}

}  // namespace

TEST_CASE("audit text: near and far the command line leaves out are marked as the scene's",
          "[audit]") {
  const SceneGeometry g = one_draw_geometry();
  // --eye and --target with no --near: not the file camera's znear, the scene's default
  const std::string scene = unfolded(report_of(g, "scene"));
  CHECK_THAT(scene, Contains("near 1 (the scene's default), far 1e+09 (the scene's default)"));
  CHECK_THAT(scene, Contains("(2 triangles in 1 draw)"));
  const std::string given = unfolded(report_of(g, "command line"));
  CHECK_THAT(given, Contains("near 1, far 1e+09:"));
  const std::string camera = unfolded(report_of(g, "camera"));
  CHECK_THAT(camera,
             Contains("near 1 (the file camera's znear), far 1e+09 (the file camera's zfar)"));
}

TEST_CASE("audit text: a pair of one draw with itself is said to be parts of one mesh", "[audit]") {
  // gltfpack merges a poster and its wall into one mesh: the tables name both sides alike
  const SceneGeometry g = one_draw_geometry();
  AuditReport r = report_of(g, "camera");
  FightPair p;
  p.winner_triangle = 0;
  p.front_triangle = 1;
  p.pixels = 42;
  r.setups[0].fighting_pixels = 42;
  r.setups[0].pairs = {p};
  const std::string text = unfolded(r);
  CHECK_THAT(text, Contains("standard/unorm24/gl: node 0/mesh 0#0 fights itself (42 pixels): two "
                            "parts of one draw"));
  CHECK_THAT(text, Contains("gltfpack"));
  r.setups[0].pairs[0].front_draw = 1;  // two draws: no such note
  SceneGeometry two = g;
  two.draws.push_back(g.draws[0]);
  two.draws[1].node = "node 1";
  two.draws[1].first_triangle = 2;
  r.geometry = &two;
  CHECK_THAT(unfolded(r), !Contains("fights itself"));
}
