// advise: the smallest near plane that holds is found by bisection, the next one down fails, and
// the emulator's MTS agrees: at the near plane found the MTS is within the separation, below it
// a distance needs more; the far plane likewise. Batch behaviour: tests/batch/batch.cpp.
#include "host/analysis/advise.h"

#include <fmt/format.h>

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "host/analysis/advise_bound.h"
#include "host/mts/mts_bound.h"
#include "tests/support/mts_fixture.h"
#include "tests/support/run_cli.h"

using namespace depthprec;
using Catch::Matchers::Contains;
using depthprec::test::kSmallScene;
using depthprec::test::run_cli;

namespace {

// The paper's frames: these tests check the bisections to near_precision; under worst-case
// sampling the answer also moves past values that fail its safety checks (the test at the end).
Scene advise_scene(const std::string& pairs) {
  return load_scene("", {"kernel=[24,24]", "frames=4", "sampling=paper", "evaluate=" + pairs});
}

}  // namespace

TEST_CASE("advise finds the smallest near plane that holds, and the next one down fails",
          "[advise]") {
  const Scene scene =
      advise_scene(R"([{"technique": "standard", "format": "unorm24", "depth_range": "gl"}])");
  AdviseRequest r;
  r.z_min = 10;
  r.z_max = 1000;
  r.separation = 0.05;
  validate(r, scene);
  const EvalPair pair = scene.evaluate[0];
  const auto rec = advise_record(test::runtime(), scene, pair, r);
  REQUIRE(rec.contains("smallest_near"));
  REQUIRE(rec.contains("next_near"));
  const double n = rec["smallest_near"], below = rec["next_near"];
  CHECK(below < n);
  CHECK(n / below <= 1 + r.near_precision);
  CHECK(near_holds(test::runtime(), scene, pair, r, n));
  CHECK(mts_within(test::runtime(), scene, pair, r, n));
  // the next near plane down fails: a probe at the separation fights, or the MTS exceeds it
  CHECK_FALSE((near_holds(test::runtime(), scene, pair, r, below) &&
               mts_within(test::runtime(), scene, pair, r, below)));
  // standard projection's error grows as z^2 / near: the farthest content decides
  CHECK(rec["fails_at"] == 1000.0);

  // The MTS search on the same pipeline, run as `mts` runs it, agrees at n: every checked
  // distance resolves within the separation.
  const auto at_n = test::mts_rows(with_near(scene, n), pair.technique, pair.format,
                                   pair.depth_range, advise_distances(r));
  for (const auto& row : at_n) CHECK(row.mts <= r.separation);
  // and, standard's error growing as z^2 / near, a near plane a tenth of n is far from enough
  const auto at_tenth = test::mts_rows(with_near(scene, n / 10), pair.technique, pair.format,
                                       pair.depth_range, {1000.0});
  CHECK(at_tenth.front().mts > 5 * r.separation);
}

TEST_CASE("advise ranks set-ups and says which cannot meet the separation", "[advise][cli]") {
  const auto r = run_cli("advise --range 10,1000 --separation 0.05 " + kSmallScene +
                         "-t standard,reversed,linear -f float32,unorm24 --format-out json");
  REQUIRE(r.exit_code == 0);
  const auto j = nlohmann::json::parse(r.output);
  CHECK(j["kind"] == "advise");
  REQUIRE(j["records"].size() == 6);
  REQUIRE(j["ranking"].size() == 6);
  // reversed float32 in [0,1] holds from the floor; standard's error grows as z^2 / near, so it
  // needs the largest near plane. Linear unorm24 with far = 1e9 has codes of 60 units and never
  // resolves 0.05, but with its far plane pulled in to the content it does.
  CHECK(j["ranking"][0] == "reversed/float32/zero_to_one");
  CHECK(j["ranking"][5].get<std::string>().rfind("standard/", 0) == 0);
  for (const auto& rec : j["records"])
    if (rec["technique"] == "linear" && rec["format"] == "unorm24") {
      CHECK(rec.contains("smallest_near"));
      CHECK(rec["far_tightened"] == true);
    }
}

TEST_CASE("advise refuses what it cannot answer", "[advise][cli][errors]") {
  const std::string base = "advise -t standard -f unorm24 " + kSmallScene;
  CHECK(run_cli(base + "--range 10,1000 --separation 0").exit_code == 3);
  CHECK(run_cli(base + "--range -1,1000 --separation 1").exit_code == 3);
  CHECK(run_cli(base + "--range 1000,10 --separation 1").exit_code == 3);
  const auto both = run_cli(base + "--range 10,1000 --separation 1 --relative 1e-3");
  CHECK(both.exit_code == 3);
  CHECK_THAT(both.output, Contains("exactly one"));
  const auto far = run_cli(base + "--range 10,1000 --separation 1 --far 500");
  CHECK(far.exit_code == 3);
  CHECK_THAT(far.output, Contains("far plane"));
  // The near plane and the distances are what advise computes: given, they were ignored silently.
  for (const char* option : {"--near 0.5", "--set near=0.5", "--distances 20,40"}) {
    INFO(option);
    const auto given = run_cli(base + "--range 10,1000 --separation 1 " + option);
    CHECK(given.exit_code == 2);
    CHECK_THAT(given.output, Contains(std::string("advise: ") + option) && Contains("drop"));
  }
}

