// The kernel variant a pair needs: kernels/mts.cl specialised by -D defines for exactly one
// technique class, storage format, depth range and set of pipeline options.
#pragma once

#include <string>

#include "host/scene.h"

namespace depthprec {

struct KernelVariant {
  std::string program;  // embedded source path
  std::string options;  // full build options, defines included
  std::string label;    // short human name, e.g. "projection/LEQUAL/gl/unorm24"
};

KernelVariant mts_variant(const Scene& scene, const EvalPair& pair);

// The technique whose depth path the kernel runs (layered runs its layer mapping's).
Technique depth_path(const Scene& scene, Technique t);

}  // namespace depthprec
