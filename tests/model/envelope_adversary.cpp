// An envelope's adversary (interface/adversary.h) against exact arithmetic, by brute force: each
// choice lies within the tolerance its specification allows, on the side that helps the farther
// plane, and as far to that side as the tolerance lets it. The exact values are x87 extended
// products: w r (24 + 24 bits), d (2^b - 1) (24 + 32) and the difference of two nearby binary32
// values all fit its 64-bit significand.
#include <catch2/catch.hpp>
#include <cmath>
#include <random>

#include "host/model/bound_model.h"
#include "host/model/storage_format.h"
#include "interface/adversary.h"

using namespace depthprec;

namespace {

DP_ADV_RECIPROCAL_DEFINE(adv_test_reciprocal, std::fma, std::nextafter)

// A binary32 of random significand and an exponent in [lo, hi], either sign when `signs`.
float adv_random_float(std::mt19937_64& rng, int lo, int hi, bool signs) {
  std::uniform_int_distribution<int> e(lo, hi);
  std::uniform_real_distribution<float> m(1.0f, 2.0f);
  const float v = std::ldexp(m(rng), e(rng));
  return signs && (rng() & 1) ? -v : v;
}

}  // namespace

TEST_CASE("the adversary's reciprocal is 1/w's faithful rounding on the side it asks for",
          "[envelope][adversary]") {
  std::mt19937_64 rng(20261128);
  long moved = 0;
  for (int i = 0; i < 4000000; ++i) {
    const float w = adv_random_float(rng, -60, 60, true);
    const float r0 = 1.0f / w;
    const bool up = rng() & 1;
    const float r = adv_test_reciprocal(w, r0, up);
    // r w against 1, exactly: r >= 1/w where w > 0 and r w >= 1, or w < 0 and r w <= 1
    const long double rw = static_cast<long double>(r) * w;
    const bool at_or_above = w > 0 ? rw >= 1.0L : rw <= 1.0L;
    const bool at_or_below = w > 0 ? rw <= 1.0L : rw >= 1.0L;
    // one of the two binary32 values around 1/w: its neighbour towards 1/w lies on the other
    // side (or r is 1/w itself), so r is within 1 ulp of 1/w (D3D 11.3 3.1.3)
    const float back = std::nextafter(r, up ? -INFINITY : INFINITY);
    const long double bw = static_cast<long double>(back) * w;
    const bool adjacent =
        rw == 1.0L || (up ? (w > 0 ? bw < 1.0L : bw > 1.0L) : (w > 0 ? bw > 1.0L : bw < 1.0L));
    if (!(up ? at_or_above : at_or_below) || !adjacent) {
      INFO("w = " << w << " r0 = " << r0 << " r = " << r << " up " << up);
      REQUIRE((up ? at_or_above : at_or_below));
      REQUIRE(adjacent);
    }
    moved += r != r0;
  }
  // half the requests ask for the side the correct rounding is not on
  CHECK(moved > 1800000);
  CHECK(adv_test_reciprocal(0.0f, INFINITY, false) == INFINITY);
  CHECK(adv_test_reciprocal(4.0f, 0.25f, true) == 0.25f);  // exact: nothing to choose
}

TEST_CASE("the adversary's unorm codes lie within the envelope's tolerance, at its far edge",
          "[envelope][adversary]") {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  for (const std::string envelope : {"d3d11", "vulkan_min"}) {
    const BoundModel& m = bound_model(envelope);
    const double t = m.adversary_conversion, slack = adversary_code_slack(m);
    for (const std::string format : {"unorm16", "unorm24", "unorm32"}) {
      const df_format f = StorageFormat::parse(format).spec();
      INFO(envelope << " " << format);
      for (int i = 0; i < 1000000; ++i) {
        // uniform in [0, 1), and a fifth from the small binades where x has fraction bits
        const float d = i % 5 ? unit(rng) : adv_random_float(rng, -30, -1, false);
        const long double x = static_cast<long double>(d) * f.max_code;
        for (const bool up : {true, false}) {
          const df_u32 c = dp_adv_unorm_code(d, f, up, slack);
          const long double off = static_cast<long double>(c) - x;
          const long double beyond = up ? off + 1 : off - 1;  // the next code on its side
          // Vulkan: one of the two nearest codes, the one on its side; D3D 11.3 3.2.3.6: within
          // 0.6 ulp, never behind the nearest code, and the next code beyond out of the
          // tolerance (to within the 2^-20 hair)
          const bool ok = t >= 1 ? c == static_cast<df_u32>(up ? std::ceil(x) : std::floor(x))
                                 : std::fabs(static_cast<double>(off)) <= t &&
                                       (up ? off >= -0.5L : off <= 0.5L) &&
                                       std::fabs(static_cast<double>(beyond)) > t - 0x1p-19;
          if (!ok) {
            INFO("d = " << d << " up " << up << " code " << c << " x " << static_cast<double>(x));
            REQUIRE(ok);
          }
        }
      }
      CHECK(dp_adv_unorm_code(0.0f, f, true, slack) == 0u);
      CHECK(dp_adv_unorm_code(1.0f, f, false, slack) == f.max_code);
      CHECK(dp_adv_unorm_code(NAN, f, true, slack) == 0u);
    }
  }
}

TEST_CASE("the adversary's interpolation shift stays within 1 part in 10^5 of every value",
          "[envelope][adversary]") {
  std::mt19937_64 rng(11);
  const double tol = static_cast<float>(bound_model("vulkan_min").interpolation_relative);
  long full = 0;
  const int n = 2000000;
  for (int i = 0; i < n; ++i) {
    const bool negative = rng() & 1;  // 1/w's planes are positive; a depth plane may not be
    float v[3];
    for (float& x : v) x = (negative ? -1 : 1) * adv_random_float(rng, -20, 3, false);
    const float c0 = adv_random_float(rng, -20, 6, true);
    const int sign = rng() & 1 ? 1 : -1;
    const float c = dp_adv_shift_plane(c0, v[0], v[1], v[2], tol, sign);
    const long double applied = static_cast<long double>(c) - c0;
    const long double allowed =
        tol * std::fmin(std::fabs(v[0]), std::fmin(std::fabs(v[1]), std::fabs(v[2])));
    // on its side, within the tolerance, and as much of it as binary32 holds: within one ulp of
    // c of the full shift
    const long double ulp = std::nextafter(std::fabs(c), INFINITY) - std::fabs(c);
    const long double size = std::fabs(applied);
    const bool ok = applied * sign >= 0 && size <= allowed && size >= allowed - ulp;
    if (!ok) {
      INFO("c0 = " << c0 << " c = " << c << " sign " << sign);
      REQUIRE(ok);
    }
    full += applied != 0;
  }
  CHECK(full > n / 3);
  // values of both signs: no magnitude bounds the triangle away from 0, so nothing moves
  CHECK(dp_adv_shift_plane(0.5f, 1.0f, -1.0f, 2.0f, tol, 1) == 0.5f);
}
