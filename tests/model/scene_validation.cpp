// Set-ups that cannot be measured are refused when the scene is read, with the key, the value
// and what is allowed; those that have a defined answer without a search get their verdict.
#include <catch2/catch.hpp>
#include <cmath>

#include "host/base/errors.h"
#include "tests/support/mts_fixture.h"

using namespace depthprec;
using namespace depthprec::test;
using Catch::Matchers::Contains;

namespace {

std::string refusal(const std::vector<std::string>& overrides) {
  try {
    load_scene("", overrides);
  } catch (const InputError& e) {
    return e.what();
  }
  return "accepted";
}

}  // namespace

TEST_CASE("a distance listed twice is refused, whatever its spelling", "[scene][errors]") {
  CHECK_THAT(refusal({"distances=[100,100]"}), Contains("lists 100 twice (entries 1 and 2)"));
  CHECK_THAT(refusal({"distances=[100,1e2]"}), Contains("lists 100 twice"));
  CHECK_THAT(refusal({"distances=[100,200,100]"}), Contains("(entries 1 and 3)"));
  CHECK(load_scene("", {"distances=[200,100,3]"}).distances ==
        std::vector<double>{200, 100, 3});  // any order
}

TEST_CASE("distances the binary32 pipeline cannot place are refused", "[scene][errors]") {
  CHECK_THAT(refusal({"distances=[1e300]"}), Contains("binary32's largest value"));
  CHECK_THAT(refusal({"distances=[3.4028234663852886e38]"}), Contains("binary32's largest value"));
  CHECK(load_scene("", {"distances=[1e38]", "far=\"inf\"",
                        "evaluate=[{\"technique\":\"infinite\",\"format\":\"float32\"}]"})
            .distances.size() == 1);
}

TEST_CASE("far = inf is refused for the techniques that need a far plane", "[scene][errors]") {
  for (const char* t :
       {"standard", "reversed", "log_vertex", "log_fragment", "linear", "w_buffer", "layered"}) {
    INFO(t);
    CHECK_THAT(refusal({"far=\"inf\"", std::string("evaluate=[{\"technique\":\"") + t +
                                           "\",\"format\":\"float32\"}]"}),
               Contains(std::string(t) + "/float32/") && Contains("needs a finite far plane"));
  }
  for (const char* t : {"infinite", "reversed_infinite", "inverse_w"})
    CHECK(refusal({"far=\"inf\"", std::string("evaluate=[{\"technique\":\"") + t +
                                      "\",\"format\":\"float32\"}]"}) == "accepted");
}

TEST_CASE("a kernel wider than the planes is refused by the commands", "[scene][errors]") {
  // The planes span plane_margin x viewport height = 220 pixels in both directions.
  const auto refused = [](const std::vector<std::string>& o) {
    try {
      check_planes_cover_kernel(load_scene("", o));
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  CHECK_THAT(refused({"viewport=[400,200]", "kernel=[225,200]"}),
             Contains("raise plane_margin to at least 1.19"));
  CHECK(refused({"viewport=[400,200]", "kernel=[215,200]"}) == "accepted");
}

// The search itself never accepts a probe with an uncovered kernel pixel: such a row has no MTS.
TEST_CASE("a kernel the planes leave uncovered gets the verdict uncovered", "[mts]") {
  const Scene scene = load_scene("", {"viewport=[40,20]", "kernel=[40,20]", "frames=3"});
  const MtsRow row =
      mts_rows(scene, Technique::standard, "unorm24", DepthRange::gl, {100.0}).front();
  CHECK(row.verdict() == Verdict::uncovered);
  CHECK(row.uncovered);
  CHECK(std::isinf(row.mts));
}

TEST_CASE("a pair that names no depth range gets its technique's own", "[scene]") {
  const Scene s = load_scene("", {"evaluate=[{\"technique\":\"reversed\",\"format\":\"float32\"},"
                                  "{\"technique\":\"inverse_w\",\"format\":\"float32\"},"
                                  "{\"technique\":\"standard\",\"format\":\"float32\"}]"});
  CHECK(s.evaluate[0].depth_range == DepthRange::zero_to_one);
  CHECK(s.evaluate[1].depth_range == DepthRange::zero_to_one);
  CHECK(s.evaluate[2].depth_range == DepthRange::gl);
  // A scene that names one range puts every such pair in it.
  const Scene g =
      load_scene("", {"pipeline.depth_range=gl",
                      "evaluate=[{\"technique\":\"reversed\",\"format\":\"float32\"}]"});
  CHECK(g.evaluate[0].depth_range == DepthRange::gl);
  CHECK_THAT(refusal({"pipeline.depth_range=opengl"}),
             Contains("expected gl, zero_to_one or technique"));
}

TEST_CASE("a distance nearer than the near plane is a verdict without probes", "[mts]") {
  const Scene scene = load_scene("", {"near=10", "kernel=[24,24]", "viewport=[24,24]", "frames=4"});
  const auto rows = mts_rows(scene, Technique::standard, "unorm24", DepthRange::gl, {5.0, 20.0});
  CHECK(rows[0].verdict() == Verdict::nearer_than_near_plane);
  CHECK(rows[0].probes == 0);
  CHECK(rows[0].flags() == "unresolvable,nearer_than_near_plane");
  CHECK(rows[1].verdict() == Verdict::resolved);
  // log_vertex maps every w in [0, far] into [0, 1]: nothing clips at the near plane.
  const auto log = mts_rows(scene, Technique::log_vertex, "float32", DepthRange::gl, {5.0});
  CHECK(log[0].verdict() == Verdict::resolved);
}
