// The depth-bias measurement on the plain host reference pipeline (host/mts/reference_pipeline.h):
// an API's rule and the options turned into the overlay's terms, for the tests that check
// kernels/bias.cl probe by probe.
#pragma once

#include "host/bias/bias_probe.h"
#include "host/bias/bias_rule.h"
#include "host/mts/reference_pipeline.h"

namespace depthprec {

// One frame of the bias probe on the reference pipeline.
BiasFrame reference_bias_frame(const Scene& scene, const EvalPair& pair, const BiasOptions& options,
                               const BiasProbe& probe, int frame);

}  // namespace depthprec
