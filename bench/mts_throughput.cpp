// Fragment pairs per second of the MTS kernel, per (technique, format): fixed batches of probes
// so every configuration does comparable work, timed after a warm-up launch (program build
// excluded). "far": s = z/8, clean, decided mostly from piece ends; "near": s = 16 vertex bounds,
// close to the MTS of good set-ups, where pixels are evaluated one by one. Not a test.
// Usage: mts_throughput [technique,...] [format,...] [kernel side]
#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <sstream>

#include "host/frame_setup.h"
#include "host/mts_evaluator.h"
#include "host/scene.h"

using namespace depthprec;

namespace {
std::vector<std::string> split(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream ss(s);
  std::string item;
  while (std::getline(ss, item, ',')) out.push_back(item);
  return out;
}
}  // namespace

int main(int argc, char** argv) {
  const auto techniques = split(argc > 1 ? argv[1] : "standard,reversed,log_fragment,linear");
  const auto formats = split(argc > 2 ? argv[2] : "unorm24,float32");
  const std::string side = argc > 3 ? argv[3] : "200";
  const Scene scene = load_scene("", {"kernel=[" + side + "," + side + "]", "viewport=[" + side + "," + side + "]"});
  OpenClRuntime rt;
  std::vector<Probe> far, near;
  for (int i = 1; i <= 16; ++i) {
    const double z = std::ldexp(1.0, i);
    far.push_back({z, z / 8});
    near.push_back({z, 16 * vertex_bound(z)});
  }
  fmt::print("{:<20} {:<9} {:<5} {:>14} {:>10} {:>14}\n", "technique", "format", "probes", "fragment pairs",
             "seconds", "pairs/s");
  for (const auto& t : techniques)
    for (const auto& f : formats) {
      const EvalPair pair{parse_technique(t), f, DepthRange::zero_to_one};
      MtsEvaluator ev(rt, scene, pair);
      ev.run({far.front()});  // warm-up: builds the program
      for (const auto& [name, probes] : {std::pair{"far", far}, std::pair{"near", near}}) {
        const uint64_t before = ev.fragment_pairs();
        const auto t0 = std::chrono::steady_clock::now();
        ev.run(probes);
        const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        const uint64_t pairs = ev.fragment_pairs() - before;
        fmt::print("{:<20} {:<9} {:<5} {:>14} {:>10.3f} {:>14.3g}\n", t, f, name, pairs, secs, pairs / secs);
      }
    }
}
