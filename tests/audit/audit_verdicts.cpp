// What the audit tells a user to act on: coplanar pixels only where the coplanar surfaces are the
// ones seen, pixels at risk wherever another implementation of the model may store the other
// order (checked against the other profiles the emulator has, pixel for pixel), the MTS of a pair
// where the pair is, and a printed bias that removes the fight from every view it was seen in.
#include <catch2/catch.hpp>

#include "host/audit/audit.h"
#include "host/audit/audit_fixes.h"
#include "host/bias/bias_rule.h"
#include "interface/audit_layout.h"
#include "interface/bias_formula.h"
#include "tests/support/audit_files.h"
#include "tests/support/mts_fixture.h"

using namespace depthprec;

namespace {

const std::string kVerdictData = test::audit_dir();

Scene verdict_scene(const std::vector<std::string>& sets) {
  std::vector<std::string> all = {"sampling=paper", "frames=4", "kernel=[24,24]"};
  all.insert(all.end(), sets.begin(), sets.end());
  return load_scene("", all);
}

// The draw of pixel i's front surface, or -1.
int front_draw(const SceneGeometry& g, const AuditPixels& px, size_t i) {
  return px.front[i] == AUDIT_NONE ? -1
                                   : static_cast<int>(&g.draw_of(px.front[i]) - g.draws.data());
}

}  // namespace

TEST_CASE("coplanar surfaces hidden behind a nearer one are not coplanar pixels", "[audit]") {
  const std::string pair = R"(evaluate=[{"technique":"standard","format":"unorm24"}])";
  SECTION("a shelf whose back face lies in the wall, drawn after it: its top hides both") {
    const SceneGeometry g = load_gltf(kVerdictData + "shelf_wall.gltf", 1000);
    const Scene scene = verdict_scene({"near=0.1", "far=100", pair});
    AuditRequest req;
    req.frames = {test::main_camera(g, 320, 180)};
    const SetupAudit a = audit_setup_pair(&test::runtime(), scene, scene.evaluate[0], g, req);
    REQUIRE(a.covered_pixels > 0);
    CHECK(a.coplanar_pixels == 0);
    CHECK(a.fighting_pixels == 0);
  }
  SECTION(
      "a rug over two coplanar floor meshes: the floors are coplanar where seen, not under it") {
    const SceneGeometry g = load_gltf(kVerdictData + "rug_tiles.gltf", 1000);
    const Scene scene = verdict_scene({"near=0.03", "far=1000", pair});
    AuditRequest req;
    req.frames = {test::main_camera(g, 320, 180)};
    const SetupAudit a = audit_setup_pair(&test::runtime(), scene, scene.evaluate[0], g, req);
    uint64_t rug = 0, rug_coplanar = 0;
    for (size_t i = 0; i < a.image.flags.size(); ++i)
      if (front_draw(g, a.image, i) == 2) {
        ++rug;
        rug_coplanar += (a.image.flags[i] & AUDIT_COPLANAR) != 0;
      }
    REQUIRE(rug > 0);
    CHECK(rug_coplanar == 0);
    CHECK(a.coplanar_pixels > a.covered_pixels / 2);  // the floors themselves
  }
}

