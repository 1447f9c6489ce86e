// The spread between implementation profiles (`mts --profiles`, `table --profiles`): each pair's
// MTS under every profile named, side by side, and how far apart they are, so a user sees where
// an answer depends on the rasterizer rather than on the format and technique.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "host/model/scene.h"

namespace depthprec {

class OpenClRuntime;  // host/runtime/opencl_runtime.h

struct ProfiledScene {
  std::string profile;
  Scene scene;  // the scene with that profile's settings
};

// One pair under every profile: technique, format, depth_range, and rows (scene distance order)
// of z, mts {profile: MTS or null}, verdict {profile: verdict}, and spread: the largest MTS over
// the smallest (null unless every profile resolved the row).
nlohmann::json profiles_record(OpenClRuntime& rt, const std::vector<ProfiledScene>& scenes,
                               const EvalPair& pair);

}  // namespace depthprec
