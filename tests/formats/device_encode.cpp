// The OpenCL build of formats/depth_format.h must agree bit for bit with the host build, for every
// format family, both rounding modes and both denormal modes (sampled here; the exhaustive proof
// in exhaustive_formats.cpp covers the main formats on every input).
#include "host/runtime/device_encode.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <cstring>
#include <random>

#include "host/model/storage_format.h"
#include "host/runtime/opencl_runtime.h"
#include "tests/support/mts_fixture.h"

using namespace depthprec;

using depthprec::test::runtime;

namespace {

// 2^16 consecutive binary32 inputs from bit pattern first: the 16-lane encoder of the MTS kernel
// agrees with the scalar one on each (device_encode_range), and both with the host's.
void check_range(const StorageFormat& f, uint32_t first) {
  std::vector<uint32_t> dev;
  REQUIRE(device_encode_range(runtime(), f, first, 1u << 16, dev) == 0);
  for (uint32_t i = 0; i < dev.size(); ++i) {
    float d;
    const uint32_t bits = first + i;
    std::memcpy(&d, &bits, sizeof d);
    INFO("bits " << bits);
    REQUIRE(dev[i] == f.encode(d));
  }
}

}  // namespace

TEST_CASE("device and host encoders agree on sampled inputs", "[formats][device]") {
  // scalar and 16-lane device encoders, host encoder: one answer for every format family
  std::mt19937 rng(2021);
  std::vector<std::string> names = {"unorm1",  "unorm7",  "unorm16", "unorm24", "unorm31",
                                    "unorm32", "float16", "float24", "float32", "e1m15",
                                    "e2m5",    "e4m12",   "e8m23",   "e5m0",    "e3m29"};
  for (const auto& name : names) {
    for (const Rounding r : {Rounding::nearest_even, Rounding::truncate}) {
      for (const Denormals dn : {Denormals::keep, Denormals::flush}) {
        const auto f = StorageFormat::parse(name, r, dn);
        INFO(name << " " << to_string(r) << " " << to_string(dn));
        check_range(f, rng() % 0x3f000000u);
      }
    }
  }
}

TEST_CASE("device and host encoders agree under the drivers' unorm conversions",
          "[formats][device]") {
  // llvmpipe's and softpipe's binary32 (and, for softpipe's unorm32, binary64) conversions: the
  // 16-lane encoder, the scalar one and the host's, over 2^16 consecutive inputs in each binade
  // from 2^-8 to 1
  for (const Conversion c : {Conversion::llvmpipe, Conversion::softpipe})
    for (const char* name : {"unorm16", "unorm24", "unorm32"}) {
      const auto f = StorageFormat::parse(name, Rounding::nearest_even, Denormals::keep, c);
      INFO(name << " " << to_string(c));
      for (uint32_t first = 0x3b800000u; first < 0x3f800000u; first += 0x00800000u)
        check_range(f, first);
    }
}

TEST_CASE("device encoder handles values outside 0..1 like the host", "[formats][device]") {
  const std::vector<float> specials = {-1.0f,    -0.0f,     0.0f, 1.0f,   1.5f,       3e38f,
                                       INFINITY, -INFINITY, NAN,  1e-45f, 0.99999994f};
  for (const char* name : {"unorm24", "unorm32", "float32", "float16", "e4m12"}) {
    const auto f = StorageFormat::parse(name);
    const auto dev = device_encode(runtime(), f, specials);
    for (const uint32_t first : {0x7f7ffff8u, 0x7f800000u - 8u, 0xff7ffff8u, 0x3f7ffff8u,
                                 0x7fc00000u - 4u, 0x80000000u /* -0 and negative denormals */}) {
      std::vector<uint32_t> block;
      INFO(name << " block from " << first);
      CHECK(device_encode_range(runtime(), f, first, 16, block) == 0);
    }
    for (size_t i = 0; i < specials.size(); ++i) {
      INFO(name << " value " << specials[i]);
      CHECK(dev[i] == f.encode(specials[i]));
    }
  }
}

TEST_CASE("float16 nearest-even matches the compiler's _Float16 conversion", "[formats]") {
  const auto f = StorageFormat::parse("float16");
  for (uint32_t bits = 0; bits <= 0x3f800000u; bits += 4093) {
    float d;
    std::memcpy(&d, &bits, sizeof d);
    const _Float16 h = static_cast<_Float16>(d);
    uint16_t hb;
    std::memcpy(&hb, &h, sizeof hb);
    INFO("bits " << bits);
    REQUIRE(f.encode(d) == hb);
  }
}
