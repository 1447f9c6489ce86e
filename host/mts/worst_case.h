// Worst-case sampling of the MTS (docs/mts.md, "The worst case"): the paper's frames sample one
// path through the cube of orientations the scene allows (each axis within
// ±rotation_range_deg); the worst case is the largest separation that fights for any orientation
// in it. After the paper's search each resolved row is searched again over rounds of new
// orientations -- the cube's corners, then a low-discrepancy sequence over the cube -- each round
// as many as all before it (round_size, then doubling), continuing the row's bracket, until a
// round raises the MTS by no more than worst_case.tolerance or max_rounds ran. Which orientation
// fights at a separation is a matter of rounding coincidences that change within hundredths of a
// degree (docs/mts.md), so the rounds sample rather than refine locally.
#pragma once

#include <functional>
#include <vector>

#include "host/model/frame_setup.h"
#include "host/mts/mts_row.h"
#include "host/mts/probe.h"

namespace depthprec {

class OpenClRuntime;  // host/runtime/opencl_runtime.h

// How many orientations round k (1-based) samples: round_size * 2^(k - 1).
size_t round_size(const Scene& scene, int round);
// The orientations of round k: angle triples inside the rotation cube, none of an earlier round's.
std::vector<Angles> round_orientations(const Scene& scene, int round);
// Round k's orientations in chunks of round_size, as the rounds are evaluated: an evaluator holds
// plane A of one chunk, so memory does not grow with the rounds.
std::vector<std::vector<Angles>> round_chunks(const Scene& scene, int round);

// Runs `use` with an evaluator of the pair for `scene` (its frames a chunk's or one orientation's)
// and the orientations the rounds sampled: the caller owns its construction and its statistics.
using WithEvaluator = std::function<void(const Scene& scene, const Orientations& orientations,
                                         const std::function<void(ProbeEvaluator&)>& use)>;

// Refines rows (search_pair's over the scene's own frames, in any order) to the worst case:
// mts and its bracket become the worst case's, mts_paper keeps the paper's, orientations and
// convergence say what the answer rests on; the work of every round is added to the row. Rows
// without a resolved MTS are left as they are. stop: as for search_pair.
void refine_worst_case(const WithEvaluator& with_evaluator, const Scene& scene,
                       const EvalPair& pair, std::vector<MtsRow>& rows,
                       const std::function<bool()>& stop = {});

// The MTS rows of these distances on the emulated pipeline as the scene samples them: the
// search over its frames, refined to the worst case under worst-case sampling.
std::vector<MtsRow> search_sampled(OpenClRuntime& rt, const Scene& scene, const EvalPair& pair,
                                   const std::vector<double>& distances,
                                   const std::function<bool()>& stop = {});

}  // namespace depthprec
