// The audit's per-pixel pass: the kernel (kernels/audit.cl) against the host reference, pixel for
// pixel, on every test scene of data/audit/ under the ideal and llvmpipe pipelines; the loader's
// node transforms; and what each scene must show (fights, none, coplanar, only along an
// intersection, far from the origin).
#include <fmt/format.h>

#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>

#include "host/audit/audit.h"
#include "host/audit/audit_device.h"
#include "interface/audit_layout.h"
#include "tests/support/audit_files.h"
#include "tests/support/mts_fixture.h"

using namespace depthprec;

namespace {

const std::string kAuditData = test::audit_dir();

SceneGeometry audit_file(const std::string& name) {
  return load_gltf(kAuditData + name, 1u << 20);
}

Scene audit_scene_of(const std::vector<std::string>& sets) {
  std::vector<std::string> all = {"sampling=paper", "frames=4", "kernel=[24,24]"};
  all.insert(all.end(), sets.begin(), sets.end());
  return load_scene("", all);
}

SetupAudit audit_of(const std::string& file, const std::vector<std::string>& sets,
                    bool reference = false, int w = 192, int h = 108) {
  const SceneGeometry g = audit_file(file);
  const Scene scene = audit_scene_of(sets);
  AuditRequest req;
  req.frames = {test::main_camera(g, w, h)};
  req.reference = reference;
  return audit_setup_pair(&test::runtime(), scene, scene.evaluate.at(0), g, req);
}

}  // namespace

TEST_CASE("the audit kernel equals the host reference pixel for pixel", "[audit]") {
  const auto [file, near, far] = GENERATE(
      table<std::string, std::string, std::string>({{"decal_wall.gltf", "0.1", "1e5"},
                                                    {"slab_railing.gltf", "0.1", "1000"},
                                                    {"terrain_road.gltf", "0.1", "5000"},
                                                    {"intersecting_boxes.gltf", "0.1", "1000"},
                                                    {"far_from_origin.glb", "0.1", "1e5"},
                                                    {"drone_road.gltf", "0.1", "5000"},
                                                    {"ground_strip.gltf", "0.001", "10000"},
                                                    {"shelf_wall.gltf", "0.1", "100"},
                                                    {"rug_tiles.gltf", "0.03", "1000"}}));
  const auto [pairs, profile] = GENERATE(table<std::string, std::string>(
      {{R"([{"technique":"standard","format":"unorm24","depth_range":"gl"}])", "ideal"},
       {R"([{"technique":"reversed","format":"float32","depth_range":"zero_to_one"}])", "llvmpipe"},
       // the fragment-stage log in llvmpipe's form, which host and kernel share; the library's
       // (OpenCL's log, within 3 ulp) is not the host's std::log
       {R"([{"technique":"log_fragment","format":"unorm24","depth_range":"gl"}])", "llvmpipe"},
       {R"([{"technique":"log_vertex","format":"float32","depth_range":"gl"}])", "ideal"}}));
  CAPTURE(file, pairs, profile);
  const SceneGeometry g = audit_file(file);
  const Scene scene = audit_scene_of(
      {"near=" + near, "far=" + far, "evaluate=" + pairs, "pipeline.profile=" + profile});
  const AuditCamera cam = test::main_camera(g, 96, 54);
  const Scene s = audit_scene(scene, cam);
  const AuditSetup a = audit_setup(s, scene.evaluate.at(0), g, cam);
  const AuditPixels host = audit_reference(s, a);
  const AuditPixels dev = audit_device(test::runtime(), s, a);
  size_t differ = 0, covered = 0;
  for (size_t i = 0; i < host.flags.size(); ++i) {
    differ += host.winner[i] != dev.winner[i] || host.front[i] != dev.front[i] ||
              host.margin[i] != dev.margin[i] || host.flags[i] != dev.flags[i];
    covered += (host.flags[i] & AUDIT_COVERED) != 0;
  }
  CHECK(differ == 0);
  // the camera sees the scene, unless its triangles behind the eye are dropped (log_vertex does not
  // clip at the near plane, and its log is not finite behind the eye)
  if (a.non_finite == 0) CHECK(covered > host.flags.size() / 20);
}

