#include "tests/formats/format_reference.h"

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

namespace {

// The largest exponent field of a float format: IEEE style reserves the all-ones one.
int top_field(const ReferenceFormat& f) {
  return f.ieee ? (1 << f.E) - 2 : (1 << f.E) - 1;
}

uint64_t float_max_code(const ReferenceFormat& f) {
  return (static_cast<uint64_t>(top_field(f)) << f.M) + ((uint64_t{1} << f.M) - 1);
}

}  // namespace

uint32_t reference_encode(float d, const ReferenceFormat& f, bool truncate, bool flush) {
  if (!(d > 0.0f)) return 0;  // 0, negatives, NaN
  if (f.unorm) return reference_unorm(d, f.bits, truncate);
  const uint64_t one = uint64_t{1} << f.M;
  const uint64_t max_code = float_max_code(f);
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
    code = field > top_field(f) ? max_code : (static_cast<uint64_t>(field) << f.M) + (mant - one);
  }
  if (code > max_code) code = max_code;
  if (flush && code < one) code = 0;
  return static_cast<uint32_t>(code);
}

ReferenceWalk::ReferenceWalk(const ReferenceFormat& f, bool truncate, bool flush, float first)
    : f_(f), truncate_(truncate), flush_(flush) {
  if (f.unorm) return;  // next() rounds each input directly
  max_code_ = float_max_code(f);
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

void ReferenceWalk::step() {
  ++code_;
  lo_ = hi_;
  hi_ = code_ < max_code_ ? value(code_ + 1) : INFINITY;
}

}  // namespace depthprec::test
