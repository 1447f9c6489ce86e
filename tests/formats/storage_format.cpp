#include "host/model/storage_format.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <cstring>
#include <random>

#include "host/base/errors.h"
#include "tests/formats/format_reference.h"

using namespace depthprec;
using Catch::Matchers::Contains;

namespace {
float from_bits(uint32_t u) {
  float f;
  std::memcpy(&f, &u, sizeof f);
  return f;
}
}  // namespace

TEST_CASE("format names parse to the parameters of docs/spec.md 4", "[formats]") {
  const auto u24 = StorageFormat::parse("unorm24");
  CHECK(u24.bits() == 24);
  CHECK(u24.max_code() == 16777215u);
  const auto u32 = StorageFormat::parse("unorm32");
  CHECK(u32.max_code() == 0xffffffffu);
  const auto f16 = StorageFormat::parse("float16");
  CHECK(f16.bits() == 16);
  CHECK(f16.largest() == 65504.0);
  CHECK(f16.smallest_positive() == std::ldexp(1.0, -24));
  const auto f24 = StorageFormat::parse("float24");
  CHECK(f24.smallest_positive() == std::ldexp(1.0, -126 - 15));
  CHECK(f24.spacing_at(0.5) == std::ldexp(1.0, -16));
  const auto e4 = StorageFormat::parse("e4m12");
  CHECK(e4.bits() == 16);
  CHECK(e4.largest() == 0.5 * (2.0 - std::ldexp(1.0, -12)));  // every LJ code is below 1
  CHECK(e4.smallest_positive() == std::ldexp(1.0, 1 - 16 - 12));
}

TEST_CASE("bad format names say what is allowed", "[formats][errors]") {
  CHECK_THROWS_WITH(StorageFormat::parse("unorm33"), Contains("unorm takes 1 to 32 bits"));
  CHECK_THROWS_WITH(StorageFormat::parse("unorm0"), Contains("unorm takes 1 to 32 bits"));
  CHECK_THROWS_WITH(StorageFormat::parse("e0m16"), Contains("unorm16"));
  CHECK_THROWS_WITH(StorageFormat::parse("e9m60"), Contains("E = 1..8"));
  CHECK_THROWS_WITH(StorageFormat::parse("e8m30"), Contains("E + M <= 32"));
  CHECK_THROWS_WITH(StorageFormat::parse("float64"), Contains("expected unorm<b>"));
  CHECK_THROWS_AS(StorageFormat::parse("depth24"), InputError);
  CHECK_THROWS_WITH(parse_rounding("up"), Contains("nearest_even or truncate"));
}

TEST_CASE("unorm rounding: ties to even, truncation, saturation", "[formats]") {
  const auto u1 = StorageFormat::parse("unorm1");
  CHECK(u1.encode(0.5f) == 0u);  // 0.5 * 1 is a tie between 0 and 1: even is 0
  CHECK(u1.encode(0.75f) == 1u);
  const auto u2 = StorageFormat::parse("unorm2");
  CHECK(u2.encode(0.5f) == 2u);  // 1.5 ties to 2
  const auto u2t = StorageFormat::parse("unorm2", Rounding::truncate);
  CHECK(u2t.encode(0.5f) == 1u);
  CHECK(u2t.encode(0.99999994f) == 2u);
  const auto u24 = StorageFormat::parse("unorm24");
  CHECK(u24.encode(1.0f) == 16777215u);
  CHECK(u24.encode(2.0f) == 16777215u);
  CHECK(u24.encode(-0.0f) == 0u);
  CHECK(u24.encode(-1.0f) == 0u);
  CHECK(u24.encode(std::nanf("")) == 0u);
  CHECK(u24.encode(INFINITY) == 16777215u);
}

