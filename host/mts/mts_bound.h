// The guaranteed MTS (docs/bound.md): a separation at and above which plane B
// provably never wins against plane A at any pixel of the kernel, for every orientation in the
// scene's rotation cube (the continuum, not samples), under every implementation the bound model
// allows. It is analysis, not sampling: forward error bounds, one beside each binary32 step, added
// up against the exact gap between the planes.
#pragma once

#include <limits>
#include <string>

#include "host/model/scene.h"
#include "host/mts/mts_row.h"

namespace depthprec {

struct MtsBound {
  // The smallest separation found at which the bound holds (plane B at the search's fl32(z + s), as
  // mts), to the scene's rel_precision; +inf where none holds up to max_separation_factor z, NaN
  // where the model has no bound for the row (`why` says why).
  double s = std::numeric_limits<double>::quiet_NaN();
  std::string why;
  // The error term that weighs most at s (vertex, clip, divide, viewport, position, setup,
  // interpolation, shader, storage), so a user sees what a tighter implementation would have to
  // improve.
  std::string dominant;
};

// The bound for one row: pair at distance z of scene.
MtsBound mts_bound(const Scene& scene, const EvalPair& pair, double z);

// How far apart two computations of one plane at distance z (two tessellations of it, the
// coplanar surfaces `bias` measures) can store their depths under the model, at any kernel pixel
// and orientation: both planes' error bounds and the conversion's width, in window depth; with the
// plane's smallest and largest depth at a kernel pixel. NaN spread where the model has none.
struct CoplanarSpread {
  double spread = std::numeric_limits<double>::quiet_NaN();
  double depth_min = 0, depth_max = 0;
};
CoplanarSpread coplanar_spread(const Scene& scene, const EvalPair& pair, double z);

// A final row's guaranteed MTS under the scene's bound model: mts_bound, bound_model and
// bound_note (the dominant term, or why there is none); left NaN on a row without an MTS. Also
// whether its MTS lies below the world grid's reach (below_world_grid).
void set_mts_bound(MtsRow& row, const Scene& scene);

// How many codes softpipe's 16-bit fast path can store away from the conversion's own interval
// at a pixel `pixels` into its run of quads, for a plane of codes_per_pixel codes per pixel
// along the run (BoundModel::unorm16_step_pixels; mts_bound.cpp gives the proof).
double stepped_code_drift(double codes_per_pixel, int pixels);

// Whether the model proves that no pixel fights at requested separation s (for tests and the
// dense scan): the exact gap exceeds both planes' error bounds and the conversion's width.
bool bound_holds(const Scene& scene, const EvalPair& pair, double z, double s);

}  // namespace depthprec
