// The kernel variant a pair needs: kernels/mts.cl specialised by -D defines for exactly one
// technique class, storage format, depth range and set of pipeline options.
#pragma once

#include <string>

#include "host/model/scene.h"

namespace depthprec {

struct KernelVariant {
  std::string program;  // embedded source path
  std::string options;  // full build options, defines included
  // mts_setup's program (kernels/mts_setup.cl) and its options: the defines it reads, a subset of
  // options', so variants that differ in format, compare or fragment stage share one build.
  std::string setup_program;
  std::string setup_options;
  std::string label;  // short human name, e.g. "projection/LEQUAL/gl/unorm24"
  // mts_raster reads plane A's codes from the plane-A cache instead of computing them
  // (CACHE_A_CODES, interface/mts_layout.h): where the depth path is costly enough (fragment-stage
  // depth, a division or a log per fragment) to pay for the cache's memory traffic, and never with
  // contraction (the cached code must be the one mts_raster would compute).
  bool cache_a_codes = false;
};

KernelVariant mts_variant(const Scene& scene, const EvalPair& pair);

// The technique whose depth path the kernel runs (layered runs its layer mapping's).
Technique depth_path(const Scene& scene, Technique t);

}  // namespace depthprec
