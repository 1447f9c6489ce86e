// Runs every pair of a scene through the MTS search with probes decided by rendering
// (RenderEvaluator): the rendered counterpart of run_scene (host/mts/mts_run.h), with the same
// rows, run control and batch behaviour. One OpenGL context, one pair after the other.
#pragma once

#include <functional>
#include <string>

#include "host/mts/run_rows.h"
#include "host/render/gl_context.h"

namespace depthprec {

// Checks, before any rendering, that the driver stores every pair's format (InputError listing
// what it does store) and that the scene asks for nothing only the emulator has
// (check_renderable); returns the depth buffers the pairs get, as the output header reports them.
std::map<std::string, std::string> check_scene_renders(const Scene& scene);

// The scene a real rasterizer renders for an emulated one: the same, with the emulation's
// implementation forms (driver_settings with a reset: a profile's) back at their defaults, since
// the driver has its own. What `compare --profile llvmpipe` renders.
Scene rendered_counterpart(const Scene& scene);

MtsRun render_scene(GlContext& gl, const Scene& scene,
                    const std::function<void(const std::string&)>& log = {},
                    const RunControl& control = {});

}  // namespace depthprec
