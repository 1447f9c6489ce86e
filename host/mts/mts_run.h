// Runs every pair of a scene through the MTS search and gathers what the reports need (run_scene,
// in the steps of SceneRun, host/mts/scene_run.h).
#pragma once

#include <functional>
#include <string>

#include "host/model/scene.h"
#include "host/mts/run_rows.h"

namespace depthprec {

class OpenClRuntime;  // host/runtime/opencl_runtime.h

// log: where verbose lines go (variants built, pairs evaluated); null for silence. The rows
// returned are the ones this run computed, in scene order.
MtsRun run_scene(OpenClRuntime& rt, const Scene& scene,
                 const std::function<void(const std::string&)>& log = {},
                 const RunControl& control = {});

}  // namespace depthprec
