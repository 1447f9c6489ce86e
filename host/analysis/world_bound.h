// world under the guaranteed MTS (host/mts/mts_bound.h): how far from the world origin content can
// sit before mts_bound, over every orientation and implementation of the bound model, exceeds the
// separation it needs. Pure analysis: the bound's terms change with a world coordinate only
// through half an ulp of its magnitude, constant within each binade, so each binade is decided at
// its largest magnitude, in closed form. `world` prints it beside the sampled limit
// (host/analysis/world_sweep.h).
#pragma once

#include <nlohmann/json.hpp>

#include "host/analysis/world_sweep.h"

namespace depthprec {

// For transform t: mts_bound_at_origin, and limit_bound, the first world distance R (a power of
// two, or world_distance_limit: limit_bound_to_limit) from which the binade of R may fail
// (mts_bound above the separation at some position in it); absent when the origin fails.
nlohmann::json world_bound(const Scene& scene, const EvalPair& pair, const WorldRequest& r,
                           Transform t);

}  // namespace depthprec
