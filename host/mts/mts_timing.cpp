#include "host/mts/mts_timing.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "host/model/frame_setup.h"
#include "host/mts/mts_evaluator.h"
#include "host/mts/mts_search.h"
#include "host/mts/reference_pipeline.h"

namespace depthprec {

const char* to_string(TimingRegime r) {
  return r == TimingRegime::far ? "far" : r == TimingRegime::near ? "near" : "at_mts";
}

namespace {

Throughput time_evaluator(MtsEvaluator& ev, const std::vector<Probe>& probes, int repeats) {
  ev.run({probes.front()});  // warm-up: builds the program and PoCL's work-group function
  Throughput best;
  for (int k = 0; k < std::max(1, repeats); ++k) {
    const uint64_t pairs0 = ev.fragment_pairs();
    const double kernel0 = ev.kernel_seconds();
    const uint64_t rows0 = ev.rows_rasterised(), reused0 = ev.rows_with_coverage_of_a();
    const auto t0 = std::chrono::steady_clock::now();
    ev.run(probes);
    Throughput t;
    t.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    t.fragment_pairs = ev.fragment_pairs() - pairs0;
    t.kernel_seconds = ev.kernel_seconds() - kernel0;
    t.rows_rasterised = ev.rows_rasterised() - rows0;
    t.rows_reused = ev.rows_with_coverage_of_a() - reused0;
    if (k == 0 || t.kernel_seconds < best.kernel_seconds) best = t;
  }
  return best;
}

}  // namespace

Throughput time_depth_path(OpenClRuntime& rt, const Scene& scene, const EvalPair& pair,
                           TimingRegime regime, int repeats) {
  std::vector<Probe> probes;
  for (int i = 1; i <= 16; ++i) {
    const double z = std::ldexp(1.0, i);
    probes.push_back({z, regime == TimingRegime::far ? z / 8 : 16 * vertex_bound(z)});
  }
  MtsEvaluator ev(rt, scene, pair);
  if (regime == TimingRegime::at_mts) {  // the search runs before the counters are read: untimed
    std::vector<double> zs;
    for (const Probe& p : probes) zs.push_back(p.z);
    probes.clear();
    for (const MtsRow& row : search_pair(ev, scene, pair, zs, nullptr, nullptr))
      if (row.verdict() == Verdict::resolved) probes.push_back({row.z, row.mts * kAtMtsFactor});
    if (probes.empty()) return {};
  }
  return time_evaluator(ev, probes, repeats);
}

Throughput time_probes(OpenClRuntime& rt, const Scene& scene, const EvalPair& pair,
                       const std::vector<Probe>& probes, int repeats) {
  if (probes.empty()) return {};
  MtsEvaluator ev(rt, scene, pair);
  return time_evaluator(ev, probes, repeats);
}

Throughput time_host_reference(const Scene& scene, const EvalPair& pair, int frames) {
  const Probe probe{256.0, 16 * vertex_bound(256.0)};
  Throughput t;
  const auto t0 = std::chrono::steady_clock::now();
  for (int f = 0; f < frames; ++f) {
    const FrameCodes codes = reference_frame(scene, pair, probe, f % scene.frames);
    t.fragment_pairs += codes.code_a.size();
  }
  t.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return t;
}

}  // namespace depthprec
