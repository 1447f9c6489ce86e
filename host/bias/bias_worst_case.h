// Depth bias under worst-case sampling (docs/bias.md): the units and slope factor a decal needs
// must hold in every orientation of the planes the scene allows, not only on the paper's frames.
// After the searches over the scene's frames, each resolved answer is probed over the rounds of
// orientations the MTS's worst case samples (host/mts/worst_case.h), a chunk at a time; an
// orientation where the answer fails is searched alone and the answer becomes the larger of the
// two, until the chunk passes.
#pragma once

#include <functional>
#include <vector>

#include "host/bias/bias_search.h"
#include "host/model/frame_setup.h"

namespace depthprec {

// Runs `use` with a bias evaluator of the pair for `scene` (its frames a chunk's or one
// orientation's) and the orientations the rounds sampled.
using WithBiasEvaluator = std::function<void(const Scene& scene, const Orientations& orientations,
                                             const std::function<void(BiasEvaluator&)>& use)>;

// Refines the answers of search_bias over the scene's frames (one per distance) to the worst
// case; answers that did not resolve are left as they are.
void refine_bias_worst_case(const WithBiasEvaluator& with_evaluator, const Scene& scene,
                            const EvalPair& pair, const BiasOptions& options,
                            const std::vector<double>& distances,
                            std::vector<BiasAnswers>& answers);

}  // namespace depthprec
