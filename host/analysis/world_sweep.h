// world: how far from the world origin content can sit before the vertex transform, not the
// depth buffer, decides whether it fights. For each pair and transform (pipeline.transform), the
// camera and the planes are moved along a direction to world distance R; the MTS at eye distance
// z is searched there as `mts` searches it (the scene's sampling), and R holds when that MTS is
// within the separation the content needs. R is scanned over powers of two from 1, then bisected
// (log scale) between the last that held and the first that failed.
#pragma once

#include <array>
#include <nlohmann/json.hpp>
#include <vector>

#include "host/model/scene.h"
#include "host/runtime/opencl_runtime.h"

namespace depthprec {

struct WorldRequest {
  double z = 100;                            // the content's eye distance
  double separation = 0;                     // what it needs there (scene units)
  std::array<double, 3> direction{1, 1, 1};  // of the move away from the origin (normalised)
  std::vector<Transform> transforms{Transform::absolute, Transform::camera_relative};
  double precision = 1.0 / 64;  // the bisection stops with fails / holds below 1 + precision
};

// Throws InputError naming what is wrong (z or separation not positive, a zero direction, a pair
// whose far plane is nearer than z).
void validate(const WorldRequest& r, const Scene& scene);

// The scene with camera and planes at world_position and the transform t.
Scene with_world(const Scene& scene, const std::array<double, 3>& world_position, Transform t);

// The farthest world distance R the sweep may try: every coordinate within world_position's
// bound (2^40) along the direction.
double world_distance_limit(const WorldRequest& r);

// One pair's answer: technique, format, depth_range, and per transform (named as the scene key
// spells it): mts_at_origin, largest_world_distance (absent when not even the origin holds),
// mts_there, fails_at (the nearest R found to fail; absent when holds_to_limit) and mts_at_fail,
// holds_to_limit, searches (MTS searches run).
nlohmann::json world_record(OpenClRuntime& rt, const Scene& scene, const EvalPair& pair,
                            const WorldRequest& r);

}  // namespace depthprec