// The tolerance bounds every implementation of the model; the emulator has three (ideal,
// llvmpipe, softpipe): where one of them says the front surface wins and the pixel is not at risk,
// the others must keep the front surface too.
TEST_CASE("where a pixel is not at risk, every profile keeps the front surface", "[audit]") {
  const auto [file, near, far] = GENERATE(
      table<std::string, std::string, std::string>({{"drone_road.gltf", "0.1", "5000"},
                                                    {"ground_strip.gltf", "0.001", "10000"},
                                                    {"rug_tiles.gltf", "0.03", "1000"},
                                                    {"terrain_road.gltf", "0.1", "5000"},
                                                    {"decal_wall.gltf", "0.1", "1e5"},
                                                    {"mobile_site.gltf", "0.1", "1e5"},
                                                    {"slab_railing.gltf", "0.1", "1000"},
                                                    {"intersecting_boxes.gltf", "0.1", "1000"},
                                                    {"shelf_wall.gltf", "0.1", "100"},
                                                    {"far_from_origin.glb", "0.1", "1e5"}}));
  const std::string pairs = GENERATE(
      std::string(R"([{"technique":"standard","format":"float32","depth_range":"gl"}])"),
      std::string(R"([{"technique":"standard","format":"unorm24","depth_range":"gl"}])"),
      std::string(R"([{"technique":"reversed","format":"float32","depth_range":"zero_to_one"}])"),
      std::string(R"([{"technique":"log_fragment","format":"unorm24","depth_range":"gl"}])"));
  CAPTURE(file, pairs);
  const SceneGeometry g = load_gltf(kVerdictData + file, 1u << 20);
  const AuditCamera cam = test::main_camera(g, 160, 90);
  std::vector<AuditPixels> by_profile;
  for (const char* profile : {"ideal", "llvmpipe", "softpipe"}) {
    const Scene scene = verdict_scene({"near=" + near, "far=" + far, "evaluate=" + pairs,
                                       std::string("pipeline.profile=") + profile});
    const Scene s = audit_scene(scene, cam);
    by_profile.push_back(audit_reference(s, audit_setup(s, scene.evaluate[0], g, cam)));
  }
  uint64_t safe = 0, at_risk = 0;
  for (size_t p = 0; p < by_profile.size(); ++p)
    for (size_t q = 0; q < by_profile.size(); ++q) {
      const AuditPixels &a = by_profile[p], &b = by_profile[q];
      for (size_t i = 0; i < a.flags.size(); ++i) {
        const bool front_wins = (a.flags[i] & AUDIT_COVERED) && a.winner[i] == a.front[i];
        if (!front_wins || (a.flags[i] & (AUDIT_AT_RISK | AUDIT_NO_MARGIN | AUDIT_COPLANAR))) {
          at_risk += (a.flags[i] & AUDIT_AT_RISK) != 0;
          continue;
        }
        // the same surface in front by the exact ray (coverage may differ at edges), and there
        // the other profile keeps it, or a neighbour on its own seam
        if (b.front[i] != a.front[i]) continue;
        ++safe;
        CAPTURE(p, q, i % a.width, i / a.width);
        CHECK((b.winner[i] == b.front[i] || g.neighbours(b.winner[i], b.front[i])));
      }
    }
  // the tessellated terrain's road is mostly safe; a 5 km quad clipped at the near plane is not
  if (file == "terrain_road.gltf" && pairs.find("reversed") != std::string::npos)
    CHECK(safe > at_risk);
}

TEST_CASE("a millimetre at 500 m in reversed float32 is not at risk", "[audit]") {
  const SceneGeometry g = load_gltf(kVerdictData + "decal_wall.gltf", 1000);
  const Scene scene = verdict_scene(
      {"near=0.1", "far=1e5",
       R"(evaluate=[{"technique":"reversed","format":"float32","depth_range":"zero_to_one"}])"});
  AuditRequest req;
  req.frames = {test::main_camera(g, 320, 180)};
  const SetupAudit a = audit_setup_pair(&test::runtime(), scene, scene.evaluate[0], g, req);
  CHECK(a.fighting_pixels == 0);
  CHECK(a.at_risk_pixels == 0);
  CHECK(a.covered_pixels > 0);
}

