// Direct3D 10+'s float-to-unorm rule for depth (D16_UNORM, D24_UNORM_S8_UINT) against the
// correctly rounded conversion the emulator stores (formats/depth_format.h, df_encode), over every
// binary32 d in [0, 1]. The rule reads: c = d * (2^n - 1); c = c + 0.5; drop the fraction; a
// result within 0.6 unit of the exact product's nearest code is conformant, and the conversion
// must not decrease. Three ways to read it are measured:
//   exact      floor(d (2^n - 1) + 1/2) in exact arithmetic (round half up)
//   product    the product rounded to binary32 first, then half up exactly
//   literal    every step in binary32: trunc(fl32(fl32(d * (2^n - 1)) + 0.5f))
// For each: the codes that differ from df_encode, the largest distance |code - d (2^n - 1)| in
// code units, how many exceed the 0.6 tolerance, and how many steps to the next binary32 lower
// the code. docs/spec.md 2 states what follows from the figures. About 25 s on one core.
//
// Usage: build/bench/d3d_unorm_rule
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <initializer_list>

#include "formats/depth_format.h"

namespace {

struct Tally {
  const char* name;
  long long differ = 0, beyond_tolerance = 0, falls = 0;
  double worst = 0;
  uint32_t prev = 0;
  void add(uint32_t code, uint32_t correct, double exact) {
    differ += code != correct;
    const double dist = std::fabs(static_cast<double>(code) - exact);
    worst = std::fmax(worst, dist);
    beyond_tolerance += dist > 0.6;
    falls += code < prev;
    prev = code;
  }
};

}  // namespace

int main() {
  for (const uint32_t bits : {16u, 24u}) {
    const df_format f = df_make_unorm(bits, DF_ROUND_NEAREST_EVEN, 0u);
    const float scale = static_cast<float>(f.max_code);
    Tally exact{"exact"}, product{"product"}, literal{"literal"};
    for (uint32_t u = 0; u <= 0x3f800000u; ++u) {
      float d;
      std::memcpy(&d, &u, 4);
      const uint32_t correct = df_encode(d, f);
      // d has 24 significant bits and max_code at most 24: the double product is exact
      const double p = static_cast<double>(d) * static_cast<double>(f.max_code);
      // p's bits span at most 48 places, so p + 1/2 is exact from p = 2^-4 on, and below that
      // floor gives 0 either way: the exact product rounded half up
      const auto half_up = static_cast<uint32_t>(std::floor(p + 0.5));
      // volatile keeps the compiler from fusing the product and the sum of the literal reading
      volatile float x = d * scale;
      const float xs = x;
      volatile float y = xs + 0.5f;
      exact.add(half_up, correct, p);
      product.add(static_cast<uint32_t>(std::floor(static_cast<double>(xs) + 0.5)), correct, p);
      literal.add(static_cast<uint32_t>(y), correct, p);
    }
    for (const Tally* t : {&exact, &product, &literal})
      std::printf(
          "unorm%-2u %-8s %10lld codes differ from correctly rounded, worst %.4f code units from "
          "d(2^n-1), %10lld beyond 0.6, %lld steps that fall\n",
          bits, t->name, t->differ, t->worst, t->beyond_tolerance, t->falls);
  }
  return 0;
}
