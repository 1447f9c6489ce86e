// A fixed timing workload for the MTS kernel of one pair, so techniques and formats compare on
// equal work: 16 distances z = 2..2^16, one probe each, timed after a warm-up launch (the program
// build excluded). "far" probes (s = z/8) are clean and decided mostly from piece ends; "near"
// probes (s = 16 vertex bounds) sit close to the MTS of good set-ups, where pixels are evaluated
// one by one: the cost of the technique's depth path. "at_mts" probes sit just above each
// distance's MTS (s = 1.02 x the MTS a search finds first, untimed): clean probes where most pixels
// must be evaluated, the bulk of a search's work once bounds decide the probes far above the MTS.
#pragma once

#include <cstdint>
#include <vector>

#include "host/model/scene.h"
#include "host/mts/probe.h"

namespace depthprec {

class OpenClRuntime;  // host/runtime/opencl_runtime.h

enum class TimingRegime { far, near, at_mts };
// Where an "at_mts" probe sits: this factor above the MTS, clean in every frame the search saw.
constexpr double kAtMtsFactor = 1.02;
const char* to_string(TimingRegime r);

struct Throughput {
  uint64_t fragment_pairs = 0;
  double wall_seconds = 0, kernel_seconds = 0;
  // Where the work went: kernel rows rasterised (the rest were decided from code bounds), and of
  // them those whose plane-B coverage was plane A's (MtsEvaluator::rows_with_coverage_of_a).
  uint64_t rows_rasterised = 0, rows_reused = 0;
  double pairs_per_second() const { return wall_seconds > 0 ? fragment_pairs / wall_seconds : 0; }
  double ns_per_pair() const { return fragment_pairs ? 1e9 * kernel_seconds / fragment_pairs : 0; }
};

// The probes, timed after a warm-up launch (the program build excluded). repeats > 1: the timed
// batch runs that many times and the fastest run counts.
Throughput time_probes(OpenClRuntime& rt, const Scene& scene, const EvalPair& pair,
                       const std::vector<Probe>& probes, int repeats = 1);

// repeats > 1: the timed batch runs that many times and the fastest run counts (this VM's
// timings vary by 10-20 % from run to run; the minimum is the stable figure).
Throughput time_depth_path(OpenClRuntime& rt, const Scene& scene, const EvalPair& pair,
                           TimingRegime regime, int repeats = 1);

// The scalar host reference (host/mts/reference_pipeline.h) on the same pair: both planes' stored
// codes at every kernel pixel of `frames` frames of one probe (z = 2^8, s = 16 vertex bounds),
// one thread, no shortcuts; fragment_pairs and wall_seconds are set.
Throughput time_host_reference(const Scene& scene, const EvalPair& pair, int frames);

}  // namespace depthprec
