// A plain C++ implementation of the emulated pipeline (docs/spec.md 2), written apart from the
// kernel to check it: same documented arithmetic forms, same formats/ source for storage, scalar
// and slow. Tests compare its stored codes with the kernel's (mts_codes) bit for bit.
#pragma once

#include "host/bias/bias_evaluator.h"
#include "host/model/scene.h"
#include "host/mts/probe.h"

namespace depthprec {

FrameCodes reference_frame(const Scene& scene, const EvalPair& pair, const Probe& probe, int frame);

// One frame of the depth-bias measurement (kernels/bias.cl): fight when plane A shows through
// the biased overlay at some kernel pixel; the other flags as the kernel's row words say them.
struct BiasFrame {
  bool fight = false, clipped = false, non_finite = false, uncovered = false;
};
BiasFrame reference_bias_frame(const Scene& scene, const EvalPair& pair, const BiasOptions& options,
                               const BiasProbe& probe, int frame);

}  // namespace depthprec
