// A plain C++ implementation of the emulated pipeline (docs/spec.md 2), written apart from the
// kernel to check it: same documented arithmetic forms, same formats/ source for storage, scalar
// and slow. Tests compare its stored codes with the kernel's (mts_codes) bit for bit.
#pragma once

#include "host/model/scene.h"
#include "host/mts/probe.h"

namespace depthprec {

FrameCodes reference_frame(const Scene& scene, const EvalPair& pair, const Probe& probe, int frame);

}  // namespace depthprec
