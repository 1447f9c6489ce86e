// The chords' margin (kernels/exact/chords.cl, CHORDS) holds: at every pixel of every kernel row
// the chords decide, either plane's depth as the pixel loop computes it lies within the margin of
// its chord, less the 8u the margin keeps for the comparisons. Brute force over the default
// scene's kernel, a round of orientations (the cube's corners first, where the planes are
// steepest) and distances from the near plane to 2e6, for every exact map: those affine in screen
// space (standard, infinite, reversed, n/w: the margin only the roundings') and the curved ones
// (the logs, linear, w/f: the chord's curvature term).
#include <catch2/catch.hpp>
#include <string>
#include <vector>

#include "host/model/frame_setup.h"
#include "host/mts/mts_exact.h"
#include "host/mts/sampler.h"
#include "tests/support/mts_fixture.h"

using namespace depthprec;

TEST_CASE("plane B's computed depth lies within the chords' margin", "[attribution][bounds]") {
  Scene scene = load_scene("", {});
  const std::vector<Angles> chunk = round_orientations(scene, 1);
  scene.frames = 40;
  Orientations sampled;
  std::vector<Probe> probes;
  for (double z : {1.005, 3.0, 30.0, 1000.0, 3e4, 2e6}) {
    sampled.at[z] = std::vector<Angles>(chunk.begin(), chunk.begin() + scene.frames);
    for (double f : {1e-3, 1e-6}) probes.push_back({z, z * f});
  }
  // every exact map: standard, infinite, reversed, n/w, log (from the vertex stage and from the
  // fragment stage, which clamps), linear, w/f, three.js's and Cesium's logs
  for (const EvalPair& pair :
       {EvalPair{Technique::standard, "unorm24", DepthRange::gl},
        EvalPair{Technique::infinite, "float32", DepthRange::gl},
        EvalPair{Technique::reversed, "unorm24", DepthRange::zero_to_one},
        EvalPair{Technique::reversed_infinite, "float32", DepthRange::zero_to_one},
        EvalPair{Technique::log_vertex, "unorm24", DepthRange::gl},
        EvalPair{Technique::log_fragment, "unorm24", DepthRange::gl},
        EvalPair{Technique::linear, "float32", DepthRange::gl},
        EvalPair{Technique::w_buffer, "unorm24", DepthRange::gl},
        EvalPair{Technique::log_threejs, "float32", DepthRange::gl},
        EvalPair{Technique::log_cesium, "unorm24", DepthRange::gl}}) {
    INFO(pair.label());
    ExactEvaluator ev(runtime(), scene, pair, sampled);
    const std::vector<double> worst = ev.chord_audit(probes);
    double largest = -1.0;
    for (size_t k = 0; k < probes.size(); ++k) {
      INFO(" z = " << probes[k].z << " s = " << probes[k].s);
      CHECK(worst[k] <= 1.0);
      largest = std::max(largest, worst[k]);
    }
    // the chords applied, and the margin is not vacuous: some pixel uses a measurable share
    CHECK(largest > 1e-3);
    WARN(pair.label() << ": largest (|D_c - chord| + 8u) / margin " << largest);
  }
}