// The naive conversion fl32(d * 16777215.0f) rounds twice. This finds binary32 depths where it
// gives another code than the correctly rounded one, so "do not use it" is a proven fact here.
TEST_CASE("a binary32 product d * (2^b - 1) is wrong for unorm24 and unorm32", "[formats]") {
  for (const char* name : {"unorm24", "unorm32"}) {
    const auto f = StorageFormat::parse(name);
    const auto rf = test::reference_format(name);
    const float scale = static_cast<float>(f.max_code());
    int naive_wrong = 0;
    for (uint32_t bits = 0; bits <= 0x3f800000u; bits += 997) {
      const float d = from_bits(bits);
      const float product = d * scale;  // binary32 product, as a naive shader would
      const auto naive = static_cast<uint64_t>(std::nearbyint(static_cast<double>(product)));
      const uint32_t exact = test::reference_encode(d, rf, false, false);
      REQUIRE(f.encode(d) == exact);
      if (naive != exact) ++naive_wrong;
    }
    INFO(name);
    CHECK(naive_wrong > 1000);
  }
}

TEST_CASE("float formats: exact values, carries, saturation, flush", "[formats]") {
  const auto f16 = StorageFormat::parse("float16");
  CHECK(f16.encode(1.0f) == 0x3c00u);
  CHECK(f16.encode(0.5f) == 0x3800u);
  CHECK(f16.encode(1e9f) == 0x7bffu);               // saturates below infinity
  CHECK(f16.encode(std::ldexp(1.0f, -20)) == 16u);  // subnormal in float16
  CHECK(f16.encode(std::ldexp(1.0f, -25)) == 0u);   // half the smallest: tie to 0
  CHECK(f16.encode(std::ldexp(1.5f, -25)) == 1u);   // above half: rounds up
  const auto f16t = StorageFormat::parse("float16", Rounding::truncate);
  CHECK(f16t.encode(std::ldexp(1.5f, -25)) == 0u);
  const auto f16z = StorageFormat::parse("float16", Rounding::nearest_even, Denormals::flush);
  CHECK(f16z.encode(std::ldexp(1.0f, -20)) == 0u);
  CHECK(f16z.encode(std::ldexp(1.0f, -14)) == 0x0400u);  // smallest normal survives
  // 1 - 2^-24 rounds up across the binade boundary to exactly 1.0 in float16
  CHECK(f16.encode(1.0f - std::ldexp(1.0f, -24)) == 0x3c00u);
  const auto e4 = StorageFormat::parse("e4m12");
  CHECK(e4.encode(1.0f) == 0xffffu);  // 1 is above every LJ code
  CHECK(e4.encode(0.25f) == (14u << 12));
  const auto f32 = StorageFormat::parse("float32");
  for (float d : {0.0f, 1e-40f, 1e-30f, 0.3f, 0.999999f, 1.0f}) {
    uint32_t bits;
    std::memcpy(&bits, &d, sizeof bits);
    CHECK(f32.encode(d) == bits);  // float32 stores the binary32 depth unchanged
    CHECK(f32.decode(f32.encode(d)) == static_cast<double>(d));
  }
}

TEST_CASE("e1m<M> is the fixed-point format with 2^(M+1) uniform codes", "[formats]") {
  const auto e1 = StorageFormat::parse("e1m15");
  for (uint32_t c : {0u, 1u, 777u, 32768u, 65535u})
    CHECK(e1.decode(c) == std::ldexp(static_cast<double>(c), -16));
}

TEST_CASE("code_floor agrees with truncating encode and brackets binary64 values", "[formats]") {
  std::mt19937 rng(7);
  for (const char* name :
       {"unorm16", "unorm24", "unorm32", "float24", "float16", "e4m12", "e2m5"}) {
    const auto f = StorageFormat::parse(name, Rounding::truncate);
    for (int i = 0; i < 20000; ++i) {
      const float d = from_bits(rng() % 0x3f800001u);
      REQUIRE(f.code_floor(d) == f.encode(d));
      const double v = std::ldexp(static_cast<double>(rng()) + 0.5, -32) * 0.999;
      const uint32_t c = f.code_floor(v);
      REQUIRE(f.decode(c) <= v);
      if (c < f.max_code()) REQUIRE(f.decode(c + 1) > v);
    }
  }
}

