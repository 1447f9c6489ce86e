// Shared helpers for tests that run the MTS evaluator on the PoCL device.
#pragma once

#include <string>
#include <vector>

#include "host/model/profile.h"
#include "host/model/scene.h"
#include "host/mts/mts_evaluator.h"
#include "host/mts/mts_search.h"
#include "host/runtime/opencl_runtime.h"

namespace depthprec::test {

inline OpenClRuntime& runtime() {
  // Never destroyed: a runtime closing at process exit would talk to PoCL after its compiler's
  // statics are gone (storing program binaries asks PoCL to compile).
  static OpenClRuntime& rt = *new OpenClRuntime;
  return rt;
}

// MTS rows of one pair at the given distances, on the scene (default: the paper's).
inline std::vector<MtsRow> mts_rows(const Scene& scene, Technique t, const std::string& format,
                                    DepthRange range, const std::vector<double>& distances) {
  const EvalPair pair{t, format, range};
  MtsEvaluator ev(runtime(), scene, pair);
  return search_pair(ev, scene, pair, distances);
}

// The llvmpipe profile's scene settings, with its clip stage or without it (pipeline.clip=none):
// its arithmetic alone.
inline std::vector<std::string> llvmpipe_sets(bool clip) {
  std::vector<std::string> sets;
  for (const std::string& s : profile("llvmpipe").sets)
    sets.push_back(clip || s != "pipeline.clip=llvmpipe" ? s : "pipeline.clip=none");
  return sets;
}

inline std::vector<double> powers_of_two(int from, int to) {
  std::vector<double> z;
  for (int i = from; i <= to; ++i) z.push_back(static_cast<double>(1ull << i));
  return z;
}

}  // namespace depthprec::test
