// The error bound the code bounds assume for llvmpipe's log (pipeline.log = llvmpipe,
// kernels/mts/bounds.cl frag_err) and the monotonicity LOG_CODE_SLACK relies on, measured over
// every binary32 x >= 1 (the shaders' argument k w + 1): the largest distance from ln x in ulps of
// ln x, and how many steps to the next binary32 make the result fall. About 35 s on one core.
//
// Usage: build/bench/llvmpipe_log_error
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>

#include "formats/df_prelude.h"
#include "interface/llvmpipe_log.h"

DP_LLVMPIPE_LOG_DEFINE(llvmpipe_log, float, df_float_bits, df_bits_float, static_cast<float>,
                       std::fma)

int main() {
  double worst = 0;
  float worst_x = 0, prev = -1;
  long long n = 0, falls = 0;
  for (uint32_t bits = 0x3f800000u; bits < 0x7f800000u; ++bits) {
    float x;
    std::memcpy(&x, &bits, 4);
    const float r = llvmpipe_log(x);
    const double exact = std::log(static_cast<double>(x));
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
  std::printf("%lld binary32 x >= 1: worst %.3f ulp of ln x (at x = %a), %lld steps that fall\n", n,
              worst, static_cast<double>(worst_x), falls);
  return 0;
}
