// Content away from the world origin (docs/spec.md 2, "World position"): at the origin every
// transform but relative_to_eye is today's pipeline; far from it the absolute transform loses
// what binary32 world coordinates must lose, camera_relative loses nothing, and relative to eye
// keeps the binary32 grid of its low part.
#include <catch2/catch.hpp>
#include <cmath>
#include <string>

#include "host/base/errors.h"
#include "host/mts/mts_bound.h"
#include "host/mts/mts_run.h"
#include "host/mts/refinement.h"
#include "host/mts/worst_case.h"
#include "interface/relative_to_eye.h"
#include "tests/support/mts_fixture.h"

using namespace depthprec;
using depthprec::test::mts_rows;

namespace {

double world_mts(const std::vector<std::string>& sets, double z) {
  const Scene scene = load_scene("", sets);
  return mts_rows(scene, Technique::reversed, "float32", DepthRange::zero_to_one, {z}).at(0).mts;
}

}  // namespace

TEST_CASE("at the world origin absolute and camera-relative are today's pipeline", "[world]") {
  for (const double z : {2.0, 100.0, 16384.0}) {
    INFO("z = " << z);
    const double today = world_mts({"frames=20"}, z);
    CHECK(world_mts({"frames=20", "world_position=[0,0,0]"}, z) == today);
    CHECK(world_mts({"frames=20", "pipeline.transform=camera_relative"}, z) == today);
    // premultiplied: P * V * MV with V the identity is P * MV
    CHECK(world_mts({"frames=20", "pipeline.compose=premultiplied"}, z) ==
          world_mts({"frames=20", "pipeline.compose=premultiplied", "world_position=[0,0,0]",
                     "pipeline.transform=absolute"},
                    z));
  }
}

TEST_CASE("far from the origin the absolute transform loses the world coordinate's ulp",
          "[world]") {
  // The planes' translation along the view axis, 3e5 - z, is a binary32 near 3e5: spacing 2^-5.
  // B separates from A once its translation rounds to the next binary32: at half that spacing,
  // as 299,900 is itself a binary32 (elsewhere in the binade anywhere from about 0 to a full
  // spacing: tests/analysis/world_sweep.cpp); until then the planes coincide.
  const double z = 100, spacing = std::ldexp(1.0, -5);
  const std::vector<std::string> far = {"frames=20", "world_position=[1e5,-2e5,3e5]"};
  const double absolute = world_mts(far, z);
  CHECK(absolute >= 0.5 * spacing * 0.99);
  CHECK(absolute <= 1.5 * spacing);
  // camera-relative forms the translation in binary64 first: the origin's answer, exactly
  std::vector<std::string> relative = far;
  relative.push_back("pipeline.transform=camera_relative");
  CHECK(world_mts(relative, z) == world_mts({"frames=20"}, z));
  // relative to eye keeps what the low part's binary32 keeps: 3e5 - z - 4 * 65536 = 37756 has a
  // spacing of 2^-8, and each vertex rounds on its own, so about one spacing
  std::vector<std::string> rte = far;
  rte.push_back("pipeline.transform=relative_to_eye");
  const double r = world_mts(rte, z);
  CHECK(r >= 0.5 * std::ldexp(1.0, -8));
  CHECK(r <= 2.0 * std::ldexp(1.0, -8));
  CHECK(r < absolute / 2);
}

TEST_CASE("attribution's storage limit is the eye's geometry, wherever the world is", "[world]") {
  // The storage-limited pipeline places the planes exactly, in eye space: moving the world moves
  // nothing it sees, under every transform, while the emulated MTS does move (absolute).
  RunControl c;
  c.attribute = true;
  const auto storage = [&](const std::vector<std::string>& sets) {
    const Scene scene = load_scene("", sets);
    return run_scene(test::runtime(), scene, {}, c).rows.at(0);
  };
  const std::vector<std::string> base = {
      "kernel=[48,48]", "frames=10", "sampling=paper", "distances=[100]",
      R"(evaluate=[{"technique": "reversed", "format": "unorm24"}])"};
  const MtsRow origin = storage(base);
  REQUIRE(std::isfinite(origin.storage_mts));
  for (const char* transform : {"absolute", "camera_relative", "relative_to_eye"}) {
    INFO(transform);
    std::vector<std::string> far = base;
    far.push_back("world_position=[1e5,1e5,1e5]");
    far.push_back(std::string("pipeline.transform=") + transform);
    CHECK(storage(far).storage_mts == origin.storage_mts);
  }
}

