// Frame order (host/mts/mts_evaluator.h): a probe visits the frames from the one that decided the
// last fighting probe of its distance, so a fighting probe below the MTS is decided at its first
// frame, and whether it fights does not change.
#include <catch2/catch.hpp>
#include <string>

#include "tests/support/mts_fixture.h"

using namespace depthprec;
using namespace depthprec::test;

TEST_CASE("a probe starts at the frame that decided its distance's last fight", "[mts][frames]") {
  const Scene scene = load_scene("", {"kernel=[48,48]", "viewport=[48,48]", "frames=40"});
  const EvalPair pair{Technique::standard, "unorm24", DepthRange::gl};
  const std::vector<MtsRow> rows =
      mts_rows(scene, pair.technique, pair.format, pair.depth_range, {2.0, 300.0});
  for (const MtsRow& row : rows) {
    REQUIRE(row.verdict() == Verdict::resolved);
    // the largest separation that fought, and one a little below it
    const Probe first{row.z, row.lo}, second{row.z, row.lo * 0.999};
    MtsEvaluator fresh(runtime(), scene, pair), ordered(runtime(), scene, pair);
    const ProbeResult in_order = fresh.run({first})[0];
    INFO("z = " << row.z << " lo = " << row.lo << " fought at frame " << in_order.frames - 1);
    REQUIRE(in_order.outcome == Outcome::fight);
    CHECK(ordered.run({first})[0].frames ==
          in_order.frames);  // nothing fought before: frame 0 first
    const ProbeResult next = ordered.run({second})[0];
    const ProbeResult next_in_order = MtsEvaluator(runtime(), scene, pair).run({second})[0];
    CHECK(to_string(next.outcome) == std::string(to_string(next_in_order.outcome)));
    if (next.outcome == Outcome::fight) {
      CHECK(next.frames <= next_in_order.frames);
      // the frame that fought last is visited first; a fight there decides the probe at once
      const Probe again{row.z, row.lo};
      CHECK(ordered.run({again})[0].frames == 1);
    }
  }
}
