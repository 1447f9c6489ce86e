// Reading eye distance back from the stored depth (host/analysis/readback.h) against binary64
// references written out here, at points whose expectations can be checked by hand.
#include "host/analysis/readback.h"

#include <catch2/catch.hpp>
#include <cmath>

#include "host/model/resolve.h"

using namespace depthprec;
using Catch::Matchers::WithinRel;

namespace {

ReadbackRow readback_row(const Scene& scene, Technique t, const char* format, DepthRange range,
                         double w, Inverse inverse) {
  for (const ReadbackRow& r : readback(scene, {t, format, range}, w))
    if (r.inverse == inverse) return r;
  FAIL("no " << to_string(inverse) << " row for " << info(t).name);
  return {};
}

// The spacing of binary32 at x (x > 0).
double ulp32(double x) {
  return std::nextafter(static_cast<float>(x), INFINITY) - static_cast<float>(x);
}

}  // namespace

TEST_CASE("readback: standard unorm24 at 5000 of 0.1..1e4 loses a code's half to storage",
          "[readback]") {
  const Scene scene = load_scene("", {"near=0.1", "far=10000"});
  const double n = 0.1, f = 1e4, w = 5000;
  // Binary64 by hand: D(w) = f (w - n) / ((f - n) w), its nearest of the 2^24 - 1 steps, and the
  // distance that code's value stands for, n f / (f - (f - n) d).
  const double D = f * (w - n) / ((f - n) * w);
  const double code = std::nearbyint(D * 16777215.0);
  const double d = code / 16777215.0;
  const double w_code = n * f / (f - (f - n) * d);
  const ReadbackRow r =
      readback_row(scene, Technique::standard, "unorm24", DepthRange::gl, w, Inverse::threejs);
  CHECK(r.code == static_cast<uint32_t>(code));
  CHECK_THAT(r.storage_error(), WithinRel(w_code - w, 1e-6));
  // One code spans 14.9 m here (resolve); the code of the exact depth stands for a distance
  // within half of that, here 3.37 m nearer.
  CHECK_THAT(r.code_gap, WithinRel(14.9, 0.01));
  const double width =
      code_interval_width({Technique::standard, n, f, {}}, scene.storage_format(r.pair), w);
  CHECK(std::fabs(r.storage_error()) <= 0.5 * width);
  CHECK(std::fabs(r.storage_error()) > 0.2 * width);
  // three.js's binary32 ( near * far ) / ( ( far - near ) * d - far ): d read as binary32 is within
  // 2^-25 of the code's value (its spacing below 1 is the code's), and (f - n) d rounds by up to
  // 2^-11 (half of binary32's spacing at 10^4); both move the denominator n f / w = 0.2 by
  // 3e-4 and 4.9e-4, that is w by 7.5 and 12.2 m at most: the inverse adds up to about 1.3 codes.
  CHECK(std::fabs(r.arithmetic_error()) <= 20);
  CHECK_THAT(r.read, WithinRel(n * f / (f - (f - n) * static_cast<double>(r.depth)), 13.0 / w));
  // Godot's inverse projection reads the same code through P's binary32 entries
  const ReadbackRow g =
      readback_row(scene, Technique::standard, "unorm24", DepthRange::gl, w, Inverse::godot);
  CHECK(g.code == r.code);
  CHECK(g.storage_error() == r.storage_error());
  CHECK(std::fabs(g.arithmetic_error()) <= 20);
}

TEST_CASE("readback: linear and reversed float32 read back within a few ulp of w", "[readback]") {
  const Scene scene = load_scene("", {"near=0.1", "far=10000"});
  for (const double w : {0.3, 2.0, 777.0, 5000.0, 9999.0}) {
    // linear: d = (w - n) / (f - n) rounds to binary32 (half its ulp), which (f - n) scales to
    // under half an ulp of w; n + d * (f - n) rounds f - n, the product and the sum: 2 ulp of w.
    const ReadbackRow lin =
        readback_row(scene, Technique::linear, "float32", DepthRange::gl, w, Inverse::linear);
    INFO("w = " << w);
    CHECK(std::fabs(lin.storage_error()) <= ulp32(w));
    CHECK(std::fabs(lin.arithmetic_error()) <= 2 * ulp32(w));
    // reversed in [0, 1]: d = n (f - w) / ((f - n) w) keeps binary32's relative precision down to
    // small d, and three.js's reversed branch ( near * far ) / ( ( near - far ) * d - near ) loses
    // a few roundings of it: within 4 ulp of w, as Godot's inverse projection is.
    for (const Inverse inv : {Inverse::threejs, Inverse::godot}) {
      const ReadbackRow rev =
          readback_row(scene, Technique::reversed, "float32", DepthRange::zero_to_one, w, inv);
      INFO(to_string(inv));
      CHECK(std::fabs(rev.arithmetic_error()) <= 4 * ulp32(w));
      CHECK(std::fabs(rev.error()) <= 8 * ulp32(w));
    }
  }
}