TEST_CASE("advise's far plane is the farthest that holds, and the next one out fails",
          "[advise][far]") {
  // Linear depth in unorm24 resolves (f - n) / 2^24 everywhere: with the scene's far plane at
  // 1e9 no near plane meets 0.01, pulled in to the content it does, and it may move out again
  // until (f - n) / 2^24 reaches the separation.
  const Scene scene =
      advise_scene(R"([{"technique": "linear", "format": "unorm24", "depth_range": "gl"}])");
  AdviseRequest r;
  r.z_min = 100;
  r.z_max = 1000;
  r.separation = 0.01;
  const EvalPair pair = scene.evaluate[0];
  const auto rec = advise_record(test::runtime(), scene, pair, r);
  REQUIRE(rec.contains("smallest_near"));
  CHECK(rec["far_tightened"] == true);
  REQUIRE(rec.contains("largest_far"));
  REQUIRE(rec.contains("next_far"));
  const double n = rec["smallest_near"], f = rec["largest_far"], out = rec["next_far"];
  CHECK(out > f);
  CHECK(out / f <= 1 + r.near_precision);
  CHECK(f == Approx(r.separation * 16777216).epsilon(0.1));
  CHECK(near_holds(test::runtime(), scene, pair, r, n, nullptr, f));
  CHECK(mts_within(test::runtime(), scene, pair, r, n, f));
  CHECK_FALSE((near_holds(test::runtime(), scene, pair, r, n, nullptr, out) &&
               mts_within(test::runtime(), scene, pair, r, n, out)));
}

TEST_CASE("advise's near plane holds under worst-case sampling as printed and beyond it",
          "[advise][worst_case][cli]") {
  // The paper's frames alone answered 4.216 here, where the worst case needs 0.01021.
  const std::string setup = "-t standard -f unorm24 --far 5e4";
  const auto a = run_cli("advise --range 500,500 --separation 0.01 " + setup +
                         " --no-timing --format-out json");
  REQUIRE(a.exit_code == 0);
  const auto rec = nlohmann::json::parse(a.output)["records"][0];
  REQUIRE(rec.contains("smallest_near"));
  const double n = rec["smallest_near"];
  CHECK(std::stod(fmt::format("{:.4g}", n)) == n);  // prints as itself
  CHECK(rec["next_near"].get<double>() < n);
  for (const double near : {n, n * 1.01, n * 1.1, n * 2, 5.0, 10.0}) {
    INFO("near " << near);
    const auto m =
        run_cli(fmt::format("mts {} --near {:.17g} --distances 500 --no-timing "
                            "--format-out json",
                            setup, near));
    REQUIRE(m.exit_code == 0);
    const auto row = nlohmann::json::parse(m.output)["rows"][0];
    CHECK(row["verdict"] == "resolved");
    CHECK(row["mts"].get<double>() <= 0.01);
  }
}

TEST_CASE("round_printed rounds to the four digits text shows, on the side asked",
          "[advise][worst_case]") {
  CHECK(round_printed(4.21601, true) == 4.217);
  CHECK(round_printed(4.21601, false) == 4.216);
  CHECK(round_printed(4.216, true) == 4.216);  // already printed as itself
  CHECK(round_printed(4.32e6 + 1, false) == 4.32e6);
  CHECK(round_printed(0.0012345, true) == 0.001235);
  CHECK(round_printed(999.95, true) == 1000);
}

