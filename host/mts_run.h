// Runs every pair of a scene through the MTS search and gathers what the reports need.
#pragma once

#include <functional>

#include "host/opencl_runtime.h"
#include "host/report.h"

namespace depthprec {

struct MtsRun {
  std::vector<MtsRow> rows;  // pair order of the scene, distance order within a pair
  RunInfo info;
};

// log: where verbose lines go (variants built, pairs evaluated); null for silence.
MtsRun run_scene(OpenClRuntime& rt, const Scene& scene,
                 const std::function<void(const std::string&)>& log = {});

}  // namespace depthprec
