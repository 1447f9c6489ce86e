// The guaranteed MTS over random scenes: near and far, field of view, rotation range, the world's
// position and the transform drawn at random, every technique and three formats; no probe of the
// search may fight above a row's mts_bound. It found two holes the fixed scenes did not:
// relative_to_eye's low parts and the orthographic clip stage's w.
#include <fmt/format.h>

#include <catch2/catch.hpp>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "host/model/technique.h"
#include "host/mts/mts_bound.h"
#include "host/mts/mts_search.h"
#include "tests/support/mts_fixture.h"

using namespace depthprec;
using namespace depthprec::test;

TEST_CASE("over random scenes no probe fights above the guaranteed MTS", "[mts][bound][property]") {
  std::mt19937 rng(20261205);
  const auto pick = [&rng](const auto& v) {
    return v[std::uniform_int_distribution<size_t>(0, v.size() - 1)(rng)];
  };
  const auto real = [&rng](double lo, double hi) {
    return std::uniform_real_distribution<double>(lo, hi)(rng);
  };
  int bounded = 0;
  for (int k = 0; k < 24; ++k) {
    const double near = pick(std::vector<double>{0.05, 0.1, 1, 3});
    const double far = pick(std::vector<double>{near * 1e3, 1e4, 1e9});
    std::string zs;
    for (int i = 0; i < 3; ++i)
      zs += fmt::format("{}{:.17g}", i ? "," : "", near * std::pow(2 * far / near, real(0, 1)));
    const double w = pick(std::vector<double>{0, 0, 3e3, 7e4, 2e6});
    const std::vector<std::string> sets = {
        "kernel=[24,24]",
        "viewport=[24,24]",
        "frames=6",
        "sampling=paper",
        fmt::format("near={}", near),
        fmt::format("far={}", far),
        fmt::format("fov_y_deg={}", pick(std::vector<int>{10, 60, 90})),
        fmt::format("rotation_range_deg={:.3g}", real(0.2, 8)),
        fmt::format("world_position=[{},{},{}]", w, -0.5 * w, 0.25 * w),
        "pipeline.transform=" +
            pick(std::vector<std::string>{"absolute", "camera_relative", "relative_to_eye"}),
        "distances=[" + zs + "]"};
    std::string all;
    for (const auto& o : sets) all += o + " ";
    INFO("scene " << k << ": " << all);
    const Scene s = load_scene("", sets);
    for (int p = 0; p < 2; ++p) {
      const Technique t = pick(technique_table()).id;
      const EvalPair pair{t, pick(std::vector<std::string>{"unorm16", "unorm24", "float32"}),
                          s.range_for(t)};
      INFO(pair.label());
      MtsEvaluator ev(runtime(), s, pair);
      for (const MtsRow& r : search_pair(ev, s, pair, s.distances)) {
        const MtsBound b = mts_bound(s, pair, r.z);
        if (!std::isfinite(b.s)) continue;
        INFO("z = " << r.z << ": mts_bound " << b.s << ", fight_max " << r.fight_max);
        CHECK(r.fight_max <= b.s);
        ++bounded;
      }
    }
  }
  CHECK(bounded >= 60);
}
