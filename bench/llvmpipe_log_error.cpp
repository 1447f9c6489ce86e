// The error bounds the code bounds assume for llvmpipe's log and log2 (pipeline.log = llvmpipe,
// kernels/mts/bounds.cl frag_err) and the monotonicity LOG_CODE_SLACK relies on, measured over
// every binary32 x >= 1 (the shaders' argument: k w + 1 for Gilg's log, 1 + w and (w - n) + 1 for
// the engines' log2): the largest distance from the exact value in ulps of it, and how many steps
// to the next binary32 make the result fall. About 70 s on one core.
//
// Usage: build/bench/llvmpipe_log_error
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>

#include "formats/df_prelude.h"
#include "interface/llvmpipe_log.h"

DP_LLVMPIPE_LOG_DEFINE(llvmpipe_log2, llvmpipe_log, float, df_float_bits, df_bits_float,
                       static_cast<float>, std::fma)

namespace {

template <class Approx, class Exact>
void measure(const char* name, Approx approx, Exact exact_of) {
  double worst = 0;
  float worst_x = 0, prev = -1;
  long long n = 0, falls = 0;
  for (uint32_t bits = 0x3f800000u; bits < 0x7f800000u; ++bits) {
    float x;
    std::memcpy(&x, &bits, 4);
    const float r = approx(x);
    const double exact = exact_of(static_cast<double>(x));
    const double ulp = std::ldexp(1.0, std::ilogb(static_cast<float>(exact)) - 23);
    const double e = std::fabs(r - exact) / ulp;
    if (e > worst) {
      worst = e;
      worst_x = x;
    }
    falls += r < prev;
    prev = r;
    ++n;
  }
  std::printf("%s: %lld binary32 x >= 1: worst %.3f ulp (at x = %a), %lld steps that fall\n", name,
              n, worst, static_cast<double>(worst_x), falls);
}

}  // namespace

int main() {
  measure("log", llvmpipe_log, [](double x) { return std::log(x); });
  measure("log2", llvmpipe_log2, [](double x) { return std::log2(x); });
  return 0;
}
