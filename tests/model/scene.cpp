#include "host/model/scene.h"

#include <catch2/catch.hpp>
#include <cstdio>
#include <fstream>

#include "host/base/errors.h"

using namespace depthprec;
using Catch::Matchers::Contains;

namespace {
std::string write_temp(const std::string& name, const std::string& text) {
  const std::string path = std::string("/tmp/depthprec_test_") + name;
  std::ofstream(path) << text;
  return path;
}
}  // namespace

TEST_CASE("the embedded default is the paper's configuration", "[scene]") {
  const Scene s = load_scene("");
  CHECK(s.near == 1.0);
  CHECK(s.far == 1e9);
  CHECK(s.kernel_w == 200);
  CHECK(s.frames == 100);
  CHECK(s.distances.size() == 30);
  CHECK(s.distances.front() == 1.005);
  CHECK(s.distances.back() == 536870912.0);
  CHECK(s.rotation_step[1] == -0.45);
  CHECK(s.evaluate.size() == 14);
  CHECK(s.pipeline.compose == Compose::separate);
}

TEST_CASE("a scene file overrides only what it names", "[scene]") {
  const auto path = write_temp("partial.json", R"({"near": 0.5, "pipeline": {"divide": "exact"},
    "evaluate": [{"technique": "reversed", "format": "float32", "depth_range": "zero_to_one"}]})");
  const Scene s = load_scene(path);
  CHECK(s.near == 0.5);
  CHECK(s.far == 1e9);
  CHECK(s.pipeline.divide == Divide::exact);
  CHECK(s.pipeline.matrix_precision == MatrixPrecision::single);
  REQUIRE(s.evaluate.size() == 1);
  CHECK(s.evaluate[0].depth_range == DepthRange::zero_to_one);
}

TEST_CASE("a scene is named by its own name key, else its file, and --set marks it changed",
          "[scene]") {
  CHECK(load_scene("").name == "gilg2021");
  CHECK(load_scene("", {"near=2"}).name == "gilg2021+set");
  const auto unnamed = write_temp("harbour_flyover.json", R"({"near": 0.5})");
  CHECK(load_scene(unnamed).name == "depthprec_test_harbour_flyover");  // the file stem
  CHECK(load_scene(unnamed, {"far=1e4"}).name == "depthprec_test_harbour_flyover+set");
  const auto named = write_temp("named.json", R"({"name": "decals", "near": 0.5})");
  CHECK(load_scene(named).name == "decals");
  CHECK(load_scene(named, {"name=\"decals_v2\"", "far=1e4"}).name == "decals_v2");
}

TEST_CASE("overrides take JSON values and dotted keys", "[scene]") {
  const Scene s = load_scene(
      "", {"near=0.25", "kernel=[64,32]", "viewport=[64,32]", "pipeline.depth_range=zero_to_one",
           "far=inf", R"(evaluate=[{"technique": "infinite", "format": "float32"}])"});
  CHECK(s.near == 0.25);
  CHECK(s.kernel_w == 64);
  CHECK(s.kernel_h == 32);
  CHECK(s.pipeline.depth_range == DepthRange::zero_to_one);
  CHECK(std::isinf(s.far));
}

TEST_CASE("scene errors name the file, position and key", "[scene][errors]") {
  const auto bad_json = write_temp("bad.json", "{\n  \"near\": 1.0,\n  \"far\": ,\n}");
  CHECK_THROWS_WITH(load_scene(bad_json), Contains("bad.json:3:") && Contains("malformed JSON"));
  const auto unknown = write_temp("unknown.json", "{\n  \"nera\": 1.0\n}");
  CHECK_THROWS_WITH(load_scene(unknown),
                    Contains("unknown.json:2:3") && Contains("unknown key 'nera'"));
  const auto neg = write_temp("neg.json", "{\"near\": -1}");
  CHECK_THROWS_WITH(load_scene(neg), Contains("'near' must be > 0"));
  CHECK_THROWS_WITH(load_scene("", {"far=0.5"}), Contains("'far' must be > near"));
  CHECK_THROWS_WITH(load_scene("", {"frames=0"}), Contains("'frames' must be 1..1000000"));
  CHECK_THROWS_WITH(load_scene("", {"kernel=[0,10]"}), Contains("'kernel' sides must be 1..16384"));
  CHECK_THROWS_WITH(load_scene("", {"log_k=0"}), Contains("'log_k' must be > 0"));
  CHECK_THROWS_WITH(load_scene("", {"pipeline.compose=fused"}),
                    Contains("expected separate or premultiplied"));
  CHECK_THROWS_WITH(load_scene("", {R"(evaluate=[{"technique":"zbuffer","format":"float32"}])"}),
                    Contains("unknown technique 'zbuffer'") && Contains("reversed_infinite"));
  CHECK_THROWS_WITH(load_scene("", {R"(evaluate=[{"technique":"linear","format":"unorm40"}])"}),
                    Contains("unorm takes 1 to 32 bits"));
  CHECK_THROWS_WITH(load_scene("/nonexistent/scene.json"), Contains("cannot read scene file"));
  CHECK_THROWS_AS(load_scene("", {"distances=[1, -2]"}), InputError);
}

// Inputs the fuzzer (scripts/fuzz.sh) found to escape as something other than an InputError.
TEST_CASE("fuzzer regressions end in input errors", "[scene][errors][fuzz]") {
  // a number beyond binary64 made nlohmann::json throw out_of_range, not parse_error
  const std::string overflow =
      "6666666666e6666666666666&6666666{\n  \"name\": \"g66666666666e6666666666666&666666666{\n";
  CHECK_THROWS_AS(load_scene_text(overflow, "crash.json"), InputError);
  CHECK_THROWS_WITH(load_scene_text("{\"near\": 1e999999}", "big.json"),
                    Contains("malformed JSON") && Contains("big.json"));
}
