// Stiffness probes, MTS attribution and the properties every row keeps on random valid scenes
// (issue 7, docs/stability.md).
#include <catch2/catch.hpp>
#include <cmath>
#include <random>

#include "host/model/frame_setup.h"
#include "host/model/scene.h"
#include "host/mts/mts_exact.h"
#include "host/mts/mts_run.h"
#include "tests/support/mts_fixture.h"

using namespace depthprec;
using namespace depthprec::test;

namespace {

Scene kernel_filling_scene(int kernel, int frames) {
  Scene s = load_scene("");
  s.kernel_w = s.kernel_h = s.viewport_w = s.viewport_h = kernel;
  s.frames = frames;
  return s;
}

Outcome probe(OpenClRuntime& rt, const Scene& s, const EvalPair& pair, double z, double sep) {
  MtsEvaluator ev(rt, s, pair);
  return ev.run({{z, sep}}).front().outcome;
}

}  // namespace

TEST_CASE("a non-monotone row's bracket holds real outcomes on both sides", "[stability]") {
  // standard/unorm24 in [0,1] flips around its MTS from z = 2^13 on (docs/stability.md)
  const Scene s = kernel_filling_scene(60, 20);
  const EvalPair pair{Technique::standard, "unorm24", DepthRange::zero_to_one};
  const auto rows =
      mts_rows(s, pair.technique, pair.format, pair.depth_range, powers_of_two(13, 18));
  int flagged = 0;
  for (const auto& r : rows) {
    INFO("z = " << r.z);
    REQUIRE(r.verdict() == Verdict::resolved);
    CHECK(probe(runtime(), s, pair, r.z, r.mts) == Outcome::clean);
    CHECK(probe(runtime(), s, pair, r.z, r.lo) == Outcome::fight);
    if (!r.non_monotone) {
      CHECK(r.fight_max == r.lo);  // monotone: the boundary the probes found is the bracket
      CHECK(r.clean_min == r.mts);
      CHECK(std::isnan(r.monotone_fight));
      continue;
    }
    ++flagged;
    CHECK(r.fight_max > r.clean_min);
    // One search: the witness the row's flags print is its own bracket's contradiction.
    CHECK(r.monotone_clean == r.clean_min);
    CHECK(r.monotone_fight == r.fight_max);
    CHECK(probe(runtime(), s, pair, r.z, r.fight_max) == Outcome::fight);  // the upper MTS fights
    CHECK(probe(runtime(), s, pair, r.z, r.clean_min) ==
          Outcome::clean);  // and the lowest clean is clean
  }
  CHECK(flagged >= 1);
}

TEST_CASE("attribution: storage limits reversed unorm24, arithmetic limits reversed float32 in gl",
          "[stability][attribution]") {
  Scene s = kernel_filling_scene(60, 20);
  s.distances = {1024.0, 65536.0, 1048576.0};
  s.evaluate = {{Technique::reversed, "unorm24", DepthRange::zero_to_one},
                {Technique::reversed, "unorm24", DepthRange::gl},
                {Technique::reversed, "float32", DepthRange::zero_to_one},
                {Technique::reversed, "float32", DepthRange::gl}};
  RunControl c;
  c.attribute = true;
  const auto rows = run_scene(runtime(), s, {}, c).rows;
  REQUIRE(rows.size() == 12);
  for (size_t i = 0; i < 3; ++i) {
    const MtsRow &u24 = rows[i], &u24_gl = rows[3 + i], &f32 = rows[6 + i], &f32_gl = rows[9 + i];
    INFO("z = " << u24.z);
    // reversed unorm24 in [0,1]: d ~ n/w, one code spans w^2 / (n (2^24 - 1)) of distance; plane
    // A may sit anywhere within its code, so the storage MTS is half to one code (plus tilt)
    const double step = u24.z * u24.z / (s.near * 16777215.0);
    CHECK(u24.storage_mts >= 0.5 * step);
    CHECK(u24.storage_mts <= 1.1 * step);
    CHECK(u24.dominant == "storage");
    // the exact mapping is the same in both depth ranges: whatever gl loses is arithmetic
    CHECK(u24_gl.storage_mts == u24.storage_mts);
    CHECK(f32_gl.storage_mts == f32.storage_mts);
    // float32 storage holds every binary32 depth: its arithmetic factor is its MTS
    CHECK(f32.arithmetic_mts == f32.mts);
    CHECK(f32_gl.arithmetic_mts == f32_gl.mts);
    // gl's 0.5 z + 0.5 in binary32 throws away what reversed float32 gains in [0,1]
    CHECK(f32_gl.arithmetic_mts > 10 * f32.arithmetic_mts);
    CHECK(f32_gl.dominant == "arithmetic");
  }
}

TEST_CASE("random valid scenes: rows keep their invariants", "[stability][property]") {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const auto& techniques = technique_table();
  const char* formats[] = {"float32", "unorm24", "float16"};
  for (int k = 0; k < 12; ++k) {
    Scene s = kernel_filling_scene(24, 5);
    s.near = std::pow(10.0, -3 + 6 * u(rng));
    s.far = k % 4 == 3 ? INFINITY : s.near * std::pow(10.0, 1 + 11 * u(rng));
    s.distances.clear();
    for (int i = 0; i < 3; ++i)
      s.distances.push_back(s.near *
                            std::pow(std::isinf(s.far) ? 1e12 : 1.5 * s.far / s.near, u(rng)));
    const EvalPair pair{techniques[rng() % techniques.size()].id, formats[rng() % 3],
                        rng() % 2 ? DepthRange::gl : DepthRange::zero_to_one};
    s.evaluate = {pair};
    RunControl c;
    c.attribute = k % 3 == 0;
    const auto rows = run_scene(runtime(), s, {}, c).rows;
    for (const auto& r : rows) {
      INFO(pair.label() << " near " << s.near << " far " << s.far << " z " << r.z);
      CHECK_FALSE(std::isnan(r.mts));
      if (r.verdict() == Verdict::resolved) {
        CHECK(r.mts >= r.vertex_bound);
        CHECK_FALSE(r.clipped);
        CHECK(r.lo < r.mts);
        CHECK(r.clean_min <= r.mts);
        CHECK(r.fight_max >= r.lo);
        // a fight above a clean probe is non-monotone; the flag may also come from an orientation
        // of the worst case whose own bracket saw it (worst_case.cpp), so no converse
        if (r.fight_max > r.clean_min) CHECK(r.non_monotone);
      } else {
        CHECK(std::isinf(r.mts));
      }
      if (c.attribute) {
        CHECK_FALSE(std::isnan(r.storage_mts));
        CHECK_FALSE(std::isnan(r.arithmetic_mts));
        CHECK_FALSE(r.dominant.empty());
      }
    }
  }
}
