// The audit's text report on what a user's own files give it (docs/audit.md "Output"): the
// caption says where near and far come from, and a note says what a pair of one draw with itself
// is, since the tables name both sides alike.
#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>
#include <regex>

#include "host/output/audit_output.h"
#include "tests/support/audit_files.h"
#include "tests/support/files.h"
#include "tests/support/run_cli.h"

using namespace depthprec;
using Catch::Matchers::Contains;
using depthprec::test::run_cli;

namespace {

const std::string kTextAuditDir = test::audit_dir();

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
  CHECK_THAT(text, Contains("its own back faces behind its front ones"));
  r.setups[0].pairs[0].front_draw = 1;  // two draws: no such note
  SceneGeometry two = g;
  two.draws.push_back(g.draws[0]);
  two.draws[1].node = "node 1";
  two.draws[1].first_triangle = 2;
  r.geometry = &two;
  CHECK_THAT(unfolded(r), !Contains("fights itself"));
}

TEST_CASE("audit's text cuts long surface names to 24 characters; CSV and JSON keep them whole",
          "[audit][cli]") {
  const auto dir = test::empty_dir("audit_names");
  auto j = nlohmann::json::parse(test::bytes_of(kTextAuditDir + "decal_wall.gltf"));
  const std::string wall = "Building_A/Facade_North/Level_03/" + std::string(150, 'w') + "_LOD0",
                    decal = "Decals/Graffiti/" + std::string(150, 'd') + "_0042";
  j["nodes"][0]["name"] = wall;
  j["meshes"][0]["name"] = wall;  // a node named as its mesh is named by the node alone
  j["nodes"][1]["name"] = decal;
  j["meshes"][1]["name"] = decal;
  test::write_bytes(dir / "long.gltf", j.dump());
  const std::string args = "audit " + (dir / "long.gltf").string() +
                           " -t standard -f unorm24 --size 160x90 --no-fixes --no-timing -q";
  const auto text = run_cli(args);
  REQUIRE(text.exit_code == 0);
  // the start and the end of each name, "…" between: 24 characters
  const auto cut = [](const std::string& s) {
    return s.substr(0, 13) + "\u2026" + s.substr(s.size() - 10);
  };
  CHECK_THAT(text.output, Contains(cut(wall)) && Contains(cut(decal)) && !Contains(wall));
  // every line within the 120 columns (characters: "…" is three bytes), and a handful of blocks
  // of columns rather than one per column
  std::istringstream lines(text.output);
  int rows = 0;
  for (std::string line; std::getline(lines, line);) {
    rows += line.rfind("standard ", 0) == 0;
    size_t chars = 0;
    for (const char c : line) chars += (static_cast<unsigned char>(c) & 0xC0) != 0x80;
    CHECK(chars <= 120);
  }
  CHECK(rows <= 6);
  const auto csv = run_cli(args + " --format-out csv");
  CHECK_THAT(csv.output, Contains("," + wall + ",") && Contains("," + decal + ","));
  const auto json = nlohmann::json::parse(run_cli(args + " --format-out json").output);
  CHECK(json.at("setups").at(0).at("pairs").at(0).at("winner").at("node") == wall);
}
