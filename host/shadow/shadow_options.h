// What a user asks `shadow` (docs/shadow.md, docs/cli.md): the command's options and a scene's
// "shadow" block (which `report` reads) fill the same fields, whose defaults are here once, and
// turn into a checked request the same way.
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "host/shadow/shadow_run.h"

namespace depthprec {

struct ShadowOptions {
  std::string light = "directional";  // or "spot": one perspective map, rows at `distances`
  double spot_angle = 60;             // degrees, the spot's full cone
  bool spot_angle_given = false;      // named on the command line (refused for a directional light)
  std::vector<double> distances;      // spot: receiver distances along its axis, metres
  // Cascades: camera splits fitted as engines fit them, or light boxes given directly (a spot
  // light's near and far: one value each, default 0.1 and 100).
  std::vector<double> splits, extent, light_near, light_far;
  double camera_near = 0.1, fov = 60, aspect = 16.0 / 9.0, caster_padding = 0;
  int resolution = 2048;
  std::string format = "float32", filter = "pcf3", api = "gl", r_unorm, slope = "max";
  bool reversed = false;
  double slope_max = 80, light_elevation = 52, light_azimuth = 30;
  std::vector<double> world_position{0, 0, 0};
  std::vector<std::string> engines;  // empty: all
  std::string bound_model = "binary32";
  uint32_t planes = 2048, grid = 8;
  uint64_t seed = 1;
};

// The splits used when neither splits nor boxes are given.
const std::vector<double>& default_shadow_splits();

// Throws InputError naming the option or key and what is allowed (docs/cli.md `shadow`).
ShadowRequest shadow_request(const ShadowOptions& o, bool emulate);

// A scene's "shadow" block: the same fields under the same names (light_elevation, ...); unknown
// keys and values of the wrong type are InputErrors that name `where` and the key.
ShadowOptions shadow_options_from_json(const nlohmann::json& block, const std::string& where);

}  // namespace depthprec
