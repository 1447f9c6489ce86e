// The paper's checks (Gilg et al. 2021, docs/spec.md 7) on the default scene, as issue "MTS
// evaluator" states them. Each asserts a measured value that a wrong pipeline would get wrong.
#include <catch2/catch.hpp>
#include <cmath>

#include "host/model/frame_setup.h"
#include "interface/mts_layout.h"
#include "tests/support/mts_fixture.h"

using namespace depthprec;
using namespace depthprec::test;

TEST_CASE("linear in unorm24 comes within 2x of (f-n)/2^24 for z from 2^12 to 2^26",
          "[mts][paper]") {
  const Scene scene = load_scene("");
  const double bound = (scene.far - scene.near) / std::ldexp(1.0, 24);
  for (const auto& r :
       mts_rows(scene, Technique::linear, "unorm24", DepthRange::gl, powers_of_two(12, 26))) {
    INFO("z = " << r.z << " mts = " << r.mts << " (f-n)/2^24 = " << bound);
    CHECK(r.flags().empty());
    CHECK(r.mts >= bound / 2);
    CHECK(r.mts <= bound * 2);
  }
}

TEST_CASE("standard (gl): MTS < 1e-6 at z = 2, unresolvable from z = 2^24", "[mts][paper]") {
  const Scene scene = load_scene("");
  std::vector<double> z = {2.0};
  for (double d : powers_of_two(24, 29)) z.push_back(d);
  for (const char* format : {"float32", "unorm24"}) {
    const auto rows = mts_rows(scene, Technique::standard, format, DepthRange::gl, z);
    INFO(format << " mts at z = 2: " << rows[0].mts);
    CHECK(rows[0].mts < 1e-6);
    CHECK_FALSE(rows[0].unresolvable);
    for (size_t i = 1; i < rows.size(); ++i) {
      INFO(format << " z = " << rows[i].z << " mts = " << rows[i].mts);
      CHECK(rows[i].unresolvable);
      CHECK(std::isinf(rows[i].mts));
    }
  }
}

TEST_CASE(
    "reversed float32 zero_to_one stays within 8x the vertex bound and gl is 100x worse at 2^20",
    "[mts][paper]") {
  const Scene scene = load_scene("");
  const auto rows = mts_rows(scene, Technique::reversed, "float32", DepthRange::zero_to_one,
                             powers_of_two(1, 22));
  for (const auto& r : rows) {
    INFO("z = " << r.z << " mts = " << r.mts << " vertex bound = " << r.vertex_bound);
    CHECK(r.mts <= 8 * r.vertex_bound);
    CHECK(r.mts >= r.vertex_bound);
  }
  const auto gl =
      mts_rows(scene, Technique::reversed, "float32", DepthRange::gl, {std::ldexp(1.0, 20)});
  const double zero_to_one_at_2_20 = rows[19].mts;
  REQUIRE(rows[19].z == std::ldexp(1.0, 20));
  INFO("gl " << gl[0].mts << " vs zero_to_one " << zero_to_one_at_2_20);
  CHECK(gl[0].mts >= 100 * zero_to_one_at_2_20);
}

TEST_CASE("no fragment of either plane is clipped at z = 1.005 in any frame", "[mts][paper]") {
  const Scene scene = load_scene("");
  for (const Technique t : {Technique::standard, Technique::reversed, Technique::linear}) {
    const EvalPair pair{t, "float32", DepthRange::gl};
    MtsEvaluator ev(runtime(), scene, pair, true, MtsEvaluator::Kernels::with_tests);
    const Probe p{1.005, vertex_bound(1.005) * 4};
    for (int frame = 0; frame < scene.frames; ++frame) {
      const FrameCodes fc = ev.codes(p, frame);
      int clipped = 0;
      for (size_t i = 0; i < fc.status_a.size(); ++i)
        clipped += (fc.status_a[i] == MTS_S_CLIPPED) + (fc.status_b[i] == MTS_S_CLIPPED);
      INFO(info(t).name << " frame " << frame);
      REQUIRE(clipped == 0);
    }
  }
}

TEST_CASE("MTS grows with z for standard, reversed and log_fragment", "[mts][paper]") {
  const Scene scene = load_scene("");
  const std::vector<double> z = {2, 64, 2048, 65536, 2097152};
  for (const Technique t : {Technique::standard, Technique::reversed, Technique::log_fragment}) {
    const auto rows = mts_rows(scene, t, "float32", DepthRange::gl, z);
    for (size_t i = 1; i < rows.size(); ++i) {
      INFO(info(t).name << " z " << rows[i - 1].z << " -> " << rows[i].z << ": " << rows[i - 1].mts
                        << " -> " << rows[i].mts);
      CHECK(rows[i].mts > rows[i - 1].mts);
    }
  }
}
