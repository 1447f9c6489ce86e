// The probe loop's shared pieces (host/mts/probe.h), on made-up row words without a device: how a
// launch's rows fold into each probe's outcome, and which probes the next launch still renders.
#include "host/mts/probe.h"

#include <catch2/catch.hpp>
#include <cstdint>
#include <vector>

#include "interface/mts_layout.h"

using namespace depthprec;

TEST_CASE("a launch's row words fold into each probe's first deciding frame", "[mts][unit]") {
  // two active probes (results 0 and 2 of three), two frames, two kernel rows each
  const size_t kh = 2;
  const uint32_t pairs = 10u << MTS_R_COUNT_SHIFT;
  const std::vector<uint32_t> rows = {
      pairs,
      pairs,  // probe 0, frame 0: clean
      pairs | MTS_R_FIGHT,
      pairs,  // probe 0, frame 1: a fight
      pairs | MTS_R_CLIPPED,
      pairs,  // probe 2, frame 0: clipped
      pairs,
      pairs | MTS_R_NONFINITE,  // probe 2, frame 1: non-finite
  };
  std::vector<ProbeResult> results(3);
  std::vector<bool> decided(3, false);
  uint64_t after = 0;
  const auto per_probe = fold_launch(rows, {0, 2}, 0, 2, kh, results, decided, after);
  CHECK(per_probe == std::vector<uint64_t>{40, 40});
  CHECK(results[0].outcome == Outcome::fight);
  CHECK(results[0].frames == 2);
  CHECK(results[2].outcome == Outcome::non_finite);
  CHECK(results[2].any_clipped);
  CHECK(decided == std::vector<bool>{true, false, true});
  CHECK(after == 0);  // both were decided in their last frame
  CHECK(undecided(decided) == std::vector<size_t>{1});
}