// The bias a pair's fixes print, applied as the API applies it (a constant window-depth offset on
// every fragment of the front surface), leaves no pixel of the pair fighting in any of the views,
// over the whole image rather than the pixels the fix was checked on.
TEST_CASE("a printed bias removes the pair's fight from every view", "[audit]") {
  const SceneGeometry g = load_gltf(kVerdictData + "rug_tiles.gltf", 1000);
  const Scene scene = verdict_scene(
      {"near=0.03", "far=1000", R"(evaluate=[{"technique":"standard","format":"unorm24"}])"});
  const AuditCamera cam = test::main_camera(g, 480, 270);
  AuditRequest req;
  req.frames = jittered_frames(cam, 8, 0.0025);
  SetupAudit a = audit_setup_pair(&test::runtime(), scene, scene.evaluate[0], g, req);
  REQUIRE(!a.pairs.empty());
  FixRequest fix;
  add_fixes(&test::runtime(), audit_scene(scene, req.frames[0]), scene, g, req.frames, a, fix);
  const FightPair& p = a.pairs[0];
  CHECK(g.draws[p.front_draw].node == "rug");
  REQUIRE(p.bias_units);
  CHECK(*p.bias_units < 0);  // nearer under LESS
  const BiasRule rule = bias_rule(BiasOptions{}, scene.storage_format(scene.evaluate[0]));
  const Draw& rug = g.draws[p.front_draw];
  uint64_t fights = 0;
  for (const AuditCamera& view : req.frames) {
    const Scene s = audit_scene(scene, view);
    AuditSetup setup = audit_setup(s, scene.evaluate[0], g, view);
    for (size_t r = 0; r < setup.records.size(); ++r)
      if (setup.source[r] >= rug.first_triangle &&
          setup.source[r] < rug.first_triangle + rug.triangles.size()) {
        const auto& z = setup.window_depths[r];
        setup.records[r].bias =
            depth_bias(rule.units_term(*p.bias_units), 0, 0.0f, 0.0f, 0.0f, z[0], z[1], z[2]);
      }
    const AuditPixels px = audit_reference(s, setup);
    for (size_t i = 0; i < px.flags.size(); ++i)
      fights += (px.flags[i] & AUDIT_FIGHT) && front_draw(g, px, i) == p.front_draw;
  }
  CHECK(fights == 0);
}

TEST_CASE("a flat-shaded box's faces meet at split vertices: its edges are seams, not fights",
          "[audit]") {
  // A unit box as Blender exports it flat-shaded: four vertices a face, 24 in all, so faces that
  // meet at an edge share positions but no index.
  SceneGeometry g;
  Draw box;
  box.node = box.mesh = "box";
  box.world = mat_identity();
  const int faces[6][4][3] = {{{-1, -1, 1}, {1, -1, 1}, {1, 1, 1}, {-1, 1, 1}},
                              {{1, -1, -1}, {-1, -1, -1}, {-1, 1, -1}, {1, 1, -1}},
                              {{1, -1, 1}, {1, -1, -1}, {1, 1, -1}, {1, 1, 1}},
                              {{-1, -1, -1}, {-1, -1, 1}, {-1, 1, 1}, {-1, 1, -1}},
                              {{-1, 1, 1}, {1, 1, 1}, {1, 1, -1}, {-1, 1, -1}},
                              {{-1, -1, -1}, {1, -1, -1}, {1, -1, 1}, {-1, -1, 1}}};
  for (const auto& face : faces) {
    const auto base = static_cast<uint32_t>(box.positions.size());
    for (const auto& c : face)
      box.positions.push_back({0.5f * c[0] + 10.0f, 0.5f * c[1] + 0.5f, 0.5f * c[2] - 20.0f});
    box.triangles.push_back({base, base + 1, base + 2});
    box.triangles.push_back({base, base + 2, base + 3});
  }
  g.draws = {box};
  g.triangles = box.triangles.size();
  // the top face's triangles meet the front face's at split corners; the front and back faces
  // have no corner in common
  CHECK(g.neighbours(0, 8));
  CHECK(g.neighbours(1, 9));
  CHECK_FALSE(g.neighbours(0, 2));
  const Scene scene = verdict_scene(
      {"near=0.05", "far=500", R"(evaluate=[{"technique":"standard","format":"unorm24"}])"});
  AuditRequest req;
  req.reference = true;
  // the box 30 m away, seen from 6 m up (a yard Blender exported, a linked duplicate of a crate)
  req.frames =
      jittered_frames(look_at_camera({0, 6, 10}, {2, 0, -10}, {0, 1, 0}, 22.9, 1280, 720), 8, 3e-3);
  const SetupAudit a = audit_setup_pair(nullptr, scene, scene.evaluate[0], g, req);
  REQUIRE(a.covered_pixels > 0);
  CHECK(a.seam_pixels > 0);
  CHECK(a.fighting_pixels == 0);
  CHECK(a.pairs.empty());
}

