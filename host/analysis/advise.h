// advise: the inverse of the MTS question. Given the distances a scene has content at and the
// separation its content needs there, how close can each set-up's near plane come? For each
// pair, a host-driven bisection over the near plane (log scale) in which a near value holds when
// a probe at the required separation is clean at every checked distance: plane B behind plane A
// by that separation never wins the depth test, on the emulated pipeline, in any frame. A larger
// near plane only helps precision, so the answer is the smallest near that holds.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "host/model/scene.h"

namespace depthprec {

class OpenClRuntime;  // host/runtime/opencl_runtime.h

struct AdviseRequest {
  double z_min = 0, z_max = 0;  // the content's distances (eye space, scene units)
  double separation = 0;        // needed there: absolute, or relative to z
  bool relative = false;
  double near_floor_ratio = 1e-6;  // the smallest near tried, as a fraction of z_min
  // The bisection stops when the holding near is within this factor of the failing one (the
  // far plane's likewise).
  double near_precision = 1.0 / 128;
  // The farthest far plane tried, as a multiple of the scene's far plane (or of the farthest
  // content, if that is farther).
  double far_ceiling_ratio = 1e6;

  double separation_at(double z) const { return relative ? separation * z : separation; }
};

// Throws InputError naming what is wrong (an empty or negative range, a separation of 0, a far
// plane nearer than the content for a technique that clips there).
void validate(const AdviseRequest& r, const Scene& scene);

// What every question about content at distances up to `farthest` needing `separation` asks of
// the scene (advise, world): a positive, finite separation, and every pair with a far plane
// having it beyond the content. Throws InputError naming what is wrong.
void check_content_request(const Scene& scene, double farthest, double separation);

// The largest near plane tried: the scene's planes are tilted and span more than the view, so at
// z_min they reach nearer than z_min (nearest_vertex_distance: z_min / 1.023 at a 60 degree view);
// 2^-10 less keeps the vertices' rounding clear of it.
double near_top(const Scene& scene, const AdviseRequest& r);
// The tightest far plane tried for a set-up that fails at the scene's: 2^-10 beyond the farthest
// vertex plane B reaches at z_max (farthest_vertex_distance at z_max plus the separation).
double tight_far(const Scene& scene, const AdviseRequest& r);

// The distances checked: z_min, z_min * 2, z_min * 4, ... below z_max, and z_max.
std::vector<double> advise_distances(const AdviseRequest& r);

// The scene with its near plane at n (and its far plane at f, when f > 0).
Scene with_near(const Scene& scene, double n, double f = 0);

// Whether near n holds for the pair: every checked distance's probe at the required separation is
// clean (no fight, nothing clipped, uncovered or non-finite). worst: a distance that failed.
bool near_holds(OpenClRuntime& rt, const Scene& scene, const EvalPair& pair, const AdviseRequest& r,
                double n, double* worst = nullptr, double f = 0);

// Whether the MTS search (as `mts` runs it, under the scene's sampling) at near n gives every
// checked distance an MTS within the separation.
bool mts_within(OpenClRuntime& rt, const Scene& scene, const EvalPair& pair, const AdviseRequest& r,
                double n, double f = 0);

// v rounded to the four significant digits text output shows, up or down (a value that prints as
// itself, on the safe side of v).
double round_printed(double v, bool up);

// Whether the set-up holds (mts_within) at near n, far f and beyond them on the safe side: near
// n times 1, 1.01, 1.1 and 2 (near_side; up to limit), or far f divided by them (down to limit).
bool holds_beyond(OpenClRuntime& rt, const Scene& scene, const EvalPair& pair,
                  const AdviseRequest& r, double n, double f, bool near_side, double limit);

// One pair's answer: technique, format, depth_range, smallest_near (absent when not even a near
// plane next to the content holds), next_near (the largest near found to fail, absent when the
// floor holds), fails_at (a distance where it fails), holds_from_floor, near_steps, and
// raised_by_mts_check: the steps the near plane rose until mts_within held (the probe at the
// separation alone can be clean where a larger separation fights).
// Techniques with a far plane also get largest_far: with that near plane, the farthest far
// plane that still holds (far_holds_to_ceiling when even the ceiling does; else next_far, the
// nearest far plane found to fail, and far_fails_at), far_steps and far_lowered_by_mts_check.
nlohmann::json advise_record(OpenClRuntime& rt, const Scene& scene, const EvalPair& pair,
                             const AdviseRequest& r);

}  // namespace depthprec
