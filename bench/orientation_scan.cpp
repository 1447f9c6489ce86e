// How the MTS of one pair at one distance depends on the orientation of the planes (docs/mts.md,
// "The worst case"): the paper's path sampled over `frames` frames gives the row's MTS and the
// frame that decided its largest fight; then the MTS of that orientation alone, and of its
// neighbours one `step` degrees apart along each axis (20 each side), each searched alone; then
// a grid of 9 x 9 x 9 orientations over the rotation cube, each alone, counted by MTS. Every MTS
// is printed relative to the path's. A smooth dependence would show neighbours near 1; rounding
// coincidences show 1 at the centre and scattered values beside it.
//
// Usage: build/bench/orientation_scan TECHNIQUE FORMAT DEPTH_RANGE Z [frames (1000)] [step (0.002)]
//   e.g. build/bench/orientation_scan linear float32 gl 16384 1000 0.01
#include <fmt/format.h>

#include <cmath>
#include <cstdlib>
#include <map>
#include <string>
#include <vector>

#include "host/base/errors.h"
#include "host/model/frame_setup.h"
#include "host/model/scene.h"
#include "host/mts/mts_evaluator.h"
#include "host/mts/mts_search.h"

using namespace depthprec;

namespace {

// The MTS of plane A at z over exactly these orientations (paper sampling: no rounds).
double mts_over(OpenClRuntime& rt, const Scene& scene, const EvalPair& pair, double z,
                const std::vector<Angles>& list) {
  Scene s = scene;
  s.frames = static_cast<int>(list.size());
  MtsEvaluator ev(rt, s, pair, Orientations{{{z, list}}});
  return search_pair(ev, s, pair, {z})[0].mts;
}

}  // namespace

int main(int argc, char** argv) try {
  if (argc < 5) {
    fmt::print(stderr, "usage: {} TECHNIQUE FORMAT DEPTH_RANGE Z [frames] [step degrees]\n",
               argv[0]);
    return 2;
  }
  const EvalPair pair{parse_technique(argv[1]), argv[2], parse_depth_range(argv[3])};
  const double z = std::atof(argv[4]);
  const int frames = argc > 5 ? std::atoi(argv[5]) : 1000;
  const double step = (argc > 6 ? std::atof(argv[6]) : 0.002) * M_PI / 180;
  const Scene scene = load_scene("", {"sampling=paper", fmt::format("frames={}", frames),
                                      fmt::format("distances=[{:.17g}]", z)});
  OpenClRuntime rt;
  // The path's answer and the frame that decided its largest fight.
  std::vector<Angles> path;
  for (int f = 0; f < frames; ++f) path.push_back(frame_angles(scene, f));
  const double whole = mts_over(rt, scene, pair, z, path);
  int decider = -1;
  for (int f = 0; f < frames && decider < 0; ++f)
    if (mts_over(rt, scene, pair, z, {path[static_cast<size_t>(f)]}) >= whole) decider = f;
  if (decider < 0) {
    fmt::print("{} z = {}: MTS {:.6g} over {} frames; no single frame reaches it\n", pair.label(),
               z, whole, frames);
    return 0;
  }
  const Angles c = path[static_cast<size_t>(decider)];
  const double deg = 180 / M_PI, r = scene.rotation_range_deg / deg;
  fmt::print(
      "{} z = {}: MTS {:.6g} over {} frames, reached by frame {} alone ({:.4f}, {:.4f}, "
      "{:.4f} degrees)\n",
      pair.label(), z, whole, frames, decider, c[0] * deg, c[1] * deg, c[2] * deg);
  for (int axis = 0; axis < 3; ++axis) {
    std::string line = fmt::format("axis {} in steps of {} degrees:", axis, step * deg);
    for (int k = -20; k <= 20; ++k) {
      Angles a = c;
      a[axis] += k * step;
      line += std::abs(a[axis]) > r
                  ? " ."
                  : fmt::format(" {:.2f}", mts_over(rt, scene, pair, z, {a}) / whole);
    }
    fmt::print("{}\n", line);
  }
  std::map<double, int> counts;  // MTS relative to the path's, to 0.05
  const int g = 9;
  for (int i = 0; i < g; ++i)
    for (int j = 0; j < g; ++j)
      for (int k = 0; k < g; ++k) {
        const Angles a{r * (-1 + 2.0 * i / (g - 1)), r * (-1 + 2.0 * j / (g - 1)),
                       r * (-1 + 2.0 * k / (g - 1))};
        ++counts[std::round(mts_over(rt, scene, pair, z, {a}) / whole * 20) / 20];
      }
  std::string hist = fmt::format("{0}x{0}x{0} grid over the cube, MTS / path's:", g);
  for (const auto& [v, n] : counts) hist += fmt::format(" {:.2f}: {}", v, n);
  fmt::print("{}\n", hist);
  return 0;
} catch (const std::exception& e) {
  fmt::print(stderr, "orientation_scan: {}\n", e.what());
  return 1;
}