TEST_CASE(
    "advise's near plane under the guaranteed MTS clears the separation, and one a tenth "
    "nearer does not",
    "[advise][bound]") {
  const Scene scene = load_scene("", {"far=5e4"});
  const EvalPair pair{Technique::standard, "unorm24", DepthRange::gl};
  AdviseRequest r;
  r.z_min = r.z_max = 500;
  r.separation = 0.01;
  const nlohmann::json j = bound_answer(scene, pair, r);
  REQUIRE(j.contains("near_bound"));
  const double n = j["near_bound"].get<double>();
  CHECK(mts_bound(with_near(scene, n), pair, 500).s <= 0.01);
  CHECK(mts_bound(with_near(scene, n / 1.1), pair, 500).s > 0.01);
  CHECK(n == round_printed(n, true));  // as text prints it
  // standard has a far plane: with that near the bound holds at the far plane found, and linear
  // (whose precision the far plane spreads) gets a finite one.
  REQUIRE(j.contains("far_bound"));
  CHECK(bound_within(scene, pair, r, n, j["far_bound"].get<double>()));
  const EvalPair linear{Technique::linear, "unorm24", DepthRange::gl};
  AdviseRequest wide = r;
  wide.separation = 1;
  const nlohmann::json lj = bound_answer(scene, linear, wide);
  REQUIRE(lj.contains("far_bound"));
  CHECK_FALSE(lj["far_bound_to_ceiling"].get<bool>());
  const double f = lj["far_bound"].get<double>();
  CHECK(bound_within(scene, linear, wide, lj["near_bound"].get<double>(), f));
  CHECK_FALSE(bound_within(scene, linear, wide, lj["near_bound"].get<double>(), 2 * f));
  // The sampled answer sits nearer: the bound costs a near plane further out.
  const auto cli = run_cli(
      "advise --range 500,500 --separation 0.01 -t standard -f unorm24 --far 5e4 "
      "--format-out json --no-timing");
  REQUIRE(cli.exit_code == 0);
  const auto rec = nlohmann::json::parse(cli.output)["records"].at(0);
  CHECK(rec["near_bound"].get<double>() == n);
  CHECK(rec["smallest_near"].get<double>() < n);
}

// Under Vulkan's minimum (the vulkan_min profile: its adversary, and rows bounded under its
// envelope), depth interpolated to 1 part in 10^5 decides: the near plane that holds 0.05 at 500
// is an order of magnitude farther out than the default model's, holds under the envelope's own
// bound, and the sampled answer (its adversary's worst case) needs a near plane at least as far.
TEST_CASE(
    "advise under vulkan_min holds the envelope's bound, at a near plane the default's "
    "cannot show",
    "[advise][bound][envelope]") {
  const Scene vulkan = load_scene("", {"far=5e4", "pipeline.profile=vulkan_min"});
  const Scene plain = load_scene("", {"far=5e4"});
  REQUIRE(vulkan.bound_model == "vulkan_min");
  const EvalPair pair{Technique::standard, "unorm24", DepthRange::gl};
  AdviseRequest r;
  r.z_min = r.z_max = 500;
  r.separation = 0.05;
  const nlohmann::json j = bound_answer(vulkan, pair, r);
  REQUIRE(j.contains("near_bound"));
  const double n = j["near_bound"].get<double>();
  CHECK(mts_bound(with_near(vulkan, n), pair, 500).s <= r.separation);
  CHECK(mts_bound(with_near(vulkan, n / 1.1), pair, 500).s > r.separation);
  const double n_plain = bound_answer(plain, pair, r)["near_bound"].get<double>();
  CHECK(n > 10 * n_plain);
  // the default model's near plane does not hold under Vulkan's envelope
  CHECK(mts_bound(with_near(vulkan, n_plain), pair, 500).s > r.separation);
  const auto cli = run_cli(
      "advise --profile vulkan_min --range 500,500 --separation 0.05 -t standard -f unorm24 "
      "--far 5e4 --set frames=8 --set sampling=paper --format-out json --no-timing");
  REQUIRE(cli.exit_code == 0);
  const auto rec = nlohmann::json::parse(cli.output)["records"].at(0);
  CHECK(rec["near_bound"].get<double>() == n);
  // the adversary's worst case, sampled, sits below the bound's near plane but not far below
  CHECK(rec["smallest_near"].get<double>() <= n);
  CHECK(rec["smallest_near"].get<double>() > n / 2);
}

TEST_CASE("advise's largest near plane keeps a wide view's tilted planes clear of it", "[advise]") {
  // At a 60 degree view the planes at the nearest content reach 1/1.023 of its distance: a near
  // plane at z_min / 1.01 clips them, and every set-up then failed "next to the content".
  const Scene scene =
      load_scene("", {"kernel=[24,24]", "frames=20", "sampling=paper", "fov_y_deg=60", "far=5e4"});
  AdviseRequest r;
  r.z_min = r.z_max = 500;
  r.separation = 0.01;
  const double top = near_top(scene, r);
  CHECK(top < 500 / 1.0226);
  CHECK(top > 500 / 1.024);
  for (const double near : {top, 500 / 1.01}) {
    const auto m = run_cli(
        fmt::format("mts -t reversed -f unorm24 --fov 60 --far 5e4 --near {:.17g} --distances 500 "
                    "--kernel 24x24 --frames 20 --set sampling=paper --no-timing --format-out json",
                    near));
    REQUIRE(m.exit_code == 0);
    const auto row = nlohmann::json::parse(m.output)["rows"][0];
    INFO("near " << near << ": " << row.dump());
    CHECK((row["verdict"] == "resolved") == (near == top));
  }
}
