// What the driver decides for itself, so `render` cannot be told otherwise: the pipeline settings
// render refuses (and `compare` resets, render_run.h's rendered_counterpart), and the check that a
// scene asks for none of them.
#pragma once

#include <vector>

#include "host/model/scene.h"

namespace depthprec {

// A pipeline setting the driver decides for itself: render refuses any value but the default.
// An implementation form (a profile's, reset set) is one a real rasterizer has its own of:
// `compare` and `bias --source rendered` render the scene with it at its default
// (rendered_counterpart). The others (divide, rounding, denormals, contraction) are refused there
// too: an emulation that sets them has no rendered counterpart.
struct DriverSetting {
  const char* setting;  // as named in the refusal, e.g. "viewport=fma"
  const char* why;
  bool (*changed)(const Pipeline&);
  void (*reset)(Pipeline&);  // nullptr: not an implementation form
};
const std::vector<DriverSetting>& driver_settings();

// Throws InputError when the scene sets a driver setting or its kernel is larger than the
// viewport.
void check_renderable(const Scene& scene);

}  // namespace depthprec
