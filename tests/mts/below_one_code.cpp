// A kernel smaller than the viewport sees a small part of the planes: at z = 5000 with near 0.1
// one unorm24 code spans 14.9 m of eye distance, while the planes' depths inside a 50x50 kernel of
// a 200x200 viewport vary by about 2 m. The search then finds a separation at which plane A
// stores one code and plane B the next in every frame: an MTS far below one code, which a z
// nearby would not give. The number is what the emulated pipeline does (the reference pipeline,
// every pixel of every frame, agrees), so it is reported, but flagged below_one_code with the
// code's width.
#include <catch2/catch.hpp>

#include "host/model/resolve.h"
#include "tests/mts/reference_outcome.h"
#include "tests/support/mts_fixture.h"

using namespace depthprec;
using namespace depthprec::test;
using Catch::Matchers::WithinRel;

namespace {

const EvalPair kPair{Technique::standard, "unorm24", DepthRange::gl};

double code_width_at(const Scene& s, double z) {
  return code_interval_width({Technique::standard, s.near, s.far, s.params},
                             s.storage_format(kPair), z);
}

}  // namespace

TEST_CASE("an MTS below one storage code is flagged, and the reference confirms its bracket",
          "[mts][reference]") {
  const Scene scene =
      load_scene("", {"near=0.1", "far=10000", "kernel=[50,50]", "viewport=[200,200]"});
  const double z = 5000;
  REQUIRE_THAT(code_width_at(scene, z), WithinRel(14.9, 0.01));  // resolve's figure at z
  const MtsRow row = mts_rows(scene, kPair.technique, kPair.format, kPair.depth_range, {z}).front();
  REQUIRE(row.verdict() == Verdict::resolved);
  CHECK(row.mts_seen < 0.1 * code_width_at(scene, z));
  CHECK(row.below_one_code);
  CHECK_THAT(row.code_width, WithinRel(code_width_at(scene, z), 1e-12));
  CHECK_THAT(row.flags(), Catch::Matchers::Contains("below_one_code"));
  // The plain reference pipeline (no shortcuts): no pixel fights at hi, some pixel at lo.
  const ReferenceOutcome at_hi = reference_outcome(scene, kPair, {z, row.hi});
  const ReferenceOutcome at_lo = reference_outcome(scene, kPair, {z, row.lo});
  CHECK(at_hi.outcome == Outcome::clean);
  CHECK_FALSE(at_hi.any_uncovered);
  CHECK(at_lo.outcome == Outcome::fight);
}

TEST_CASE("with the kernel filling the viewport the same set-up needs more than one code",
          "[mts]") {
  const Scene scene =
      load_scene("", {"near=0.1", "far=10000", "kernel=[50,50]", "viewport=[50,50]"});
  const double z = 5000;
  const MtsRow row = mts_rows(scene, kPair.technique, kPair.format, kPair.depth_range, {z}).front();
  REQUIRE(row.verdict() == Verdict::resolved);
  CHECK(row.mts_seen > code_width_at(scene, z));
  CHECK_FALSE(row.below_one_code);
}
