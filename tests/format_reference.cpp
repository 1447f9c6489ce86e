#include "format_reference.h"

#include <cfenv>
#include <cmath>
#include <stdexcept>

namespace depthprec::test {

ReferenceFormat reference_format(const std::string& name) {
  if (name == "unorm16") return {name, true, 16, 0, 0, 0, false};
  if (name == "unorm24") return {name, true, 24, 0, 0, 0, false};
  if (name == "unorm32") return {name, true, 32, 0, 0, 0, false};
  if (name == "float32") return {name, false, 32, 8, 23, 127, true};
  if (name == "float24") return {name, false, 24, 8, 15, 127, true};
  if (name == "float16") return {name, false, 16, 5, 10, 15, true};
  if (name == "e4m12") return {name, false, 16, 4, 12, 16, false};
  if (name == "e3m13") return {name, false, 16, 3, 13, 8, false};
  throw std::invalid_argument("no reference description for " + name);
}

uint32_t reference_encode(float d, const ReferenceFormat& f, bool truncate, bool flush) {
  if (!(d > 0.0f)) return 0;  // 0, negatives, NaN
  if (f.unorm && f.bits <= 29) {
    // d (2^b - 1): a 24-bit significand times a b-bit integer, exact in binary64's 53 bits
    const uint64_t max = (uint64_t{1} << f.bits) - 1;
    const double x = static_cast<double>(d) * static_cast<double>(max);
    double r = std::rint(x);  // ties to even, in SSE (the library's rint)
    if (truncate && r > x) r -= 1.0;
    return static_cast<uint32_t>(r >= static_cast<double>(max) ? max : r);
  }
  if (f.unorm) {
    const uint64_t max = (uint64_t{1} << f.bits) - 1;
    const long double x = static_cast<long double>(d) * static_cast<long double>(max);
    // rint rounds ties to even in the FPU's current mode; truncation of x >= 0 is rint stepped
    // back where it rounded up (std::trunc would switch the x87 control word twice per input).
    long double r = std::rint(x);
    if (truncate && r > x) r -= 1.0L;
    if (r >= static_cast<long double>(max)) return static_cast<uint32_t>(max);
    // r is an integer below 2^32, so binary64 holds it and the SSE conversion is exact (a cast
    // from long double would switch the control word as well).
    return static_cast<uint32_t>(static_cast<double>(r));
  }
  const uint64_t one = uint64_t{1} << f.M;
  const int top_field = f.ieee ? (1 << f.E) - 2 : (1 << f.E) - 1;
  const uint64_t max_code = (static_cast<uint64_t>(top_field) << f.M) + (one - 1);
  int e = 0;
  std::frexp(static_cast<double>(d), &e);
  int p = e - 1;
  const bool subnormal = p < 1 - f.bias;
  int qp = subnormal ? 1 - f.bias : p;
  double n = std::ldexp(static_cast<double>(d), f.M - qp);  // exact: a power-of-two scaling
  n = truncate ? std::trunc(n) : std::rint(n);              // rint: ties to even
  auto mant = static_cast<uint64_t>(n);
  uint64_t code;
  if (subnormal) {
    code = mant;  // mant == 2^M is the smallest normal, code 2^M
  } else {
    if (mant == 2 * one) {  // rounding carried into the next binade
      mant = one;
      qp += 1;
    }
    const int field = qp + f.bias;
    code = field > top_field ? max_code : (static_cast<uint64_t>(field) << f.M) + (mant - one);
  }
  if (code > max_code) code = max_code;
  if (flush && code < one) code = 0;
  return static_cast<uint32_t>(code);
}

ReferenceWalk::ReferenceWalk(const ReferenceFormat& f, bool truncate, bool flush, float first)
    : f_(f), truncate_(truncate), flush_(flush) {
  if (f.unorm) return;  // next() rounds each input directly
  const int top_field = f.ieee ? (1 << f.E) - 2 : (1 << f.E) - 1;
  max_code_ = (static_cast<uint64_t>(top_field) << f.M) + ((uint64_t{1} << f.M) - 1);
  code_ = reference_encode(first, f, truncate, false);
  lo_ = value(code_);
  hi_ = code_ < max_code_ ? value(code_ + 1) : INFINITY;
}

double ReferenceWalk::value(uint64_t code) const {
  const uint64_t field = code >> f_.M, mant = code & ((uint64_t{1} << f_.M) - 1);
  if (field == 0) return std::ldexp(static_cast<double>(mant), 1 - f_.bias - f_.M);
  return std::ldexp(static_cast<double>(mant + (uint64_t{1} << f_.M)),
                    static_cast<int>(field) - f_.bias - f_.M);
}

bool ReferenceWalk::beyond(float d) const {
  if (code_ >= max_code_) return false;
  const bool next_even = ((code_ + 1) & 1) == 0;
  const double v = static_cast<double>(d);
  if (truncate_) return v >= hi_;
  const double mid = lo_ + (hi_ - lo_) / 2;  // exact: one bit below the finer spacing
  return v > mid || (v == mid && next_even);
}

uint32_t ReferenceWalk::next(float d) {
  if (f_.unorm) return reference_encode(d, f_, truncate_, flush_);
  while (beyond(d)) {
    ++code_;
    lo_ = hi_;
    hi_ = code_ < max_code_ ? value(code_ + 1) : INFINITY;
  }
  return static_cast<uint32_t>(flush_ && code_ < (uint64_t{1} << f_.M) ? 0 : code_);
}

}  // namespace depthprec::test
