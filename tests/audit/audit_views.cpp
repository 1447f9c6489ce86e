// audit's views as a user gives them: --frames and --jitter, --path, a file's cameras by their
// name or their node's (an orthographic one refused by name), --size, the file camera's planes,
// and what the output says of several views.
#include <catch2/catch.hpp>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "tests/support/audit_files.h"
#include "tests/support/files.h"
#include "tests/support/run_cli.h"

using namespace depthprec;
using Catch::Matchers::Contains;
using depthprec::test::run_cli;

namespace {

const std::string kViewsDir = test::audit_dir();

}  // namespace

TEST_CASE("audit's views: --frames adds jittered views, --path reads them from a file",
          "[audit][cli]") {
  const std::string base = kViewsDir +
                           "decal_wall.gltf -t standard -f unorm24 --size 160x90 "
                           "--no-fixes";
  const auto one = test::audit_json(base + " --frames 1");
  const auto four = test::audit_json(base + " --frames 4 --jitter 0.5");
  CHECK(test::audit_json(base).at("setups").at(0).at("frames") == 8);  // the default
  const auto& s1 = one.at("setups").at(0);
  const auto& s4 = four.at("setups").at(0);
  CHECK(s4.at("frames") == 4);
  CHECK(s4.at("pixels").get<int>() == 4 * s1.at("pixels").get<int>());
  CHECK(s4.at("fighting_pixels").get<int>() > 3 * s1.at("fighting_pixels").get<int>());
  // the same first view from a path file gives frame 0's counts
  const auto dir = test::empty_dir("audit_path");
  test::write_bytes(dir / "path.txt", "# eye, then target\n0,0,0, 0,0,-1\n0.5,0,0, 0.5,0,-1\n");
  const auto path = test::audit_json(base + " --fov-y 10 --path " + (dir / "path.txt").string());
  CHECK(path.at("setups").at(0).at("frames") == 2);
  CHECK(path.at("setups").at(0).at("pixels") == 2 * s1.at("pixels").get<int>());
  test::write_bytes(dir / "bad.txt", "0,0,0\n");
  const auto bad = run_cli("audit " + base + " --path " + (dir / "bad.txt").string());
  CHECK(bad.exit_code == 3);
  CHECK_THAT(bad.output, Contains("bad.txt:1: expected ex,ey,ez,tx,ty,tz"));
}

TEST_CASE("audit over several views says its pixel counts are sums and its PNG the first view",
          "[audit][cli]") {
  const auto dir = test::empty_dir("audit_views_said");
  const std::string args = kViewsDir +
                           "decal_wall.gltf -t standard -f unorm24 --size 160x90 --no-fixes "
                           "--frames 3 --jitter 0.5 --png " +
                           (dir / "v").string();
  const auto j = test::audit_json(args);
  CHECK(j.at("pixel_counts") == "summed over frames");
  CHECK(j.at("png_frame") == 0);
  CHECK(j.at("setups").at(0).at("pixels") == 3 * 160 * 90);
  const auto text = run_cli("audit " + args + " --no-timing -q");
  REQUIRE(text.exit_code == 0);
  // the caption, unfolded
  std::string flat = text.output;
  for (size_t at; (at = flat.find("\n  ")) != std::string::npos;) flat.replace(at, 3, " ");
  CHECK_THAT(flat, Contains("over 3 views (pixel counts are sums over the views; the PNGs are "
                            "view 1's)"));
}

TEST_CASE("audit names the file camera's znear and zfar as theirs, never as a --set",
          "[audit][cli]") {
  const std::string small = " --size 32x18 --no-fixes --no-timing";
  // infinite has no far plane: the note says whose far plane it ignores
  const auto note =
      run_cli("audit " + kViewsDir + "decal_wall.gltf -t infinite,standard -f float32" + small +
              " --format-out json");
  REQUIRE(note.exit_code == 0);
  CHECK_THAT(note.output, Contains("note: the file camera's zfar (100000): infinite has no far "
                                   "plane") &&
                              !Contains("--set"));
  const auto j = nlohmann::json::parse(note.output.substr(note.output.find('{')));
  CHECK(j.at("near_source") == "camera");
  CHECK(j.at("far_source") == "camera");
  // a camera whose zfar is nearer than its znear: the error blames the camera
  const auto dir = test::empty_dir("audit_camera_planes");
  auto g = nlohmann::json::parse(test::bytes_of(kViewsDir + "decal_wall.gltf"));
  g["cameras"][0]["perspective"]["znear"] = 10;
  g["cameras"][0]["perspective"]["zfar"] = 5;
  test::write_bytes(dir / "planes.gltf", g.dump());
  const auto bad =
      run_cli("audit " + (dir / "planes.gltf").string() + " -t standard -f float32" + small);
  CHECK(bad.exit_code == 3);
  CHECK_THAT(bad.output, Contains("the file camera's zfar (5): 'far' must be > near (10)") &&
                             !Contains("--set"));
  // what the command line gives is the command line's
  const auto typed = run_cli("audit " + (dir / "planes.gltf").string() +
                             " -t standard -f float32 --far 1e4" + small + " --format-out json");
  REQUIRE(typed.exit_code == 0);
  const auto t = nlohmann::json::parse(typed.output);
  CHECK(t.at("far_source") == "command line");
  CHECK(t.at("near_source") == "camera");
  CHECK(t.at("far") == 1e4);
}

// Blender exports a camera object "EyeCam" as a node holding camera "EyeCam_data": the user knows
// the node. An orthographic camera is refused by name, not reported missing.
TEST_CASE("audit finds a file camera by its node's name and refuses an orthographic one",
          "[audit][cli]") {
  const auto dir = test::empty_dir("audit_cameras");
  nlohmann::json j = nlohmann::json::parse(test::bytes_of(kViewsDir + "decal_wall.gltf"));
  j["cameras"][0]["name"] = "EyeCam_data";
  j["cameras"].push_back(
      {{"name", "Top_data"},
       {"type", "orthographic"},
       {"orthographic", {{"xmag", 10}, {"ymag", 10}, {"znear", 0.1}, {"zfar", 100}}}});
  for (auto& node : j["nodes"])
    if (node.contains("camera")) node["name"] = "EyeCam";
  j["nodes"].push_back({{"name", "Top"}, {"camera", 1}, {"translation", {0, 100, 0}}});
  j["scenes"][0]["nodes"].push_back(j["nodes"].size() - 1);
  const std::string file = (dir / "cams.gltf").string();
  test::write_bytes(file, j.dump());
  const std::string base = file + " -t standard -f unorm24 --size 160X90 --frames 1 --no-fixes";
  // the only perspective camera by default, by its node's name, and by its own
  CHECK(test::audit_json(base).at("camera") == "camera EyeCam_data");
  CHECK(test::audit_json(base + " --camera EyeCam").at("camera") == "camera EyeCam_data");
  CHECK(test::audit_json(base + " --camera EyeCam_data").at("width") == 160);
  const auto ortho = run_cli("audit " + base + " --camera Top");
  CHECK(ortho.exit_code == 3);
  CHECK_THAT(ortho.output, Contains("camera 'Top' is orthographic"));
  const auto missing = run_cli("audit " + base + " --camera Side");
  CHECK(missing.exit_code == 3);
  CHECK_THAT(missing.output, Contains("EyeCam_data (node EyeCam)"));
  CHECK_THAT(missing.output, Contains("Top_data (node Top) (orthographic)"));
}