TEST_CASE("the glTF loader composes node transforms and keeps names and draw order", "[audit]") {
  const SceneGeometry g = audit_file("far_from_origin.glb");
  REQUIRE(g.draws.size() == 2);
  CHECK(g.draws[0].node == "wall");
  CHECK(g.draws[1].node == "decal");  // drawn after the wall
  CHECK(g.draws[1].first_triangle == g.draws[0].triangles.size());
  // the parent "site" at (1e6, 0, 1e6) moves the children
  CHECK(g.draws[0].world[3] == 1e6);
  CHECK(g.draws[0].world[11] == 1e6);
  REQUIRE(g.cameras.size() == 1);
  CHECK(g.cameras[0].world[3] == 1e6);
  const SceneGeometry binary = audit_file("decal_wall.glb"), text = audit_file("decal_wall.gltf");
  REQUIRE(binary.triangles == text.triangles);
  CHECK(binary.draws[1].positions == text.draws[1].positions);
}

TEST_CASE("the decal 1 mm before a wall at 500 m fights in unorm24, not in reversed float32",
          "[audit]") {
  const SetupAudit standard = audit_of(
      "decal_wall.gltf",
      {"near=0.1", "far=1e5", R"(evaluate=[{"technique":"standard","format":"unorm24"}])"});
  CHECK(standard.fighting_pixels > 50);
  REQUIRE(standard.pairs.size() == 1);
  const SceneGeometry g = audit_file("decal_wall.gltf");
  CHECK(g.draws[standard.pairs[0].winner_draw].node == "wall");
  CHECK(g.draws[standard.pairs[0].front_draw].node == "decal");
  CHECK(standard.pairs[0].depth_median == Approx(500).epsilon(0.01));
  CHECK(standard.pairs[0].separation_median == Approx(0.001).epsilon(0.05));
  // every pixel the decal covers fights: the wall's code is the decal's or below it
  uint64_t decal_pixels = 0;
  for (size_t i = 0; i < standard.image.front.size(); ++i)
    decal_pixels +=
        standard.image.front[i] != AUDIT_NONE && &g.draw_of(standard.image.front[i]) == &g.draws[1];
  CHECK(standard.fighting_pixels == decal_pixels);
  const SetupAudit reversed = audit_of(
      "decal_wall.gltf",
      {"near=0.1", "far=1e5",
       R"(evaluate=[{"technique":"reversed","format":"float32","depth_range":"zero_to_one"}])"});
  CHECK(reversed.fighting_pixels == 0);
  CHECK(reversed.covered_pixels == standard.covered_pixels);
}

TEST_CASE("surfaces in one plane are coplanar pixels, not fights", "[audit]") {
  const SetupAudit a = audit_of(
      "slab_railing.gltf",
      {"near=0.1", "far=1000",
       R"(evaluate=[{"technique":"reversed","format":"float32","depth_range":"zero_to_one"}])"},
      false, 384, 216);
  CHECK(a.coplanar_pixels > 100);
  CHECK(a.fighting_pixels == 0);
  const SceneGeometry g = audit_file("slab_railing.gltf");
  for (const FightPair& p : a.pairs) {  // no fight between the slab and the base in its plane
    CAPTURE(g.draws[p.winner_draw].node, g.draws[p.front_draw].node, p.pixels);
    CHECK(p.separation_median > 0);
  }
}

TEST_CASE("intersecting boxes fight only along their intersection", "[audit]") {
  const SetupAudit a = audit_of(
      "intersecting_boxes.gltf",
      {"near=0.1", "far=1000", R"(evaluate=[{"technique":"standard","format":"unorm16"}])"}, false,
      384, 216);
  REQUIRE(a.fighting_pixels > 0);
  CHECK(a.fighting_pixels < a.covered_pixels / 20);
  for (const FightPair& p : a.pairs) CHECK(p.separation_min < 0.05);
}

