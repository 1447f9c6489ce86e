// world: the sweep over the world distance finds where the absolute transform stops keeping the
// separation, and camera-relative rendering never does; bad requests are refused.
#include "host/analysis/world_sweep.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <nlohmann/json.hpp>

#include "tests/support/mts_fixture.h"
#include "tests/support/run_cli.h"

using namespace depthprec;
using Catch::Matchers::Contains;
using depthprec::test::run_cli;

TEST_CASE("world: absolute fails where the world coordinate's spacing does, camera-relative never",
          "[world]") {
  const Scene scene =
      load_scene("", {"kernel=[32,32]", "frames=8", "sampling=paper",
                      R"(evaluate=[{"technique": "reversed", "format": "float32"}])"});
  WorldRequest r;
  r.z = 100;
  r.separation = 0.01;
  const nlohmann::json rec = world_record(test::runtime(), scene, scene.evaluate[0], r);
  const nlohmann::json& abs = rec["transforms"]["absolute"];
  const nlohmann::json& rel = rec["transforms"]["camera_relative"];
  CHECK(abs["mts_at_origin"] == rel["mts_at_origin"]);
  // Along (1,1,1) the view-axis coordinate is R / sqrt(3): its binary32 spacing passes 0.01 (the
  // planes separate at half a spacing) between 2^16 and 2^18 of it.
  const double R = abs["largest_world_distance"].get<double>();
  CHECK(R >= std::ldexp(1.0, 16));
  CHECK(R <= std::sqrt(3.0) * std::ldexp(1.0, 18));
  CHECK(abs["mts_there"].get<double>() <= 0.01);
  CHECK(abs["mts_at_fail"].get<double>() > 0.01);
  CHECK(abs["fails_at"].get<double>() / R <= 1 + r.precision);
  CHECK(rel["holds_to_limit"] == true);
  CHECK(rel["largest_world_distance"].get<double>() == world_distance_limit(r));
}

TEST_CASE("world refuses what it cannot sweep", "[world][cli]") {
  const auto none = run_cli("world -t reversed -f float32 --distance 100");
  CHECK(none.exit_code == 3);
  CHECK_THAT(none.output, Contains("--separation"));
  const auto moved =
      run_cli("world -t reversed -f float32 --separation 0.01 --set 'world_position=[1,0,0]'");
  CHECK(moved.exit_code == 3);
  CHECK_THAT(moved.output, Contains("world_position"));
  const auto dir = run_cli("world -t reversed -f float32 --separation 0.01 --direction 0,0,0");
  CHECK(dir.exit_code == 3);
  CHECK_THAT(dir.output, Contains("--direction"));
  const auto transform =
      run_cli("world -t reversed -f float32 --separation 0.01 --transforms eye_relative");
  CHECK(transform.exit_code == 3);
  CHECK_THAT(transform.output, Contains("relative_to_eye"));
}