TEST_CASE("readback: the log inverses against their binary64 closed forms", "[readback]") {
  const Scene scene = load_scene("", {"near=1", "far=1e9"});
  for (const double w : {1.5, 100.0, 12345.0, 1e6, 5e8}) {
    INFO("w = " << w);
    // three.js: w = (f + 1)^d - 1 = exp2(d log2(f + 1)) - 1. The exponent x = d log2(f + 1) is
    // under 30, where binary32's spacing is 2^-19: the log2 (glibc's log2f, within 0.75 ulp) and
    // the product (half an ulp) put up to 2.4e-6 into it, which exp2 turns into 1.7e-6 = 28 u of
    // w + 1, with exp2's own rounding and the - 1 under 40 u.
    const ReadbackRow t =
        readback_row(scene, Technique::log_threejs, "float32", DepthRange::gl, w, Inverse::exp2);
    const double d = t.depth;
    CHECK_THAT(t.exact, WithinRel(std::expm1(d * std::log1p(1e9)), 1e-12));
    CHECK(std::fabs(t.arithmetic_error()) <= 40 * 0x1.0p-24 * (w + 1));
    // Cesium: w = 2^(d log2(f - n + 1)) - 1 + n, with n = 1 the same curve as three.js's less
    // one: its code stores log2(w) / log2(1e9)
    const ReadbackRow c =
        readback_row(scene, Technique::log_cesium, "float32", DepthRange::gl, w, Inverse::cesium);
    CHECK_THAT(c.exact, WithinRel(1 + std::expm1(c.depth * std::log1p(1e9 - 1)), 1e-12));
    CHECK(std::fabs(c.arithmetic_error()) <= 40 * 0x1.0p-24 * w);
  }
  // At the near plane Cesium stores 0 and reads back exactly n
  const ReadbackRow at_near =
      readback_row(scene, Technique::log_cesium, "unorm24", DepthRange::gl, 1.0, Inverse::cesium);
  CHECK(at_near.code == 0);
  CHECK(at_near.read == 1.0);
  CHECK(at_near.error() == 0);
}

TEST_CASE("readback: which inverses read which technique, and distances it stores no depth for",
          "[readback]") {
  CHECK(inverses_of(Technique::standard) == std::vector<Inverse>{Inverse::threejs, Inverse::godot});
  CHECK(inverses_of(Technique::reversed_infinite) == std::vector<Inverse>{Inverse::godot});
  CHECK(inverses_of(Technique::log_threejs_vertex) == std::vector<Inverse>{Inverse::exp2});
  CHECK(inverses_of(Technique::log_cesium) == std::vector<Inverse>{Inverse::cesium});
  const Scene scene = load_scene("", {"near=1", "far=1e9"});
  CHECK_THROWS_WITH(readback(scene, {Technique::log_cesium, "float32", DepthRange::gl}, 0.5),
                    Catch::Matchers::Contains("nearer than the near plane 1: log_cesium clips it"));
  CHECK_THROWS_WITH(readback(scene, {Technique::standard, "unorm24", DepthRange::gl}, 2e9),
                    Catch::Matchers::Contains("beyond the far plane"));
  // log_threejs_vertex does not clip at the near plane: its depth there reads back
  CHECK(readback(scene, {Technique::log_threejs_vertex, "unorm24", DepthRange::gl}, 0.5).size() ==
        1);
  // layered reads through the mapping of the layer that holds w
  const auto layered = readback(scene, {Technique::layered, "unorm24", DepthRange::gl}, 1e5);
  REQUIRE(layered.size() == 2);
  CHECK(std::fabs(layered[0].error()) < layered[0].code_gap);
}
