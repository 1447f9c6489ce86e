// Shader programs from the embedded sources (host/render/shaders/), compiled on the current
// context with the defines prepended: the driver's compiler, the driver's arithmetic.
#pragma once

#include <string>

#include "host/model/scene.h"

namespace depthprec {

// A linked program of the vertex and fragment shader at those embedded paths; throws
// RuntimeError with the driver's log when either does not compile or they do not link.
// The embedded shader at path with its #includes expanded, as GLSL takes it (no #version).
std::string glsl_source(const std::string& path);

// The shaders' defines for a pair under the scene's pipeline: DEPTH_FROM, FRAG_DEPTH, VERTEX_LOG,
// DEPTH_RANGE_GL, COMPOSE_PREMULTIPLIED, VIEW_TRANSLATE and RELATIVE_TO_EYE.
std::string shader_defines(const Scene& scene, const EvalPair& pair);

unsigned link_program(const std::string& vertex_path, const std::string& fragment_path,
                      const std::string& defines);

}  // namespace depthprec
