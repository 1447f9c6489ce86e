// Depth bias under worst-case sampling (docs/bias.md): the units and slope factor a decal needs
// must hold in every orientation of the planes the scene allows, not only on the paper's frames.
// After the searches over the scene's frames, each resolved answer is probed over the rounds of
// orientations the MTS's worst case samples (host/mts/worst_case.h), a chunk at a time; an
// orientation where the answer fails is searched alone and the answer becomes the larger of the
// two, until the chunk passes.
#pragma once

#include <vector>

#include "host/bias/bias_search.h"
#include "host/model/frame_setup.h"
#include "host/mts/refinement.h"

namespace depthprec {

// Refines the answers of search_bias over the scene's frames (one per distance) to the worst
// case with the one refinement (host/mts/refinement.h) over the source's evaluators; answers that
// did not resolve are left as they are.
void refine_bias_worst_case(EvaluatorSource<BiasEvaluator>& source, const Scene& scene,
                            const EvalPair& pair, const BiasOptions& options,
                            const std::vector<double>& distances,
                            std::vector<BiasAnswers>& answers);

// The answers of these distances as the scene samples them: search_bias over its frames, refined
// to the worst case under worst-case sampling.
std::vector<BiasAnswers> search_bias_sampled(EvaluatorSource<BiasEvaluator>& source,
                                             const Scene& scene, const EvalPair& pair,
                                             const BiasOptions& options,
                                             const std::vector<double>& distances);

}  // namespace depthprec