TEST_CASE("defines describe the format for a kernel", "[formats]") {
  CHECK(StorageFormat::parse("unorm24").defines() ==
        "-DDF_KIND=0 -DDF_BITS=24u -DDF_ROUNDING=0u -DDF_FLUSH=0u -DDF_CONVERT=0u");
  CHECK(
      StorageFormat::parse("unorm16", Rounding::nearest_even, Denormals::keep, Conversion::llvmpipe)
          .defines() == "-DDF_KIND=0 -DDF_BITS=16u -DDF_ROUNDING=0u -DDF_FLUSH=0u -DDF_CONVERT=1u");
  CHECK_THROWS_AS(StorageFormat::parse("unorm20", Rounding::nearest_even, Denormals::keep,
                                       Conversion::llvmpipe),
                  InputError);
  CHECK(StorageFormat::parse("e4m12", Rounding::truncate, Denormals::flush).defines() ==
        "-DDF_KIND=1 -DDF_E=4 -DDF_M=12 -DDF_IEEE=0u -DDF_ROUNDING=1u -DDF_FLUSH=1u");
}

TEST_CASE("binary64 encode: the binary32 codes for binary32 inputs, correctly rounded otherwise",
          "[formats]") {
  std::mt19937_64 rng(20261121);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (const char* name : {"unorm1", "unorm16", "unorm24", "unorm32", "float32", "float24",
                           "float16", "e4m12", "e2m5", "e8m24"}) {
    for (const Rounding r : {Rounding::nearest_even, Rounding::truncate}) {
      for (const Denormals dn : {Denormals::keep, Denormals::flush}) {
        const auto f = StorageFormat::parse(name, r, dn);
        INFO(name << (r == Rounding::truncate ? " truncate" : " nearest")
                  << (dn == Denormals::flush ? " flush" : ""));
        int bad32 = 0, bad64 = 0;
        for (int i = 0; i < 20000; ++i) {
          // spread over the binades, down into binary32's subnormals
          const double d = std::ldexp(unit(rng), -static_cast<int>(rng() % 140));
          const float d32 = static_cast<float>(d);
          if (f.encode64(static_cast<double>(d32)) != f.encode(d32)) ++bad32;
          // d lies between the values of its code and the next code, and on the rounding's side
          const uint32_t c = f.encode64(d);
          const double lo = f.decode(c);
          if (f.is_unorm()) {
            // exact reference: round(d * max) in 128-bit integers, d = m * 2^-k
            int e = 0;
            const double fr = std::frexp(d, &e);
            const auto m = static_cast<unsigned __int128>(std::ldexp(fr, 53));
            const int shift = 53 - e;  // d = m / 2^shift
            const unsigned __int128 p = m * f.max_code();
            unsigned __int128 q = shift >= 127 ? 0 : p >> shift;
            if (r == Rounding::nearest_even && shift < 127) {
              const unsigned __int128 rem = p - (q << shift),
                                      half = static_cast<unsigned __int128>(1) << (shift - 1);
              if (rem > half || (rem == half && (q & 1))) ++q;
            }
            if (c != static_cast<uint32_t>(q)) ++bad64;
          } else if (c < f.max_code() && !(dn == Denormals::flush && c == 0)) {
            const double hi = f.decode(c + 1);
            const bool inside = lo <= d && d < hi;
            const bool nearer =
                r == Rounding::truncate || (d - lo < hi - d || (d - lo == hi - d && (c & 1u) == 0));
            const bool carried = r == Rounding::nearest_even && c > 0 && f.decode(c - 1) < d &&
                                 d < lo && lo - d <= d - f.decode(c - 1);
            if (!((inside && nearer) || carried)) ++bad64;
          }
        }
        CHECK(bad32 == 0);
        CHECK(bad64 == 0);
      }
    }
  }
}

