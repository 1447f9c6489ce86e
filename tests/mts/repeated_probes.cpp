// A probe whose plane B is an earlier probe's (the same z and the same distance B is built from)
// takes that probe's result instead of being rendered again (MtsEvaluator::run): it must be the
// result rendering it gives, and only a probe that went through every frame may be taken.
#include <catch2/catch.hpp>
#include <string>

#include "host/model/frame_setup.h"
#include "tests/support/mts_fixture.h"

using namespace depthprec;
using namespace depthprec::test;

TEST_CASE("separations that build the same plane B give the same matrices in every frame",
          "[mts][repeat]") {
  // fl32(1.005 + s) is one ulp above fl32(1.005) for both: the same plane B under binary32
  // matrices; under binary64 ones the two distances differ, and so do the matrices.
  const double z = 1.005, s1 = 1.2e-7, s2 = 0.6e-7;
  for (const std::string precision : {"float", "double"}) {
    INFO("matrix_precision " << precision);
    const Scene scene = load_scene("", {"pipeline.matrix_precision=" + precision});
    const EvalPair pair{Technique::standard, "float32", DepthRange::gl};
    const ProbeConstants pc = probe_constants(scene, pair, z);
    const bool same = plane_matrix_distance(scene, z + s1) == plane_matrix_distance(scene, z + s2);
    CHECK(same == (precision == "float"));
    bool all_frames_equal = true, any_frame_equal = false;
    for (int f = 0; f < scene.frames; ++f) {
      const bool eq = plane_matrix(scene, pc, z + s1, f) == plane_matrix(scene, pc, z + s2, f);
      all_frames_equal = all_frames_equal && eq;
      any_frame_equal = any_frame_equal || eq;
    }
    CHECK(all_frames_equal == same);
    CHECK(any_frame_equal == same);
  }
}

TEST_CASE("a probe repeating an earlier probe's plane B takes the result rendering it gives",
          "[mts][repeat]") {
  const Scene scene = load_scene("", {"kernel=[64,64]", "viewport=[64,64]", "frames=12"});
  const EvalPair pair{Technique::standard, "float32", DepthRange::gl};
  const double z = 1.005;
  const Probe first{z, 1.2e-7}, repeat{z, 0.6e-7}, other{z, 1e-3}, below{z, 1e-9};
  REQUIRE(plane_matrix_distance(scene, z + first.s) == plane_matrix_distance(scene, z + repeat.s));
  // first and repeat are one ulp of fl32(z) apart from plane A: clean; below is plane A itself
  MtsEvaluator ev(runtime(), scene, pair);
  const auto r1 = ev.run({first});
  REQUIRE(r1[0].outcome == Outcome::clean);
  const auto r2 = ev.run({repeat});
  CHECK(ev.probes_repeated() == 1);
  // the same probe rendered by an evaluator holding plane A already (as ev does)
  MtsEvaluator fresh(runtime(), scene, pair);
  fresh.run({other});
  const auto launches_before = fresh.launches();
  const auto f2 = fresh.run({repeat});
  CHECK(fresh.probes_repeated() == 0);
  CHECK(fresh.launches() > launches_before);
  CHECK(to_string(r2[0].outcome) == std::string(to_string(f2[0].outcome)));
  CHECK(r2[0].frames == f2[0].frames);
  CHECK(r2[0].frames == scene.frames);
  CHECK(r2[0].fragment_pairs == f2[0].fragment_pairs);
  CHECK(r2[0].any_clipped == f2[0].any_clipped);
  CHECK(r2[0].any_non_finite == f2[0].any_non_finite);
  CHECK(r2[0].any_uncovered == f2[0].any_uncovered);
  CHECK(r2[0].launches == f2[0].launches);
  CHECK(r2[0].launches < r1[0].launches);  // r1's include filling plane A's cache
  // another plane B at the same distance is rendered
  ev.run({other});
  CHECK(ev.probes_repeated() == 1);
  // a fight is decided by whichever frame the frame order visits first: rendered every time
  const auto b1 = ev.run({below});
  const auto b2 = ev.run({below});
  REQUIRE(b1[0].outcome == Outcome::fight);
  CHECK(b2[0].outcome == Outcome::fight);
  CHECK(ev.probes_repeated() == 1);
}
