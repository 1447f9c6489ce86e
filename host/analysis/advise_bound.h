// advise under the guaranteed MTS (host/mts/mts_bound.h): the near and far planes at which every
// checked distance's mts_bound is within the separation, so two planes that far apart fight on no
// implementation of the bound model in no orientation of the cube. Pure analysis: no rendering, no
// sampling; `advise` prints it beside the sampled answer (host/analysis/advise.h).
#pragma once

#include <nlohmann/json.hpp>

#include "host/analysis/advise.h"

namespace depthprec {

// Whether near n (and far f, when f > 0) holds under the bound: mts_bound at every distance
// advise_distances(r) names is at most the separation there.
bool bound_within(const Scene& scene, const EvalPair& pair, const AdviseRequest& r, double n,
                  double f = 0);

// The pair's answer under the bound: near_bound (absent when not even a near plane next to the
// content holds), near_bound_from_floor, and for a technique with a far plane far_bound (with
// that near, the farthest far plane that holds up to the ceiling) and far_bound_to_ceiling.
// Each value is as text prints it, rounded to the safe side, and holds there and beyond (near
// times 1.01, 1.1 and 2; far divided by them).
nlohmann::json bound_answer(const Scene& scene, const EvalPair& pair, const AdviseRequest& r);

}  // namespace depthprec
