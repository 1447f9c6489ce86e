// The bisection itself (docs/spec.md 5.2), driven by synthetic outcomes: its probe sequence,
// bracket and verdicts, independent of any device.
#include "host/mts/mts_search.h"

#include <catch2/catch.hpp>
#include <cmath>

#include "host/model/frame_setup.h"

using namespace depthprec;

namespace {
// Runs a bisection against a threshold: fights below t, clean at or above it (clipped above c).
Bisection run(double z, double t, double c = INFINITY, double rel = std::ldexp(1.0, -10)) {
  Bisection b(z, rel, std::ldexp(1.0, 20), vertex_bound(z));
  while (!b.done()) {
    const double s = b.next();
    b.record(s >= c ? Outcome::clipped : s < t ? Outcome::fight : Outcome::clean);
  }
  return b;
}
}  // namespace

TEST_CASE("the probe sequence starts at z, doubles while fighting, then bisects at midpoints",
          "[search]") {
  const Bisection b = run(4.0, 37.0);
  const auto& h = b.history();
  REQUIRE(h.size() >= 5);
  CHECK(h[0].first == 4.0);
  CHECK(h[1].first == 8.0);
  CHECK(h[2].first == 16.0);
  CHECK(h[3].first == 32.0);
  CHECK(h[4].first == 64.0);  // first clean
  CHECK(h[5].first == 48.0);  // midpoint of [32, 64]
  CHECK(h[6].first == 40.0);
  CHECK(b.resolved());
  CHECK(b.lo() < 37.0);
  CHECK(b.hi() >= 37.0);
  CHECK((b.hi() - b.lo()) / b.hi() <= std::ldexp(1.0, -10));
}

TEST_CASE("a separation below z bisects down from 0..z", "[search]") {
  const Bisection b = run(2.0, 3e-7);
  CHECK(b.history()[0].first == 2.0);
  CHECK(b.history()[1].first == 1.0);  // s = 0 counts as fighting
  CHECK(b.hi() >= 3e-7);
  CHECK(b.lo() < 3e-7);
  CHECK((b.hi() - b.lo()) / b.hi() <= std::ldexp(1.0, -10));
}

TEST_CASE("fighting past 2^20 z is unresolvable", "[search]") {
  const Bisection b = run(1.0, 1e30);
  CHECK_FALSE(b.resolved());
  CHECK(b.history().back().first == std::ldexp(1.0, 20));
  CHECK(b.probes() == 21);
}

TEST_CASE("clipped separations are never accepted as MTS", "[search]") {
  // clean from 10 on, but clipped from 12: the answer lies in [10, 12)
  const Bisection ok = run(4.0, 10.0, 12.0);
  CHECK(ok.resolved());
  CHECK(ok.hi() >= 10.0);
  CHECK(ok.hi() < 12.0);
  CHECK(ok.saw_clipped());
  // clipped before anything is clean: no MTS
  const Bisection none = run(4.0, 20.0, 12.0);
  CHECK_FALSE(none.resolved());
  CHECK(none.saw_clipped());
}

TEST_CASE("a ceiling below the vertex bound ends the search in few probes", "[search]") {
  // everything that does not fight is clipped: the ceiling halves down to where plane B would
  // coincide with plane A, and stops there (not at binary64 underflow, ~1000 probes later)
  for (double z : {2.0, 1e6, std::ldexp(1.0, 60)}) {
    INFO("z = " << z);
    const Bisection b = run(z, INFINITY, 0.0);
    CHECK_FALSE(b.resolved());
    CHECK(b.saw_clipped());
    CHECK(b.probes() <= 30);
    CHECK(b.history().back().first < 2 * vertex_bound(z));
  }
}

TEST_CASE("the vertex bound is where fl32(z + s) leaves fl32(z)", "[search]") {
  for (double z : {1.005, 2.0, 3.0, 1000.1, 16777216.0, 536870912.0}) {
    const double vb = vertex_bound(z);
    INFO("z = " << z);
    CHECK(static_cast<float>(z + vb * 0.999) == static_cast<float>(z));
    CHECK(static_cast<float>(z + vb * 1.001) > static_cast<float>(z));
  }
  CHECK(vertex_bound(2.0) == std::ldexp(1.0, -23));
}