TEST_CASE("a coplanar pair counts every pixel the surface drawn later in the plane lost",
          "[audit]") {
  // A 10 m decal exactly in a 100 m wall's plane, drawn after it (as far from the origin, where
  // binary32 node translations put a 1 cm decal into its wall): under LESS the wall keeps every
  // pixel whose codes tie, and the pair says so, whichever surface binary64 puts a hair nearer.
  SceneGeometry g;
  const auto quad = [](const std::string& name, float half) {
    Draw d;
    d.node = d.mesh = name;
    d.world = mat_identity();
    d.positions = {
        {-half, -half, -100}, {half, -half, -100}, {half, half, -100}, {-half, half, -100}};
    d.triangles = {{0, 1, 2}, {0, 2, 3}};
    return d;
  };
  g.draws = {quad("wall", 50), quad("decal", 5)};
  g.draws[1].first_triangle = 2;
  g.triangles = 4;
  const Scene scene = verdict_scene(
      {"near=0.5", "far=2000", R"(evaluate=[{"technique":"standard","format":"unorm24"}])"});
  for (const bool reference : {true, false}) {
    CAPTURE(reference);
    AuditRequest req;
    req.reference = reference;
    req.frames = {look_at_camera({0.3, 0.2, 0}, {0, 0, -100}, {0, 1, 0}, 22.9, 320, 180)};
    const SetupAudit a = audit_setup_pair(&test::runtime(), scene, scene.evaluate[0], g, req);
    uint64_t decal_lost = 0;
    for (size_t i = 0; i < a.image.flags.size(); ++i)
      decal_lost += (a.image.flags[i] & AUDIT_COPLANAR) && a.image.winner[i] != AUDIT_NONE &&
                    &g.draw_of(a.image.winner[i]) == &g.draws[0];
    REQUIRE(decal_lost > 1000);  // the decal's pixels
    CHECK(a.fighting_pixels == 0);
    REQUIRE(a.coplanar_pairs.size() == 1);
    const FightPair& p = a.coplanar_pairs[0];
    CHECK(p.winner_draw == 0);  // kept: the wall, drawn first
    CHECK(p.front_draw == 1);   // lost: the decal
    CHECK(p.pixels == decal_lost);
  }
}

// The published mobile case (docs/spec.md 2, "Shader precision"): content about 2000 m from the
// origin under a mediump vertex shader, where binary16 holds world coordinates to a metre or two.
// A decal 5 cm before a wall 20 m from the eye fights on every pixel it covers under the absolute
// transform, and every one of those fights is mediump's alone (highp shaders keep the decal);
// camera-relative matrices hand the shader small coordinates and nothing fights.
TEST_CASE("2000 m from the origin a mediump vertex shader makes fights highp does not",
          "[audit][mediump]") {
  const SceneGeometry g = load_gltf(kVerdictData + "mobile_site.gltf", 1000);
  const std::string pair = R"(evaluate=[{"technique":"standard","format":"unorm24"}])";
  AuditRequest req;
  req.frames = {test::main_camera(g, 160, 90)};
  const auto audit = [&](const std::string& precision, const std::string& transform) {
    const Scene scene =
        verdict_scene({"near=0.1", "far=1e5", pair, "pipeline.shader_precision=" + precision,
                       "pipeline.transform=" + transform});
    return audit_setup_pair(&test::runtime(), scene, scene.evaluate[0], g, req);
  };
  const SetupAudit mediump = audit("mediump", "absolute");
  REQUIRE(mediump.reduced_precision == "mediump");
  CHECK(mediump.fighting_pixels > mediump.covered_pixels / 10);
  CHECK(mediump.precision_only_pixels == mediump.fighting_pixels);
  const SetupAudit highp = audit("highp", "absolute");
  CHECK(highp.reduced_precision.empty());
  CHECK(highp.fighting_pixels == 0);
  // nor at risk: binary32's 2^-13 at 2000 m moves each vertex's eye position, which moves its
  // z_clip and w together, so the depth moves by n / w^2 of it, not by 1 / w as two independent
  // clip errors would count it (host/audit/depth_tolerance.cpp window_error)
  CHECK(highp.at_risk_pixels == 0);
  const SetupAudit relative = audit("mediump", "camera_relative");
  CHECK(relative.fighting_pixels == 0);
  CHECK(relative.precision_only_pixels == 0);
  // the GLSL ES 1.00 highp minimum holds 2000 to 2^-6: the 5 cm stays in front
  const SetupAudit es2 = audit("es2_highp", "absolute");
  CHECK(es2.reduced_precision == "es2_highp");
  CHECK(es2.fighting_pixels == 0);
  CHECK(es2.precision_only_pixels == 0);
}
