// The dozen rows of the default scene that the guaranteed MTS's dense scan holds to it: the test's
// 1,500 orientations per row (tests/mts/mts_bound.cpp) and the benchmark's 10^5
// (bench/bound_scan.cpp) take the same rows.
#pragma once

#include <utility>
#include <vector>

#include "host/model/scene.h"

namespace depthprec::test {

inline const std::vector<std::pair<EvalPair, double>>& bound_scan_rows() {
  static const std::vector<std::pair<EvalPair, double>> rows = {
      {{Technique::standard, "float32", DepthRange::gl}, 1.005},
      {{Technique::standard, "unorm24", DepthRange::gl}, 512},
      {{Technique::standard, "float32", DepthRange::gl}, 65536},
      {{Technique::reversed, "float32", DepthRange::zero_to_one}, 2},
      {{Technique::reversed, "float32", DepthRange::zero_to_one}, 16384},
      {{Technique::reversed, "unorm24", DepthRange::zero_to_one}, 4096},
      {{Technique::reversed_infinite, "float32", DepthRange::zero_to_one}, 8388608},
      {{Technique::log_fragment, "float32", DepthRange::gl}, 1024},
      {{Technique::log_fragment, "unorm24", DepthRange::gl}, 64},
      {{Technique::linear, "float32", DepthRange::gl}, 16384},
      {{Technique::linear, "unorm24", DepthRange::gl}, 8192},
      {{Technique::layered, "float32", DepthRange::gl}, 4096},
  };
  return rows;
}

}  // namespace depthprec::test
