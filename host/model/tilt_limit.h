// The steepest tilt of `bias --tilt` a scene can measure (docs/spec.md 5.6): the tilted planes'
// footprints (host/model/tilted_plane.h) must exist in every frame the scene renders.
#pragma once

#include "host/model/scene.h"

namespace depthprec {

// The steepest tilt (degrees) whose footprint exists in every frame of the scene, less one degree
// so that the far side stays a bounded size (at the geometric limit it runs to infinity): 82.4
// for the default scene (fov 10 degrees, plane_margin 1.1, rotations of 1 degree).
double max_tilt_deg(const Scene& scene);

// Throws InputError naming the limit when the scene's planes tilted tilt_deg cannot cover the
// view in every frame.
void check_tilt(const Scene& scene, double tilt_deg);

}  // namespace depthprec
