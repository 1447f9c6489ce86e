// An independent reference for storage-format encoding, written without formats/depth_format.h:
// it rounds with the FPU (for unorm d * (2^b - 1) in binary64 up to 29 bits, in x87 long double
// beyond, whose 64-bit significand holds the 56 bits unorm32 needs; binary64 scaling by powers of
// two for floats, which is exact) instead of integer shift-and-round.
#pragma once

#include <cmath>
#include <cstdint>
#include <cstring>
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

// unorm's codes of the binary32 values with bit patterns first, first + 1, ... (n of them, none
// negative or NaN) for bits <= 29, in a loop the compiler vectorizes: d (2^b - 1) is exact in
// binary64 (a 24-bit significand times a b-bit integer), and adding 2^52 rounds it to an integer,
// ties to even in the FPU's current mode (what std::rint compiles to; exact below 2^52, and from
// there the code is the largest anyway). Truncation of x >= 0 is that stepped back where it
// rounded up. The exhaustive proof takes them a block at a time, reference_unorm one by one.
inline void reference_unorm_codes(uint32_t first, uint32_t n, int bits, bool truncate,
                                  uint32_t* out) {
  const double max = static_cast<double>((uint64_t{1} << bits) - 1);
  for (uint32_t i = 0; i < n; ++i) {
    const uint32_t u = first + i;
    float d;
    std::memcpy(&d, &u, sizeof d);
    const double x = static_cast<double>(d) * max;
    double r = (x + 0x1.0p52) - 0x1.0p52;
    if (truncate && r > x) r -= 1;
    out[i] = r >= max ? static_cast<uint32_t>(max)
                      : static_cast<uint32_t>(static_cast<int32_t>(r));  // r < 2^29
  }
}

// reference_encode of a unorm<bits> format. Inline, as the walk's next() is: the exhaustive
// proof calls it once per binary32 in [0, 1] for unorm32, where a call's overhead was the most of
// its cost. unorm32's product has 56 bits, which x87 long double's 64 hold; rint there, and
// truncation as above (std::trunc, and a cast from long double, would switch the x87 control word
// twice per input); the integer below 2^32 then converts exactly.
inline uint32_t reference_unorm(float d, int bits, bool truncate) {
  if (!(d > 0.0f)) return 0;  // 0, negatives, NaN
  if (bits <= 29) {
    uint32_t u, code;
    std::memcpy(&u, &d, sizeof u);
    reference_unorm_codes(u, 1, bits, truncate, &code);
    return code;
  }
  const uint64_t max = (uint64_t{1} << bits) - 1;
  const long double x = static_cast<long double>(d) * static_cast<long double>(max);
  long double r = std::rint(x);
  if (truncate && r > x) r -= 1;
  if (r >= static_cast<long double>(max)) return static_cast<uint32_t>(max);
  return static_cast<uint32_t>(static_cast<double>(r));
}

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
  uint32_t next(float d) {
    if (f_.unorm) return reference_unorm(d, f_.bits, truncate_);
    while (beyond(d)) step();
    return static_cast<uint32_t>(flush_ && code_ < (uint64_t{1} << f_.M) ? 0 : code_);
  }

 private:
  double value(uint64_t code) const;  // the code's value, exact
  void step();                        // to code_ + 1
  // d rounds to code_ + 1 or above
  bool beyond(float d) const {
    if (code_ >= max_code_) return false;
    const bool next_even = ((code_ + 1) & 1) == 0;
    const double v = static_cast<double>(d);
    if (truncate_) return v >= hi_;
    const double mid = lo_ + (hi_ - lo_) / 2;  // exact: one bit below the finer spacing
    return v > mid || (v == mid && next_even);
  }
  ReferenceFormat f_;
  bool truncate_, flush_;
  uint64_t code_ = 0, max_code_ = 0;
  double lo_ = 0, hi_ = 0;  // floats: the values of code_ and code_ + 1
};

}  // namespace depthprec::test
