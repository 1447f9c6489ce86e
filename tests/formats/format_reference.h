// An independent reference for storage-format encoding, written without formats/depth_format.h:
// it rounds with the FPU (for unorm d * (2^b - 1) in binary64 up to 29 bits, in x87 long double
// beyond, whose 64-bit significand holds the 56 bits unorm32 needs; binary64 scaling by powers of
// two for floats, which is exact) instead of integer shift-and-round.
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

// reference_encode's codes for ascending inputs. Float formats by the definition of rounding
// instead of by scaling: the code whose value is nearest d (ties to the even code) or, truncating,
// the largest whose value is at most d. The walk keeps the current code and steps to the next
// while d lies beyond their midpoint (or the next code's value), each code's value exact in
// binary64 (ldexp): a comparison per input where reference_encode takes frexp, ldexp and a
// rounding. The first code is reference_encode's. unorm inputs go to reference_encode, whose
// one product and rounding is already cheap.
class ReferenceWalk {
 public:
  ReferenceWalk(const ReferenceFormat& f, bool truncate, bool flush, float first);
  // Code of d; d must be no smaller than the previous call's (or first), and in [0, 1].
  uint32_t next(float d);

 private:
  double value(uint64_t code) const;  // the code's value, exact
  bool beyond(float d) const;         // d rounds to code_ + 1 or above
  ReferenceFormat f_;
  bool truncate_, flush_;
  uint64_t code_ = 0, max_code_ = 0;
  double lo_ = 0, hi_ = 0;  // floats: the values of code_ and code_ + 1
};

}  // namespace depthprec::test
