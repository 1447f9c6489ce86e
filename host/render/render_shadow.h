// `shadow --source rendered`: the proven biases checked on the system's OpenGL. Per receiver
// plane of the emulation's sampling, the caster triangle is drawn into a depth texture of the
// format (the driver's transform, set-up, interpolation, polygon offset and storage), and a
// receiver pass looks each receiver point up in it through the filter's texels in a fragment
// shader. At each recipe's bound no point may shadow itself; at 90 % of it some should. The gap
// the constant costs is measured on a wall standing on level ground.
#pragma once

#include <nlohmann/json.hpp>

#include "host/shadow/shadow_run.h"

namespace depthprec {

// Planes rendered per cascade at most: the first of the emulation's.
constexpr uint32_t kRenderedShadowPlanes = 256;

// The check of one cascade on the current GL context, from its record's bound: per recipe the
// acne points at the bound and at 90 % of it, and whether all three were clean at the bound.
nlohmann::json rendered_shadow_check(const ShadowRequest& r, size_t cascade,
                                     const nlohmann::json& record);

// The shadow gap a depth bias of bias_metres (along the light, on the receiver) costs a wall
// standing on level ground, three ways: the formula (gap_of), a ray cast (the first ground point
// whose ray to the light meets the wall farther than the bias) and rendered (wall and ground drawn
// into the cascade's map, ground points behind the wall looked up through the nearest texel,
// averaged over 8 sub-texel placements).
nlohmann::json rendered_shadow_gap(const ShadowSetup& s, size_t cascade, double bias_metres);

}  // namespace depthprec
