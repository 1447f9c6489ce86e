// The guaranteed MTS against a dense scan of the rotation cube (docs/mts.md "The guaranteed
// bound"): at a dozen rows of the default scene, under each profile and its own bound model, N
// uniform orientations (and the cube's corners) probed at mts_bound; none may fight. Prints one
// line per row and profile, and the total.
//   build/bench/bound_scan [N]      (default 100000)
#include <fmt/format.h>

#include <cmath>
#include <cstdlib>
#include <random>

#include "host/model/frame_setup.h"
#include "host/model/profile.h"
#include "host/mts/mts_bound.h"
#include "host/mts/mts_evaluator.h"
#include "host/runtime/opencl_runtime.h"

using namespace depthprec;

int main(int argc, char** argv) {
  const size_t n = argc > 1 ? std::strtoull(argv[1], nullptr, 10) : 100000;
  const size_t chunk = 5000;  // orientations per evaluator: plane A's memory stays bounded
  const std::vector<std::pair<EvalPair, double>> rows = {
      {{Technique::standard, "float32", DepthRange::gl}, 1.005},
      {{Technique::standard, "unorm24", DepthRange::gl}, 512},
      {{Technique::standard, "float32", DepthRange::gl}, 65536},
      {{Technique::reversed, "float32", DepthRange::zero_to_one}, 2},
      {{Technique::reversed, "float32", DepthRange::zero_to_one}, 16384},
      {{Technique::reversed, "unorm24", DepthRange::zero_to_one}, 4096},
      {{Technique::reversed_infinite, "float32", DepthRange::zero_to_one}, 8388608},
      {{Technique::log_fragment, "float32", DepthRange::gl}, 1024},
      {{Technique::log_fragment, "unorm24", DepthRange::gl}, 64},
      {{Technique::linear, "float32", DepthRange::gl}, 16384},
      {{Technique::linear, "unorm24", DepthRange::gl}, 8192},
      {{Technique::layered, "float32", DepthRange::gl}, 4096},
  };
  OpenClRuntime rt;
  int fights = 0;
  for (const std::string prof : {"ideal", "llvmpipe", "softpipe"}) {
    std::vector<std::string> sets = profile(prof).sets;
    sets.push_back("bound_model=" + prof);
    Scene s = load_scene("", sets);
    const double r = s.rotation_range_deg * M_PI / 180;
    uint64_t seed = 1;
    for (const auto& [pair, z] : rows) {
      const MtsBound b = mts_bound(s, pair, z);
      std::mt19937_64 rng(seed++);
      std::uniform_real_distribution<double> u(-r, r);
      bool fought = false;
      for (size_t done = 0; done < n && !fought; done += chunk) {
        std::vector<Angles> angles;
        if (done == 0)
          for (int c = 0; c < 8; ++c) angles.push_back({c & 1 ? r : -r, c & 2 ? r : -r, c & 4 ? r : -r});
        while (angles.size() < std::min(chunk, n - done) + (done == 0 ? 8 : 0))
          angles.push_back({u(rng), u(rng), u(rng)});
        Scene part = s;
        part.frames = static_cast<int>(angles.size());
        Orientations o;
        o.at[z] = angles;
        MtsEvaluator ev(rt, part, pair, o);
        const Outcome out = ev.run({{z, b.s}}).at(0).outcome;
        fought = out == Outcome::fight || out == Outcome::non_finite;
      }
      fights += fought;
      fmt::print("{:<9} {:<36} z = {:<9g} mts_bound {:<11.4g} {}\n", prof, pair.label(), z, b.s,
                 fought ? "FIGHTS" : fmt::format("clean over {} orientations", n + 8));
    }
  }
  fmt::print("{} of {} rows fight at mts_bound\n", fights, 3 * rows.size());
  return fights == 0 ? 0 : 1;
}
