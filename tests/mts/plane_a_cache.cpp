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
  // evaluator fills them over what the last one left there (other distances, as many of them),
  // or, with more frames, finds them too small and makes its own.
  const Scene six = load_scene("", {"kernel=[24,24]", "viewport=[24,24]", "frames=6"});
  const Scene nine = load_scene("", {"kernel=[24,24]", "viewport=[24,24]", "frames=9"});
  for (const Technique t : {Technique::standard, Technique::log_fragment}) {
    const EvalPair pair{t, "unorm24", DepthRange::gl};
    std::vector<Probe> before, after;
    for (int i = 0; i < 3; ++i) {
      const double z = 2.0 * std::pow(5.0, i);
      before.push_back({z, 64 * vertex_bound(z)});
      after.push_back({1.1 * z, i % 2 ? z / 64 : 64 * vertex_bound(z)});
    }
    MtsEvaluator first(runtime(), six, pair);
    first.run(before);
    MtsEvaluator::PlaneABuffers left = first.release_plane_a_buffers();
    REQUIRE(left.bytes() > 0);
    for (const Scene* s : {&six, &nine}) {
      INFO(pair.label() << ", frames " << s->frames);
      const cl_mem rows = left.rows();
      MtsEvaluator fresh(runtime(), *s, pair), inheriting(runtime(), *s, pair);
      inheriting.adopt_plane_a_buffers(std::move(left));
      const auto expected = fresh.run(after), got = inheriting.run(after);
      for (size_t k = 0; k < after.size(); ++k) check_same(got[k], expected[k]);
      left = inheriting.release_plane_a_buffers();  // handed on again
      CHECK((left.rows() == rows) == (s == &six));  // taken over, or too small for 9 frames
    }
  }
}
