// Depth bias under worst-case sampling (host/bias/bias_worst_case.h): the refined answers are
// never below the paper's frames', they pass in every orientation the rounds sampled (checked on
// one evaluator over all of them at once), and the whole unit below fails in one of them.
#include "host/bias/bias_worst_case.h"

#include <fmt/format.h>

#include <catch2/catch.hpp>
#include <cmath>
#include <map>
#include <memory>

#include "host/bias/bias_evaluator.h"
#include "host/model/frame_setup.h"
#include "tests/support/mts_fixture.h"

using namespace depthprec;

TEST_CASE("bias answers under worst-case sampling hold in every orientation sampled",
          "[bias][worst_case]") {
  const Scene scene =
      load_scene("", {"kernel=[32,32]", "viewport=[32,32]", "frames=6", "distances=[2,300,40000]",
                      "worst_case.round_size=10", "worst_case.max_rounds=3",
                      R"(evaluate=[{"technique": "standard", "format": "unorm24"}])"});
  const EvalPair pair = scene.evaluate[0];
  BiasOptions o;
  o.api = BiasApi::d3d;
  o.set_factor = 1;
  // Every orientation a distance's answers rest on: the frames', then each chunk's.
  std::map<double, std::vector<Angles>> used;
  for (double z : scene.distances)
    for (int f = 0; f < scene.frames; ++f) used[z].push_back(frame_angles(scene, f));
  // The emulated evaluators, noting the chunks' orientations.
  struct Source : EvaluatorSource<BiasEvaluator> {
    Source(const Scene& scene, const EvalPair& pair, const BiasOptions& o,
           std::map<double, std::vector<Angles>>& used)
        : scene_(scene), pair_(pair), o_(o), used_(used) {}
    std::unique_ptr<BiasEvaluator> make(const Scene& s, const Orientations& sampled) override {
      if (s.frames == scene_.worst_case.round_size)
        for (const auto& [z, list] : sampled.at)
          used_[z].insert(used_[z].end(), list.begin(), list.end());
      return std::make_unique<BiasEmulator>(test::runtime(), s, pair_, o_, sampled);
    }
    const Scene& scene_;
    const EvalPair& pair_;
    const BiasOptions& o_;
    std::map<double, std::vector<Angles>>& used_;
  } source(scene, pair, o, used);
  std::vector<BiasAnswers> paper, worst;
  {
    const std::unique_ptr<BiasEvaluator> ev = source.make(scene, {});
    paper = search_bias(*ev, scene, pair, o, scene.distances);
  }
  worst = paper;
  refine_bias_worst_case(source, scene, pair, o, scene.distances, worst);
  int rose = 0;
  for (size_t k = 0; k < scene.distances.size(); ++k) {
    const double z = scene.distances[k];
    INFO("z = " << z);
    REQUIRE(worst[k].units.resolved());
    CHECK(worst[k].units.value >= paper[k].units.value);
    rose += worst[k].units.value > paper[k].units.value;
    CHECK(worst[k].orientations == used[z].size());
    // One evaluator over every orientation used at z: the answer passes, one unit less fails.
    Scene all = scene;
    all.frames = static_cast<int>(used[z].size());
    BiasEmulator ev(test::runtime(), all, pair, o, Orientations{{{z, used[z]}}});
    const double u = worst[k].units.value;
    const auto r = ev.run({bias_probe(all, pair, o, kBiasUnits, z, u),
                           bias_probe(all, pair, o, kBiasUnits, z, u - 1)});
    CHECK(bias_passes(r[0]));
    if (u >= 1) CHECK_FALSE(bias_passes(r[1]));
    if (worst[k].with_factor.resolved()) {
      const auto w =
          ev.run({bias_probe(all, pair, o, kBiasWithFactor, z, worst[k].with_factor.value)});
      CHECK(bias_passes(w[0]));
    }
  }
  CHECK(rose >= 1);  // the scene leaves the paper's frames something to find
}
