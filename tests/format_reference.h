// An independent reference for storage-format encoding, written without formats/depth_format.h:
// it rounds with the FPU (x87 long double for unorm, where d * (2^b - 1) needs up to 56 bits and
// long double's 64-bit significand holds it exactly; binary64 scaling by powers of two for
// floats, which is exact) instead of integer shift-and-round.
#pragma once

#include <cstdint>
#include <string>

namespace depthprec::test {

struct ReferenceFormat {
  std::string name;
  bool unorm = false;
  int bits = 0;      // unorm
  int E = 0, M = 0;  // float
  int bias = 0;
  bool ieee = false;  // all-ones exponent reserved
};

// The formats the exhaustive proof covers, described from docs/spec.md 4 directly.
ReferenceFormat reference_format(const std::string& name);

uint32_t reference_encode(float d, const ReferenceFormat& f, bool truncate, bool flush);

}  // namespace depthprec::test
