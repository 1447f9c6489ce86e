// The evaluator sets plane A up once per distance and keeps it in a cache of a fixed number of
// slots: a run with more distances than slots goes through them in groups, and a later run
// evicts the least recently used distances. None of that may change a probe's result.
#include <catch2/catch.hpp>
#include <cmath>
#include <set>
#include <string>

#include "tests/support/mts_fixture.h"

using namespace depthprec;
using namespace depthprec::test;

namespace {

void check_same(const ProbeResult& a, const ProbeResult& b) {
  CHECK(to_string(a.outcome) == std::string(to_string(b.outcome)));
  CHECK(a.frames == b.frames);
  CHECK(a.fragment_pairs == b.fragment_pairs);
  CHECK(a.any_clipped == b.any_clipped);
  CHECK(a.any_non_finite == b.any_non_finite);
  CHECK(a.any_uncovered == b.any_uncovered);
}

}  // namespace

TEST_CASE("more distances than plane-A cache slots, and evictions, change no probe result",
          "[mts][cache]") {
  const Scene scene = load_scene("", {"kernel=[24,24]", "viewport=[24,24]", "frames=6"});
  // standard reads plane A's codes from the pixels it computes; log_fragment from the cache
  for (const Technique t : {Technique::standard, Technique::log_fragment}) {
    const EvalPair pair{t, "unorm24", DepthRange::gl};
    MtsEvaluator ev(runtime(), scene, pair);
    // distinct distances, each probed far above and close to its vertex bound
    std::vector<Probe> probes;
    const int distances = static_cast<int>(ev.max_plane_a_slots()) + 7;
    for (int i = 0; i < distances; ++i) {
      const double z = 1.5 * std::pow(1.13, i);
      probes.push_back({z, i % 2 ? z / 64 : 64 * vertex_bound(z)});
    }
    const auto grouped = ev.run(probes);
    // a second run over the first distances again, after the last ones evicted them
    const std::vector<Probe> again(probes.begin(), probes.begin() + 9);
    const auto refilled = ev.run(again);
    std::set<std::string> outcomes;
    for (size_t k = 0; k < probes.size(); ++k) {
      INFO(pair.label() << " z = " << probes[k].z << " s = " << probes[k].s);
      MtsEvaluator fresh(runtime(), scene, pair);
      const ProbeResult alone = fresh.run({probes[k]}).front();
      check_same(grouped[k], alone);
      if (k < again.size()) check_same(refilled[k], alone);
      outcomes.insert(to_string(alone.outcome));
    }
    INFO(pair.label());
    CHECK(outcomes.count("clean") == 1);
    CHECK(outcomes.count("fight") == 1);
  }
}

TEST_CASE("an evaluator on a finished one's plane-A buffers gives a fresh one's probe results",
          "[mts][cache]") {
  // The worst case's chunks hand their plane-A buffers on (SceneRun's evaluator source): the next
  // evaluator fills them over what the last one left there, with fewer distances (smaller cache)
  // or more frames (buffers too small: new ones).
  const Scene many = load_scene("", {"kernel=[24,24]", "viewport=[24,24]", "frames=6"});
  const Scene more_frames = load_scene("", {"kernel=[24,24]", "viewport=[24,24]", "frames=9"});
  for (const Technique t : {Technique::standard, Technique::log_fragment}) {
    const EvalPair pair{t, "unorm24", DepthRange::gl};
    std::vector<Probe> wide, narrow;
    for (int i = 0; i < 8; ++i) {
      const double z = 2.0 * std::pow(1.7, i);
      wide.push_back({z, i % 2 ? z / 64 : 64 * vertex_bound(z)});
      if (i % 3 == 0) narrow.push_back({1.1 * z, wide.back().s});
    }
    MtsEvaluator first(runtime(), many, pair);
    first.run(wide);
    MtsEvaluator::PlaneABuffers left = first.release_plane_a_buffers();
    REQUIRE(left.bytes() > 0);
    for (const Scene* s : {&many, &more_frames}) {
      INFO(pair.label() << ", frames " << s->frames);
      MtsEvaluator fresh(runtime(), *s, pair), inheriting(runtime(), *s, pair);
      inheriting.adopt_plane_a_buffers(std::move(left));
      const auto expected = fresh.run(narrow), got = inheriting.run(narrow);
      for (size_t k = 0; k < narrow.size(); ++k) check_same(got[k], expected[k]);
      left = inheriting.release_plane_a_buffers();  // handed on again
      CHECK(left.bytes() > 0);
    }
  }
}
