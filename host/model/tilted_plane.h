// The rectangle a tilted plane (`bias --tilt`) needs so that it covers the view in a frame
// (docs/spec.md 5.6); the steepest tilt a scene can measure is host/model/tilt_limit.h's.
//
// An untilted plane spans plane_margin times the view at its own distance (docs/spec.md 5.1). A
// tilted one, seen obliquely, reaches deeper on its far side than on its near side, and its far
// side must be wider too: a fixed square, or one lengthened only along y, leaves the kernel's
// corners uncovered from about 45 degrees on, and a symmetric lengthening puts its near half
// behind the camera near 80. So the tilted plane is sized frame by frame: its rectangle is the
// bounding box, in the plane's own coordinates, of the four points where the rays through the
// corners of the view widened by plane_margin meet it (the frame's rotation included).
#pragma once

#include <array>
#include <optional>

#include "host/model/scene.h"

namespace depthprec {

// A rectangle in a plane's own coordinates (x, y before the rotation): its centre and sides.
struct PlaneRect {
  double cx = 0, cy = 0, width = 0, height = 0;
};

// The rectangle of a plane at distance D turned by angles (radians about x, y, z, applied as
// R = Rx(x) Ry(y) Rz(z), the tilt included in x) that covers the view widened by plane_margin:
// the viewport, or the kernel where it is larger. None when a corner ray of that view does not
// meet the plane in front of the camera (the plane is seen too nearly edge-on).
std::optional<PlaneRect> view_footprint(const Scene& scene, double D,
                                        const std::array<double, 3>& angles);

}  // namespace depthprec
