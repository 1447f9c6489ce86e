#include "host/mts/mts_run.h"

#include "host/mts/scene_run.h"

namespace depthprec {

MtsRun run_scene(OpenClRuntime& rt, const Scene& scene,
                 const std::function<void(const std::string&)>& log, const RunControl& control) {
  return SceneRun(rt, scene, log, control).run();
}

}  // namespace depthprec
