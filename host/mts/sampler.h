// The sampler of orientations for the worst case (docs/mts.md, "The worst case"): rounds of angle
// triples inside the rotation cube the scene allows (each axis within ±rotation_range_deg) -- the
// cube's corners, then a low-discrepancy sequence over the cube -- each round as many as all
// before it (round_size, then doubling). Which orientation fights at a separation is a matter of
// rounding coincidences that change within hundredths of a degree (docs/mts.md), so the rounds
// sample rather than refine locally. What they sample travels as Orientations
// (host/model/frame_setup.h) to the evaluators; the scene itself never holds it.
#pragma once

#include <cstddef>
#include <vector>

#include "host/model/scene.h"

namespace depthprec {

// How many orientations round k (1-based) samples: round_size * 2^(k - 1).
size_t round_size(const Scene& scene, int round);
// The orientations of round k: angle triples inside the rotation cube, none of an earlier round's.
std::vector<Angles> round_orientations(const Scene& scene, int round);
// Round k's orientations in chunks of round_size, as the rounds are evaluated: an evaluator holds
// plane A of one chunk, so memory does not grow with the rounds.
std::vector<std::vector<Angles>> round_chunks(const Scene& scene, int round);

}  // namespace depthprec
