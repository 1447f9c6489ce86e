// world: how far from the world origin content can sit before the vertex transform, not the
// depth buffer, decides whether it fights (docs/spec.md 2, "World position"). Camera and planes
// move together to R times a direction; what the vertex stage keeps of a vertex's world
// coordinate is a grid whose spacing is constant within each binade of the coordinate's
// magnitude, and within one binade the MTS saws between about 0 and a full spacing as the
// planes' translation moves between two grid points. So one position that holds says nothing
// about its neighbours, and the MTS is not monotonic in R: the limit is decided per binade. It
// is the start of the first binade in which the spacing reaches the separation (the sawtooth
// comes within a rounding of a full spacing there), or of an earlier binade where a position at
// the sawtooth's peak was measured to fail. Binades whose spacing cannot reach the separation
// even taken twice (each plane's coordinates round twice) are decided without a search.
#pragma once

#include <array>
#include <nlohmann/json.hpp>
#include <vector>

#include "host/model/scene.h"

namespace depthprec {

class OpenClRuntime;  // host/runtime/opencl_runtime.h

struct WorldRequest {
  double z = 100;                            // the content's eye distance
  double separation = 0;                     // what it needs there (scene units)
  std::array<double, 3> direction{1, 1, 1};  // of the move away from the origin (normalised)
  std::vector<Transform> transforms{Transform::absolute, Transform::camera_relative};
};

// Throws InputError naming what is wrong (z or separation not positive, a zero direction, a pair
// whose far plane is nearer than z).
void validate(const WorldRequest& r, const Scene& scene);

// The scene with camera and planes at world_position and the transform t.
Scene with_world(const Scene& scene, const std::array<double, 3>& world_position, Transform t);

// The farthest world distance R the sweep may try: every coordinate within world_position's
// bound (2^40) along the direction.
double world_distance_limit(const WorldRequest& r);

// The spacing of the grid that transform t keeps of world coordinates of this magnitude:
// binary32's (absolute: the model matrix and the vertex's products; premultiplied in binary64,
// binary64's; binary16's under a mediump vertex shader), binary64's (camera_relative: the host
// forms the translation), or binary32's of the low part, below 65536, and binary64's of the world
// position (relative_to_eye).
double coordinate_spacing(Transform t, const Scene& scene, double magnitude);

// How far a vertex of either plane reaches from the plane's centre (its half-diagonal): a
// vertex coordinate's magnitude is at most the centre's plus this.
double plane_reach(const Scene& scene, const WorldRequest& r);

// The smallest world distance at which some vertex coordinate (plane A's centre at
// R * direction + (0, 0, -z), give or take plane_reach) reaches `magnitude`, and its axis (0 x,
// 1 y, 2 z: the depth axis of the view, which looks down -z). Infinity when none ever does.
double first_reach(const WorldRequest& r, const Scene& scene, double magnitude, int* axis);

// Where the spacing alone decides (no search): the first world distance whose coordinates reach
// the magnitude from which transform t's spacing is at least the separation.
struct SpacingLimit {
  double distance = 0;    // infinity when no coordinate reaches it within world_distance_limit
  double coordinate = 0;  // that magnitude, a power of two
  double spacing = 0;     // the spacing from it on
  int axis = -1;          // the axis reaching it first
};
SpacingLimit spacing_limit(const WorldRequest& r, const Scene& scene, Transform t);

// A world distance at or below `at` (within one spacing of the depth-axis coordinate) where plane
// A's translation along the view sits just below the midpoint above its grid point, so plane B,
// behind it, rounds onto the next grid point only once the separation is nearly a full spacing:
// the peak of the sawtooth. `at` itself when the direction has no z (the view's depth axis never
// moves).
double sawtooth_peak(const WorldRequest& r, const Scene& scene, Transform t, double at);

// One pair's answer: technique, format, depth_range, and per transform (named as the scene key
// spells it): mts_at_origin; limit (absent when not even the origin holds): every position below
// it holds; holds_to_bound (no binade up to world_distance_limit fails: limit is that bound);
// limit_from ("spacing", "measured": a peak in the binade below the spacing's was found to fail,
// or "bound"); spacing, coordinate, axis ("x", "y", "z"): the grid's spacing at the limit, the
// coordinate's magnitude there and the axis it is on; mts_below and mts_below_at: the largest MTS
// measured below the limit and where; fails_at and mts_at_fail: a position measured to fail, when
// one was (the depth axis's peak just past its own spacing limit); probes: every [R, MTS]
// searched; searches.
nlohmann::json world_record(OpenClRuntime& rt, const Scene& scene, const EvalPair& pair,
                            const WorldRequest& r);

}  // namespace depthprec
