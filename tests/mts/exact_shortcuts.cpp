// The storage-limited pipeline's shortcuts (kernels/mts_exact.cl) change no probe result: rows and
// stretches of 8 pixels decided clean from their end pixels (ROW_ENDS), plane A read from the
// cache the evaluator fills for a distance's second run on (A_CACHED), and with the cache pixels
// decided clean from plane B's chords (CHORDS). Probes run from s = z down past the
// storage-limited MTS over a round's orientations (the cube's corners first, where the planes are
// steepest), with and without the shortcuts, at distances where the codes' spread along a row is
// wide and narrow, for a less- and a greater-compare, unorm and float formats (float16 through the
// one-code-at-a-time encoder), a vertex-stage and a fragment-stage mapping, maps affine in screen
// space (standard, reversed) and curved ones (log, linear), and parallel rays (orthographic, which
// the chords leave out).
#include <catch2/catch.hpp>
#include <string>
#include <vector>

#include "host/model/frame_setup.h"
#include "host/mts/mts_exact.h"
#include "host/mts/sampler.h"
#include "tests/support/mts_fixture.h"

using namespace depthprec;

TEST_CASE("the storage-limited pipeline's shortcuts change no probe result",
          "[attribution][bounds]") {
  // 48 pixels a row: whole stretches of 8; 41: a last stretch of 1, and cache rows padded to 48;
  // 33: a last chord segment of no length; 133: a second block of chord knots (a few rows across
  // a square viewport, which the planes cover)
  const auto [kernel, viewport] =
      GENERATE(table<std::string, std::string>({{"[48,48]", "[48,48]"},
                                                {"[41,39]", "[41,39]"},
                                                {"[33,9]", "[33,33]"},
                                                {"[133,6]", "[133,133]"}}));
  INFO("kernel " << kernel << " in viewport " << viewport);
  Scene scene = load_scene("", {"kernel=" + kernel, "viewport=" + viewport});
  const std::vector<Angles> chunk = round_orientations(scene, 1);
  scene.frames = 24;
  Orientations sampled;
  std::vector<Probe> probes;
  for (double z : {1.005, 30.0, 3000.0, 2e6}) {
    sampled.at[z] = std::vector<Angles>(chunk.begin(), chunk.begin() + scene.frames);
    for (double f = 1.0; f > 1e-9; f /= 2) probes.push_back({z, z * f});
  }
  for (const EvalPair& pair : {EvalPair{Technique::standard, "unorm24", DepthRange::gl},
                               EvalPair{Technique::reversed, "float32", DepthRange::zero_to_one},
                               EvalPair{Technique::log_fragment, "unorm16", DepthRange::gl},
                               EvalPair{Technique::linear, "float32", DepthRange::gl},
                               // a unorm under a greater-compare; a format encode8 takes one code
                               // at a time (the chords against A's cache leave it to the ends)
                               EvalPair{Technique::reversed, "unorm24", DepthRange::zero_to_one},
                               EvalPair{Technique::standard, "float16", DepthRange::gl},
                               EvalPair{Technique::orthographic, "unorm24", DepthRange::gl}}) {
    ExactEvaluator with(runtime(), scene, pair, sampled),
        without(runtime(), scene, pair, sampled, false);
    const auto b = without.run(probes);
    const auto first = with.run(probes);  // plane A computed in every probe
    REQUIRE(with.cache_fills() == 0);
    const auto cached = with.run(probes);  // plane A from the cache
    INFO(pair.label());
    CHECK(with.cache_fills() == 4);
    int fights = 0, clean = 0;
    for (const auto& a : {first, cached})
      for (size_t k = 0; k < probes.size(); ++k) {
        INFO(" z = " << probes[k].z << " s = " << probes[k].s);
        CHECK(to_string(a[k].outcome) == std::string(to_string(b[k].outcome)));
        CHECK(a[k].frames == b[k].frames);
        CHECK(a[k].deciding_frame == b[k].deciding_frame);
        CHECK(a[k].fragment_pairs == b[k].fragment_pairs);
        CHECK(a[k].any_uncovered == b[k].any_uncovered);
        CHECK(a[k].any_clipped == b[k].any_clipped);
        fights += a[k].outcome == Outcome::fight;
        clean += a[k].outcome == Outcome::clean;
      }
    CHECK(with.rows_decided_from_ends() > 0);  // the shortcuts were taken
    CHECK(without.rows_decided_from_ends() == 0);
    // the chords decide pixels near the MTS, where the ends leave them (not for parallel rays)
    if (pair.technique == Technique::orthographic)
      CHECK(with.rows_decided_from_chords() == 0);
    else
      CHECK(with.rows_decided_from_chords() > 0);
    CHECK(without.rows_decided_from_chords() == 0);
    CHECK(fights > 0);  // the descent reaches separations that fight
    CHECK(clean > 0);
  }
}