TEST_CASE("far from the origin the absolute transform fights where camera-relative does not",
          "[audit]") {
  const std::string pair =
      R"(evaluate=[{"technique":"reversed","format":"float32","depth_range":"zero_to_one"}])";
  const SetupAudit absolute =
      audit_of("far_from_origin.glb", {"near=0.1", "far=1e5", pair, "pipeline.transform=absolute"});
  const SetupAudit relative = audit_of(
      "far_from_origin.glb", {"near=0.1", "far=1e5", pair, "pipeline.transform=camera_relative"});
  CHECK(absolute.fighting_pixels > 50);
  CHECK(relative.fighting_pixels == 0);
  CHECK(relative.covered_pixels > 0);
}

TEST_CASE("the glTF loader reads node matrices, 16-bit indices and unindexed triangles",
          "[audit]") {
  // One triangle's positions (0,0,0) (1,0,0) (0,1,0), then 16-bit indices 0 1 2 (padded).
  std::string bytes;
  for (float f : {0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f, 0.f})
    bytes.append(reinterpret_cast<const char*>(&f), 4);
  for (uint16_t i : {0, 1, 2, 0}) bytes.append(reinterpret_cast<const char*>(&i), 2);
  bytes.resize(45, '\0');  // a whole number of base64 groups: no padding characters
  static const char* b64 = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string enc;
  for (size_t k = 0; k < bytes.size(); k += 3) {
    const uint32_t v =
        (uint8_t(bytes[k]) << 16) | (uint8_t(bytes[k + 1]) << 8) | uint8_t(bytes[k + 2]);
    for (int c = 0; c < 4; ++c) enc += b64[(v >> (18 - 6 * c)) & 63];
  }
  const auto dir = std::filesystem::temp_directory_path() / "depthprec_test_gltf_forms";
  std::filesystem::create_directories(dir);
  const std::string gltf = fmt::format(
      R"({{"asset":{{"version":"2.0"}},"scenes":[{{"nodes":[0,1]}}],
"nodes":[{{"name":"moved","mesh":0,"matrix":[2,0,0,0, 0,2,0,0, 0,0,2,0, 10,20,30,1]}},
{{"name":"plain","mesh":1}}],
"meshes":[{{"name":"indexed","primitives":[{{"attributes":{{"POSITION":0}},"indices":1}}]}},
{{"name":"unindexed","primitives":[{{"attributes":{{"POSITION":0}}}}]}}],
"accessors":[{{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[1,1,0]}},
{{"bufferView":1,"componentType":5123,"count":3,"type":"SCALAR"}}],
"bufferViews":[{{"buffer":0,"byteOffset":0,"byteLength":36}},{{"buffer":0,"byteOffset":36,"byteLength":6}}],
"buffers":[{{"byteLength":{},"uri":"data:application/octet-stream;base64,{}"}}]}})",
      bytes.size(), enc);
  std::ofstream((dir / "forms.gltf").string()) << gltf;
  const SceneGeometry g = load_gltf((dir / "forms.gltf").string(), 100);
  REQUIRE(g.draws.size() == 2);
  CHECK(g.triangles == 2);
  CHECK(g.draws[0].triangles.at(0) == std::array<uint32_t, 3>{0, 1, 2});
  CHECK(g.draws[1].triangles.at(0) == std::array<uint32_t, 3>{0, 1, 2});
  // glTF's matrix is column-major: scale 2, then translation (10, 20, 30)
  const auto p = transform_point(g.draws[0].world, 1, 0, 0);
  CHECK(p == std::array<double, 3>{12, 20, 30});
  CHECK(g.draws[0].mesh == "indexed");
  CHECK(g.draws[1].node == "plain");
  CHECK_THROWS_WITH(load_gltf((dir / "forms.gltf").string(), 1),
                    Catch::Contains("2 triangles, more than the audit takes (1;"));
}