TEST_CASE(
    "softpipe's unorm conversion is its C expression: a truncated binary32 or binary64 product",
    "[formats]") {
  // formats/depth_format.h computes unorm32's binary64 product in integers; here, as softpipe
  // writes it (sp_quad_depth_test.c), for every 61st binary32 in (0, 1) and the last ones
  const auto u16 = StorageFormat::parse("unorm16", Rounding::nearest_even, Denormals::keep,
                                        Conversion::softpipe);
  const auto u24 = StorageFormat::parse("unorm24", Rounding::nearest_even, Denormals::keep,
                                        Conversion::softpipe);
  const auto u32 = StorageFormat::parse("unorm32", Rounding::nearest_even, Denormals::keep,
                                        Conversion::softpipe);
  uint64_t bad = 0, checked = 0;
  const auto check = [&](uint32_t u) {
    const float d = from_bits(u);
    bad += u16.encode(d) != static_cast<uint32_t>(d * 65535.0f);
    bad += u24.encode(d) != static_cast<uint32_t>(d * 16777215.0f);
    bad += u32.encode(d) != static_cast<uint32_t>(static_cast<double>(d) * 4294967295.0);
    ++checked;
  };
  for (uint32_t u = 1; u < 0x3f800000u; u += 61) check(u);
  for (uint32_t u = 0x3f800000u - 4096; u < 0x3f800000u; ++u) check(u);
  INFO(checked << " depths");
  CHECK(bad == 0);
  // and it differs from the correctly rounded code where the product's fraction is a half or more
  CHECK(u24.encode(0.5f) == 8388607u);
  CHECK(StorageFormat::parse("unorm24").encode(0.5f) == 8388608u);
  CHECK(u16.encode(0.5f) == 32767u);
  CHECK(StorageFormat::parse("unorm16").encode(0.5f) == 32768u);
}

TEST_CASE(
    "from df_order_exact_from on, codes follow binary32 order: a depth test needs no encoding",
    "[formats]") {
  // Every binary32 from T's predecessor to 1: codes strictly increasing. With d >= T > d', that
  // puts code(d') <= code(pred T) < code(T) <= code(d); with both >= T, order is kept exactly.
  // One step lower (T's predecessor itself as T) must fail: T is the least such pattern.
  int with_region = 0;
  for (const char* name : {"unorm16", "unorm24", "unorm32", "float32", "float16", "e4m12"}) {
    for (const Rounding r :
         {Rounding::nearest_even, Rounding::truncate, Rounding(-1), Rounding(-2)}) {
      // Rounding(-1), (-2): llvmpipe's and softpipe's conversions where the format has them
      const int driver = -static_cast<int>(r);
      if (driver > 0 && std::string(name).rfind("unorm", 0) != 0) continue;
      const auto f = driver > 0 ? StorageFormat::parse(
                                      name, Rounding::nearest_even, Denormals::keep,
                                      driver == 1 ? Conversion::llvmpipe : Conversion::softpipe)
                                : StorageFormat::parse(name, r);
      const uint32_t from = df_order_exact_from(f.spec());
      INFO(name << (r == Rounding::truncate ? " truncate" : " nearest") << " from " << from);
      if (from > 0x3f800000u) continue;
      ++with_region;
      uint32_t bad = 0;
      for (uint32_t u = from - 1; u < 0x3f800000u; ++u)
        if (f.encode(from_bits(u + 1)) <= f.encode(from_bits(u))) ++bad;
      CHECK(bad == 0);
      CHECK(f.encode(from_bits(from - 1)) == f.encode(from_bits(from - 2)));
    }
  }
  CHECK(with_region == 4);  // unorm24: both roundings, llvmpipe's and softpipe's conversions
}
