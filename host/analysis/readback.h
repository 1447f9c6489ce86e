// Reading eye distance back from a stored depth (`depthprec readback`, docs/spec.md 8): per
// technique and format, the distance a shader reconstructs from the depth buffer with the inverse
// engines write, in binary32, against the true distance; and the same code through an exact
// inverse, which separates what storage loses from what the inverse's arithmetic adds.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "host/model/scene.h"

namespace depthprec {

// The inverses as engines and users write them (docs/spec.md 8), each operation in binary32.
enum class Inverse {
  threejs,   // three.js perspectiveDepthToViewZ (standard and reversed branches)
  godot,     // Godot's INV_PROJECTION_MATRIX * vec4(ndc, 1), / w, -z (projections)
  linear,    // n + d (f - n)
  w_buffer,  // d f
  exp2,      // (exp2(d log2(k f + 1)) - 1) / k: Gilg's and three.js's log (k = 1 for three.js)
  cesium,    // exp2(d log2(f - n + 1)) - 1 + n, the log2 a binary32 uniform (reverseLogDepth)
};
const char* to_string(Inverse i);

// The inverses that read back the depth a technique stores (for layered, its layer mapping's).
std::vector<Inverse> inverses_of(Technique t);

struct ReadbackRow {
  EvalPair pair;
  Inverse inverse = Inverse::threejs;
  double distance = 0;  // the true eye distance w
  uint32_t code = 0;    // the code of its exact depth, correctly rounded into the format
  float depth = 0;      // that code as the shader reads it: decoded, rounded to binary32
  double read = 0;      // the distance the binary32 inverse reconstructs from `depth`
  double exact = 0;     // the exact inverse of the code's value (binary128, binary64 for logs)
  double code_gap = 0;  // resolve's resolution at w: the eye distance to the farther neighbour
  double error() const { return read - distance; }
  double relative_error() const;  // |error| / distance
  double storage_error() const { return exact - distance; }
  double arithmetic_error() const { return read - exact; }
  const char* dominant() const;  // "arithmetic" when |arithmetic_error| > |storage_error|
};

// The rows of one pair at distance w, one per inverse of its technique. Throws InputError for a
// distance the pair stores no depth for (outside the clip volume).
std::vector<ReadbackRow> readback(const Scene& scene, const EvalPair& pair, double w);

}  // namespace depthprec
