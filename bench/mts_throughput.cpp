// Fragment pairs per second of the MTS kernel per (technique, format), in the regimes of
// host/mts/mts_timing.h, and beside them the scalar host reference's (one thread, every pixel). Not
// a test: speed targets live here and in docs/performance.md; bench/side_by_side.sh adds the
// default table's wall time.
// Usage: mts_throughput [technique,...] [format,...] [kernel side] [repeats: the fastest of n runs]
//                       [regime,...: far, near, at_mts]
#include <fmt/format.h>

#include <algorithm>
#include <sstream>

#include "host/model/scene.h"
#include "host/mts/mts_timing.h"
#include "host/runtime/opencl_runtime.h"

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
  const int repeats = argc > 4 ? std::stoi(argv[4]) : 1;
  const auto regimes = split(argc > 5 ? argv[5] : "far,near,at_mts");
  const Scene scene = load_scene(
      "", {"kernel=[" + side + "," + side + "]", "viewport=[" + side + "," + side + "]"});
  OpenClRuntime rt;
  fmt::print("{:<20} {:<9} {:<6} {:>14} {:>10} {:>14} {:>9} {:>12} {:>12} {:>16}\n", "technique",
             "format", "probes", "fragment pairs", "seconds", "pairs/s", "ns/pair", "rows raster",
             "rows reused", "host ref pairs/s");
  for (const auto& t : techniques)
    for (const auto& f : formats) {
      const EvalPair pair{parse_technique(t), f, DepthRange::zero_to_one};
      const double host_ref = time_host_reference(scene, pair, 4).pairs_per_second();
      for (const TimingRegime regime :
           {TimingRegime::far, TimingRegime::near, TimingRegime::at_mts}) {
        if (std::find(regimes.begin(), regimes.end(), to_string(regime)) == regimes.end()) continue;
        const Throughput r = time_depth_path(rt, scene, pair, regime, repeats);
        fmt::print(
            "{:<20} {:<9} {:<6} {:>14} {:>10.3f} {:>14.3g} {:>9.2f} {:>12} {:>12} {:>16.3g}\n", t,
            f, to_string(regime), r.fragment_pairs, r.wall_seconds, r.pairs_per_second(),
            r.ns_per_pair(), r.rows_rasterised, r.rows_reused, host_ref);
      }
    }
}