TEST_CASE("relative-to-eye positions split as Cesium's EncodedCartesian3 does", "[world]") {
  float high = 0, low = 0;
  dp_rte_encode(100000.0, &high, &low);
  CHECK(high == 65536.0f);
  CHECK(low == 34464.0f);
  dp_rte_encode(-100000.3, &high, &low);
  CHECK(high == -65536.0f);
  CHECK(low == static_cast<float>(-34464.3));
  dp_rte_encode(65535.5, &high, &low);
  CHECK(high == 0.0f);
  CHECK(low == 65535.5f);
  // the eye-space difference: high parts cancel exactly, the low parts' roundings remain
  float eh = 0, el = 0;
  dp_rte_encode(100000.0, &eh, &el);
  CHECK(dp_rte_eye(99900.001, eh, el) == static_cast<float>(34364.001) - 34464.0f);
}

TEST_CASE("world_position out of range or malformed is refused with the key", "[world]") {
  CHECK_THROWS_WITH(
      load_scene("", {"world_position=[2e12,0,0]"}),
      Catch::Matchers::Contains("world_position") && Catch::Matchers::Contains("2^40"));
  CHECK_THROWS_WITH(load_scene("", {"world_position=[1,2]"}),
                    Catch::Matchers::Contains("world_position"));
  CHECK_THROWS_WITH(load_scene("", {"pipeline.transform=eye_relative"}),
                    Catch::Matchers::Contains("camera_relative"));
}

TEST_CASE(
    "under mediump content 3000 units out along the view needs a unit, camera-relative far less",
    "[world][mediump]") {
  // A mediump vertex shader holds the planes' translation along the view axis, 3000 - 100, in
  // binary16, whose spacing from 2048 to 4096 is 2: B separates from A once its translation
  // rounds to the next value, about one unit. Camera-relative hands the shader -100 and -100 - s
  // instead, whose spacing is 2^-4, and the projection's binary16 rows then decide.
  const auto mediump_mts = [](const std::string& transform) {
    const Scene scene =
        load_scene("", {"frames=20", "world_position=[0,0,3000]",
                        "pipeline.shader_precision=mediump", "pipeline.transform=" + transform});
    MtsRow row = mts_rows(scene, Technique::standard, "unorm24", DepthRange::gl, {100.0}).at(0);
    set_mts_bound(row, scene);
    INFO(transform << ": mts " << row.mts << ", bound " << row.mts_bound);
    CHECK(row.mts_bound >= row.mts);  // the bound takes the shader's precision from the pipeline
    return row.mts;
  };
  const double absolute = mediump_mts("absolute"), relative = mediump_mts("camera_relative");
  CHECK(absolute >= 1.0);
  CHECK(absolute <= 2.0);
  CHECK(relative <= absolute / 10);
  CHECK(relative >= std::ldexp(1.0, -5));
  // Highp keeps far less of either away: binary32's spacing at 2900 is 2^-12.
  CHECK(world_mts({"frames=20", "world_position=[0,0,3000]"}, 100) < relative / 10);
  // Not modelled with relative to eye: refused with the key.
  CHECK_THROWS_WITH(
      load_scene("", {"pipeline.shader_precision=mediump", "pipeline.transform=relative_to_eye"}),
      Catch::Contains("pipeline.shader_precision"));
}

TEST_CASE("far from the origin the guaranteed MTS holds under every transform", "[world][bound]") {
  // relative_to_eye keeps a coordinate's low part, below 65536, in binary32 (Cesium's split): at
  // (1e5, -2e5, 3e5) its 2^-8 spacing is most of a vertex's error, which the bound once took as
  // 2^-46 of the world coordinate (1.85e-4 against an MTS of 3.6e-3 at z = 100).
  for (const std::string transform : {"absolute", "camera_relative", "relative_to_eye"}) {
    const Scene s = load_scene(
        "", {"frames=12", "kernel=[32,32]", "viewport=[32,32]", "world_position=[1e5,-2e5,3e5]",
             "pipeline.transform=" + transform, "distances=[2,100,5000,3e5]"});
    for (const EvalPair& pair :
         std::vector<EvalPair>{{Technique::reversed, "float32", DepthRange::zero_to_one},
                               {Technique::standard, "unorm24", DepthRange::gl},
                               {Technique::log_fragment, "float32", DepthRange::gl}}) {
      PairSource<ProbeEvaluator, MtsEvaluator> source(test::runtime(), pair);
      for (const MtsRow& r : search_sampled(source, s, pair, s.distances, {}, {})) {
        if (r.verdict() != Verdict::resolved || !std::isfinite(r.mts_bound)) continue;
        INFO(transform << " " << pair.label() << " z = " << r.z << ": mts " << r.mts
                       << ", mts_bound " << r.mts_bound);
        CHECK(r.mts_bound >= r.mts);
        CHECK(r.mts_bound >= r.fight_max);
      }
    }
  }
}
