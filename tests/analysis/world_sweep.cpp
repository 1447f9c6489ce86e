// world: the limit is a binade's, not a probed position's: every position below it holds, the
// first binade whose spacing reaches the separation is where it stops, and the spacing reported
// is binary32's there; camera-relative rendering never stops; bad requests are refused.
#include "host/analysis/world_sweep.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <nlohmann/json.hpp>

#include "host/analysis/world_bound.h"
#include "host/mts/mts_bound.h"
#include "host/mts/worst_case.h"
#include "tests/support/mts_fixture.h"
#include "tests/support/run_cli.h"

using namespace depthprec;
using Catch::Matchers::Contains;
using depthprec::test::run_cli;

namespace {

Scene sweep_scene() {
  return load_scene("", {"kernel=[32,32]", "frames=8", "sampling=paper",
                         R"(evaluate=[{"technique": "reversed", "format": "float32"}])"});
}

// The MTS at eye distance r.z with the world R along the request's direction.
double sweep_mts(const Scene& scene, const WorldRequest& r, double R) {
  const double n = std::sqrt(r.direction[0] * r.direction[0] + r.direction[1] * r.direction[1] +
                             r.direction[2] * r.direction[2]);
  const Scene s =
      with_world(scene, {R * r.direction[0] / n, R * r.direction[1] / n, R * r.direction[2] / n},
                 Transform::absolute);
  const MtsRow row = search_sampled(test::runtime(), s, scene.evaluate[0], {r.z}).at(0);
  return row.verdict() == Verdict::resolved ? row.mts : INFINITY;
}

// The spacing of binary32 in the binade holding x (x itself need not be a binary32).
double sweep_ulp32(double x) {
  int e = 0;
  std::frexp(x, &e);
  const float lo = std::ldexp(1.0f, e - 1);
  return static_cast<double>(std::nextafter(lo, INFINITY)) - static_cast<double>(lo);
}

}  // namespace

TEST_CASE("world's spacing limit is where a coordinate's binary32 spacing reaches the separation",
          "[world]") {
  const Scene scene = sweep_scene();
  WorldRequest r;
  r.z = 100;
  r.separation = 0.01;  // 2^-7 < 0.01 <= 2^-6: coordinates must stay below 2^17
  const double reach = plane_reach(scene, r);
  // Along (1,1,1) x and y reach 2^17 first (z is 100 behind them): R = sqrt(3) (2^17 - reach),
  // about 227 km, below 230,900 m where the MTS is measured at 0.013.
  const SpacingLimit diag = spacing_limit(r, scene, Transform::absolute);
  CHECK(diag.coordinate == std::ldexp(1.0, 17));
  CHECK(diag.spacing == std::ldexp(1.0, -6));
  CHECK(diag.spacing == sweep_ulp32(diag.coordinate));
  CHECK(diag.axis == 0);
  CHECK(diag.distance == Approx(std::sqrt(3.0) * (std::ldexp(1.0, 17) - reach)).epsilon(1e-12));
  CHECK(diag.distance < 230900);
  // just below it every coordinate's spacing is 2^-7
  CHECK(sweep_ulp32(diag.distance * (1 - 1e-9) / std::sqrt(3.0) + reach) == std::ldexp(1.0, -7));
  // A lateral direction stops where x does, whatever this view sees (2^17 - reach, not 3.3e7).
  r.direction = {1, 0, 0};
  const SpacingLimit lateral = spacing_limit(r, scene, Transform::absolute);
  CHECK(lateral.axis == 0);
  CHECK(lateral.distance == Approx(std::ldexp(1.0, 17) - reach).epsilon(1e-12));
  // Along the view, z: the planes are z = 100 ahead of the camera.
  r.direction = {0, 0, 1};
  const SpacingLimit along = spacing_limit(r, scene, Transform::absolute);
  CHECK(along.axis == 2);
  CHECK(along.distance == Approx(std::ldexp(1.0, 17) - reach + 100).epsilon(1e-12));
  // camera_relative keeps binary64's grid, relative_to_eye binary32's below 65536 (2^-8 at most)
  r.direction = {1, 1, 1};
  CHECK(std::isinf(spacing_limit(r, scene, Transform::camera_relative).distance));
  CHECK(std::isinf(spacing_limit(r, scene, Transform::relative_to_eye).distance));
  r.separation = 0.003;
  const SpacingLimit rte = spacing_limit(r, scene, Transform::relative_to_eye);
  CHECK(rte.coordinate == std::ldexp(1.0, 15));
  CHECK(rte.spacing == std::ldexp(1.0, -8));
}

