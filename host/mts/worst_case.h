// Worst-case sampling of the MTS (docs/mts.md, "The worst case"): the paper's frames sample one
// path through the cube of orientations the scene allows (each axis within
// ±rotation_range_deg); the worst case is the largest separation that fights for any orientation
// in it. After the paper's frames (search_paper_frames) each resolved row is searched again over
// the sampler's rounds of new orientations (host/mts/sampler.h), continuing the row's bracket,
// until a round raises the MTS by no more than worst_case.tolerance or max_rounds ran: the MTS's
// part of the one refinement (host/mts/refinement.h), which bias shares.
#pragma once

#include <functional>
#include <vector>

#include "host/model/frame_setup.h"
#include "host/mts/mts_row.h"
#include "host/mts/probe.h"
#include "host/mts/refinement.h"
#include "host/mts/sampler.h"

namespace depthprec {

class OpenClRuntime;  // host/runtime/opencl_runtime.h

// Refines rows (search_paper_frames' or search_pair's over the scene's own frames, in any order)
// to the worst case with
// the one refinement (host/mts/refinement.h) over the source's evaluators: mts and its bracket
// become the worst case's, mts_paper keeps the paper's, orientations and convergence say what the
// answer rests on; the work of every round is added to the row. Rows without a resolved MTS are
// left as they are. stop: as for search_pair.
void refine_worst_case(EvaluatorSource<ProbeEvaluator>& source, const Scene& scene,
                       const EvalPair& pair, std::vector<MtsRow>& rows,
                       const std::function<bool()>& stop = {});

// The rows of the scene's own frames (the paper's path), as the worst case's first chunk: the
// first frame searched alone, then every frame probed at the row's answer and each one that fights
// searched alone from scratch, on the bisection's own grid -- where each frame's fights are
// monotone in the separation, the largest of the frames' answers is the one search_pair over all
// frames gives, at a fraction of its probes (a clean probe near the MTS renders every frame).
// mts_paper is that answer. stop: as for search_pair.
std::vector<MtsRow> search_paper_frames(EvaluatorSource<ProbeEvaluator>& source, const Scene& scene,
                                        const EvalPair& pair, const std::vector<double>& distances,
                                        const std::function<bool()>& stop = {});

// The MTS rows of these distances as the scene samples them, over the source's evaluators: the
// search over its frames, refined to the worst case under worst-case sampling -- the one place
// that decides it. on_row gets each row once final (under worst-case sampling, after the
// refinement).
std::vector<MtsRow> search_sampled(EvaluatorSource<ProbeEvaluator>& source, const Scene& scene,
                                   const EvalPair& pair, const std::vector<double>& distances,
                                   const std::function<void(const MtsRow&)>& on_row = {},
                                   const std::function<bool()>& stop = {});
// The same on the emulated pipeline.
std::vector<MtsRow> search_sampled(OpenClRuntime& rt, const Scene& scene, const EvalPair& pair,
                                   const std::vector<double>& distances,
                                   const std::function<bool()>& stop = {});

}  // namespace depthprec