TEST_CASE("world: every position below the limit holds, and the sawtooth reaches a spacing",
          "[world]") {
  const Scene scene = sweep_scene();
  WorldRequest r;
  r.z = 100;
  r.separation = 0.01;
  const nlohmann::json rec = world_record(test::runtime(), scene, scene.evaluate[0], r);
  const nlohmann::json& abs = rec["transforms"]["absolute"];
  const nlohmann::json& rel = rec["transforms"]["camera_relative"];
  CHECK(abs["mts_at_origin"] == rel["mts_at_origin"]);
  const double limit = abs["limit"].get<double>();
  const double spacing = abs["spacing"].get<double>();
  CHECK(abs["limit_from"] == "spacing");
  CHECK(limit == spacing_limit(r, scene, Transform::absolute).distance);
  CHECK(spacing == std::ldexp(1.0, -6));
  CHECK(spacing == sweep_ulp32(abs["coordinate"].get<double>()));
  CHECK(abs["axis"] == "x");
  // 230,900 m fails (a position a probe of powers of two and bisection passed over): the limit
  // is below it.
  CHECK(sweep_mts(scene, r, 230900) > r.separation);
  CHECK(limit < 230900);
  // Every position searched below the limit holds, and so do others in its last binade: the
  // sawtooth's peaks there, 0.9 of it, and just below it.
  for (const auto& p : abs["probes"])
    if (p[0].get<double>() < limit) CHECK(p[1].get<double>() <= r.separation);
  CHECK(abs["mts_below"].get<double>() <= r.separation);
  for (const double R :
       {0.9 * limit, sawtooth_peak(r, scene, Transform::absolute, 0.9 * limit),
        sawtooth_peak(r, scene, Transform::absolute, limit * (1 - 1e-6)), limit * (1 - 1e-9)}) {
    INFO("R = " << R);
    CHECK(R < limit);
    CHECK(sweep_mts(scene, r, R) <= r.separation);
  }
  // Past it the depth coordinate's peak needs nearly a full spacing, not half of one.
  REQUIRE(abs.contains("fails_at"));
  CHECK(abs["fails_at"].get<double>() >= limit);
  CHECK(abs["mts_at_fail"].get<double>() > r.separation);
  CHECK(abs["mts_at_fail"].get<double>() >= 0.95 * spacing);
  CHECK(rel["holds_to_bound"] == true);
  CHECK(rel["limit"].get<double>() == world_distance_limit(r));
  CHECK(rel["mts_below"].get<double>() <= r.separation);
}

TEST_CASE("world: a lateral direction's limit is where its spacing reaches the separation",
          "[world]") {
  const Scene scene = sweep_scene();
  WorldRequest r;
  r.z = 100;
  r.separation = 0.01;
  r.direction = {1, 0, 0};
  r.transforms = {Transform::absolute};
  const nlohmann::json abs =
      world_record(test::runtime(), scene, scene.evaluate[0], r)["transforms"]["absolute"];
  // This view sees x only through the planes' slope and holds far beyond; a camera turned toward
  // x would not, so the limit is x's spacing limit, about 131 km.
  CHECK(abs["limit"].get<double>() == Approx(std::ldexp(1.0, 17) - plane_reach(scene, r)));
  CHECK(abs["axis"] == "x");
  CHECK(abs["spacing"].get<double>() == std::ldexp(1.0, -6));
  CHECK(abs["holds_to_bound"] == false);
  CHECK_FALSE(abs.contains("fails_at"));
  CHECK(abs["mts_below"].get<double>() <= r.separation);
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

TEST_CASE("world's limit under the guaranteed MTS: every binade below it holds, its own does not",
          "[world][bound]") {
  const Scene scene = load_scene("", {});
  const EvalPair pair{Technique::reversed, "float32", DepthRange::zero_to_one};
  WorldRequest r;
  r.z = 100;
  r.separation = 0.01;
  const nlohmann::json j = world_bound(scene, pair, r, Transform::absolute);
  REQUIRE(j.contains("limit_bound"));
  const double R = j["limit_bound"].get<double>();
  // a binade of the coordinates begins there, as the sampled limit's do: R = 2^k sqrt(3)
  const double coordinate = R / std::sqrt(3.0);
  CHECK(coordinate == Approx(std::exp2(std::round(std::log2(coordinate)))).epsilon(1e-12));
  CHECK(j["mts_bound_at_origin"].get<double>() <= 0.01);
  CHECK_FALSE(j["limit_bound_to_limit"].get<bool>());
  const auto bound_at = [&](double d) {
    const double c = d / std::sqrt(3.0);
    return mts_bound(with_world(scene, {c, c, c}, Transform::absolute), pair, r.z).s;
  };
  for (const double d : {R / 4, R / 2, std::nextafter(R, 0.0)}) CHECK(bound_at(d) <= 0.01);
  CHECK((bound_at(R) > 0.01 || bound_at(std::nextafter(2 * R, 0.0)) > 0.01));
  // camera-relative rendering keeps the content's precision wherever it is.
  CHECK(world_bound(scene, pair, r, Transform::camera_relative)["limit_bound_to_limit"] == true);
}

TEST_CASE("an MTS below the world grid's reach is flagged, with the reach", "[world][mts]") {
  // (1e4, 0, 0): x's spacing 2^-10, through the slope tan 1 deg / cos 1 deg = 0.017458, and z's
  // 2^-22 at 1 + the plane's side (2.3 at a 60 degree view): 2 (2^-23 + 0.017458 (2^-11 +
  // 2^-23)) = 1.729e-5 for both planes. At the origin nothing is flagged.
  const std::string pair =
      "mts -t reversed -f float32 --near 0.1 --far 5e4 --fov 60 --distances 1 --frames 8 "
      "--kernel 24x24 --set sampling=paper --no-timing --format-out json";
  const auto away = run_cli(pair + " --set world_position=[1e4,0,0]");
  REQUIRE(away.exit_code == 0);
  const auto row = nlohmann::json::parse(away.output)["rows"][0];
  INFO(row.dump());
  CHECK_THAT(row["flags"].get<std::string>(), Contains("below_world_grid"));
  CHECK(row["world_grid_reach"].get<double>() == Approx(1.729e-5).epsilon(0.002));
  CHECK(row["mts"].get<double>() < row["world_grid_reach"].get<double>());
  const auto origin = run_cli(pair);
  REQUIRE(origin.exit_code == 0);
  const auto at0 = nlohmann::json::parse(origin.output)["rows"][0];
  CHECK_FALSE(at0.contains("world_grid_reach"));
  CHECK(at0["flags"].get<std::string>().find("below_world_grid") == std::string::npos);
}
