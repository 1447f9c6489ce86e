// Lapidous-Jiao metric: stability against a binary128 evaluation of eq. 7 as written, the
// paper's findings as they come out of this implementation, and the docs/spec.md 7 reference
// figures.
#include <catch2/catch.hpp>
#include <cmath>

#include "host/analysis/lj_tables.h"
#include "host/lj/lj_metric.h"
#include "host/lj/lj_pipeline.h"
#include "host/model/resolve.h"
#include "tests/support/mts_fixture.h"

using namespace depthprec;
using quad = __float128;

namespace {

quad qabs(quad x) {
  return x < 0 ? -x : x;
}

quad pow2(int p) {
  quad r = 1;
  for (; p > 0; --p) r *= 2;
  for (; p < 0; ++p) r /= 2;
  return r;
}

// floor(log2 x) for a positive binary128
int binade(quad x) {
  int p = static_cast<int>(std::floor(std::log2(static_cast<double>(x))));
  while (pow2(p) > x) --p;
  while (pow2(p + 1) <= x) ++p;
  return p;
}

// Eq. 7 literally, in binary128: dZe = |Ze(D + delta) - Ze(D)| with the docs/spec.md 6 readings.
double reference_ae(const LjConfig& c, const StorageFormat& f) {
  const quad d = c.near, fa = c.far;
  quad num = 0, den = 0;
  const df_format& s = f.spec();
  const quad top = f.largest();
  for (long long i = 0; i < c.samples; ++i) {
    const quad Ze = d + (fa - d) * quad(i) / quad(c.samples - 1);
    quad D;
    switch (c.buffer) {
      case LjBuffer::z:
        D = fa / (fa - d) * (1 - d / Ze);
        break;
      case LjBuffer::w:
        D = Ze / fa;
        break;
      case LjBuffer::inverse_w:
        D = d / Ze;
        break;
      default:
        D = d / (fa - d) * (fa / Ze - 1);
        break;
    }
    const int p = D > 0 ? binade(D) : -1000;
    const quad dv = D >= quad(0x1p-126) ? pow2(p - 23) : quad(0x1p-149);
    quad dp;
    if (f.is_unorm())
      dp = quad(1) / quad(s.max_code);
    else if (D >= top)
      dp = top - quad(f.decode(s.max_code - 1));
    else
      dp = pow2(std::max(p, 1 - s.bias) - s.man_bits);
    const quad delta = dv > dp ? dv : dp;
    auto ze = [&](quad x) -> quad {
      switch (c.buffer) {
        case LjBuffer::z:
          return d / (1 - x * (fa - d) / fa);
        case LjBuffer::w:
          return x * fa;
        case LjBuffer::inverse_w:
          return d / x;
        default:
          return fa / (1 + x * (fa - d) / d);
      }
    };
    if (c.buffer == LjBuffer::z && 1 - (D + delta) * (fa - d) / fa <= 0) return INFINITY;
    const quad w = c.sampling == LjSampling::uniform ? quad(1) : Ze - d;
    num += qabs(ze(D + delta) - ze(D)) * w;
    den += w;
  }
  return static_cast<double>(num / ((fa - d) * den));
}

LjConfig cfg(LjBuffer b, double far, long long n = 1000000, LjSampling s = LjSampling::uniform) {
  return table_config(b, far, n, s);  // near 1, as every LJ table
}

double ae(LjBuffer b, const std::string& format, double far, LjSampling s = LjSampling::uniform) {
  return lj_average_error_device(test::runtime(), cfg(b, far, 200000, s),
                                 StorageFormat::parse(format))
      .ae;
}

int best_e(LjBuffer b, int bits, double far) {
  int best = 0;
  double best_ae = ae(b, "unorm" + std::to_string(bits), far);
  for (int e = 1; e <= 8; ++e) {
    const double v = ae(b, "e" + std::to_string(e) + "m" + std::to_string(bits - e), far);
    if (v < best_ae) best_ae = v, best = e;
  }
  return best;
}

}  // namespace

TEST_CASE("binary64 ae agrees with eq. 7 in binary128 to 1e-12", "[lj][stability]") {
  struct Case {
    LjBuffer b;
    const char* format;
    double far;
  };
  const Case cases[] = {{LjBuffer::z, "unorm16", 100},
                        {LjBuffer::z, "unorm24", 1e4},
                        {LjBuffer::z, "unorm24", 1e6},
                        {LjBuffer::z, "float32", 1e6},
                        {LjBuffer::z, "unorm32", 1e3},
                        {LjBuffer::w, "unorm24", 1e6},
                        {LjBuffer::w, "float32", 50},
                        {LjBuffer::inverse_w, "e4m12", 1e3},
                        {LjBuffer::inverse_w, "float32", 1e6},
                        {LjBuffer::complementary_z, "float32", 1e6},
                        {LjBuffer::complementary_z, "e4m20", 1e4},
                        {LjBuffer::complementary_z, "e3m13", 20}};
  for (const auto& k : cases) {
    for (const LjSampling s : {LjSampling::uniform, LjSampling::increasing}) {
      const LjConfig c = cfg(k.b, k.far, 20001, s);
      const StorageFormat f = StorageFormat::parse(k.format);
      const double host = lj_average_error(c, f).ae;
      const double ref = reference_ae(c, f);
      INFO(to_string(k.b) << " " << k.format << " f/d " << k.far << " " << to_string(s) << ": host "
                          << host << " reference " << ref);
      REQUIRE(std::isfinite(ref));
      CHECK(std::abs(host - ref) <= 1e-12 * ref);
    }
  }
}

TEST_CASE("the device kernel agrees with the host and the Z pole gives inf not NaN", "[lj]") {
  for (const auto& [b, format, far] : {std::tuple{LjBuffer::z, "unorm24", 1e4},
                                       std::tuple{LjBuffer::complementary_z, "float32", 1e6},
                                       std::tuple{LjBuffer::inverse_w, "e4m12", 500.0}}) {
    const LjConfig c = cfg(b, far, 1000000);
    const StorageFormat f = StorageFormat::parse(format);
    const double host = lj_average_error(c, f).ae;
    const double dev = lj_average_error_device(test::runtime(), c, f).ae;
    INFO(to_string(b) << " " << format << " " << far);
    CHECK(std::abs(host - dev) <= 1e-12 * host);
  }
  const LjResult pole =
      lj_average_error(cfg(LjBuffer::z, 1e6, 10001), StorageFormat::parse("unorm16"));
  CHECK(std::isinf(pole.ae));
  CHECK(pole.infinite_samples > 0);
  const LjResult pole_dev = lj_average_error_device(test::runtime(), cfg(LjBuffer::z, 1e6, 10001),
                                                    StorageFormat::parse("unorm16"));
  CHECK(std::isinf(pole_dev.ae));
}

// LJ99 eq. 2 makes E = 0 and E = 1 the same integer format (uniform codes 2^-b apart);
// docs/spec.md's unorm<b> spaces its codes 1/(2^b - 1), a hair wider, so e1m<b-1> edges it out by
// 2^-b relative. "Integer storage is best" therefore reads: the best E is 0 or 1, unorm within
// 2^(1-b) of it.
TEST_CASE("LJ99: integer storage is best for Z and W at 16 and 24 bits", "[lj][paper]") {
  for (int bits : {16, 24})
    for (double far : {10.0, 100.0, 1000.0})
      for (const LjBuffer b : {LjBuffer::z, LjBuffer::w}) {
        INFO(bits << " bits, f/d " << far << " " << to_string(b));
        CHECK(best_e(b, bits, far) <= 1);
        const double integer = ae(b, "unorm" + std::to_string(bits), far);
        const double e1 = ae(b, "e1m" + std::to_string(bits - 1), far);
        const double e2 = ae(b, "e2m" + std::to_string(bits - 2), far);
        CHECK(std::abs(integer - e1) <= std::ldexp(2.0, -bits) * e1);
        CHECK(e2 > 1.2 * integer);
      }
}

TEST_CASE("LJ99: inverse W is best with 3 exponent bits for 20 < f/d < 200, 4 above 200",
          "[lj][paper]") {
  for (int bits : {16, 24}) {
    for (double far : {50.0, 100.0}) {
      INFO(bits << " bits, f/d " << far);
      CHECK(best_e(LjBuffer::inverse_w, bits, far) == 3);
    }
    for (double far : {500.0, 1000.0}) {
      INFO(bits << " bits, f/d " << far);
      CHECK(best_e(LjBuffer::inverse_w, bits, far) == 4);
    }
  }
}

TEST_CASE("LJ99: complementary Z has about 2x the W error at 16/24 bits for f/d >= 100",
          "[lj][paper]") {
  for (int bits : {16, 24})
    for (double far : {100.0, 1000.0}) {
      double best = INFINITY;
      for (int e = 1; e <= 8; ++e)
        best = std::min(best, ae(LjBuffer::complementary_z,
                                 "e" + std::to_string(e) + "m" + std::to_string(bits - e), far));
      const double w = ae(LjBuffer::w, "unorm" + std::to_string(bits), far);
      INFO(bits << " bits, f/d " << far << ": complementary Z " << best << ", W " << w);
      CHECK(best / w > 1.4);
      CHECK(best / w < 3.0);
    }
}

TEST_CASE("LJ99: 32-bit complementary Z is limited by the per-vertex term and beats W",
          "[lj][paper]") {
  for (double far : {10.0, 100.0, 1000.0}) {
    const LjResult cz = lj_average_error(cfg(LjBuffer::complementary_z, far, 100001),
                                         StorageFormat::parse("float32"));
    const LjResult w =
        lj_average_error(cfg(LjBuffer::w, far, 100001), StorageFormat::parse("unorm32"));
    INFO("f/d " << far << ": vertex-limited fraction " << cz.vertex_limited << ", ae " << cz.ae
                << " vs W " << w.ae);
    CHECK(cz.vertex_limited == 1.0);  // float32 storage never resolves finer than the vertex input
    CHECK(w.ae / cz.ae > 2.0);        // "3 times better than W buffer"
    CHECK(w.ae / cz.ae < 4.0);
    // the 28-bit "24.4" format gives the same precision (the vertex term limits both)
    const LjResult cz28 = lj_average_error(cfg(LjBuffer::complementary_z, far, 100001),
                                           StorageFormat::parse("e4m24"));
    CHECK(std::abs(cz28.ae - cz.ae) < 0.01 * cz.ae);
  }
}

TEST_CASE("OpenGL wiki: 16-bit Z, n = 0.01, f = 1000, codes 1 and 65534", "[lj][resolve]") {
  const ResolveSetup s{Technique::standard, 0.01, 1000, {}};
  const auto f = StorageFormat::parse("unorm16");
  CHECK(std::round(resolve_code(s, f, 1).distance * 1e8) == 1000015.0);       // 0.01000015
  CHECK(std::round(resolve_code(s, f, 65534).distance * 1e5) == 39590054.0);  // 395.90054
}

TEST_CASE("a code at the end of the range has one neighbour, and its gap is not rounded to zero",
          "[lj][resolve]") {
  // Reversed float32 at the far plane: depth 0, code 0. Code 1 (2^-149 of depth) lies
  // f (f - n) / n 2^-149 nearer: 1.4e-36, far below binary128's resolution at 1e4.
  const ResolveSetup s{Technique::reversed, 0.1, 1e4, {}};
  const DistanceResolution at_far = resolve_distance(s, StorageFormat::parse("float32"), 1e4);
  CHECK(at_far.code == 0u);
  CHECK(std::isnan(at_far.gap_below));
  const double slope = 1e4 * (1e4 - 0.1) / 0.1;
  CHECK(at_far.gap_above == Approx(slope * std::ldexp(1.0, -149)).epsilon(1e-6));
  CHECK(at_far.resolution == at_far.gap_above);
  // Standard unorm16 at the far plane: its last code, whose only neighbour is below.
  const ResolveSetup st{Technique::standard, 0.1, 1e4, {}};
  const DistanceResolution last = resolve_distance(st, StorageFormat::parse("unorm16"), 1e4);
  CHECK(last.code == 65535u);
  CHECK(std::isnan(last.gap_above));
  CHECK(last.gap_below > 1000);
  CHECK(last.resolution == last.gap_below);
}

TEST_CASE("Quantitative analysis: reversed float32 Z, n = 0.1, f = 1e4", "[lj][resolve]") {
  const ResolveSetup s{Technique::reversed, 0.1, 1e4, {}};
  const auto f = StorageFormat::parse("float32");
  const CodeInterval ci = resolve_code(s, f, 700000000u);
  CHECK(std::abs(ci.depth - 8.22242e-14) < 1e-19);
  CHECK(ci.distance > 9999.9999);
  CHECK(ci.distance < 10000.0);
  double worst = 0;
  for (const auto& r : resolution_curve(s, f, 400)) worst = std::max(worst, r.resolution);
  INFO("worst resolution " << worst);
  CHECK(worst < 1e-3);  // below 1 mm over the range
  // with the far plane at infinity, precision is barely changed up to about 1000
  const ResolveSetup inf{Technique::reversed_infinite, 0.1, INFINITY, {}};
  for (double w : {1.0, 10.0, 100.0, 1000.0}) {
    const double a = resolve_distance(s, f, w).resolution,
                 b = resolve_distance(inf, f, w).resolution;
    INFO("w " << w << ": finite " << a << " infinite " << b);
    CHECK(b / a < 1.1);
    CHECK(b / a > 0.9);
  }
}

TEST_CASE("the pipeline-measured ae follows the analytic one where arithmetic is exact enough",
          "[lj][pipeline]") {
  Pipeline p;
  p.depth_range = DepthRange::zero_to_one;
  for (const auto& [b, format] :
       {std::pair{LjBuffer::z, "unorm16"}, std::pair{LjBuffer::w, "unorm16"},
        std::pair{LjBuffer::complementary_z, "e4m12"}}) {
    const LjConfig c = cfg(b, 100, 100001);
    const auto f = StorageFormat::parse(format);
    const double analytic = lj_average_error(c, f).ae;
    const LjPipelineResult pipe = lj_pipeline_error(c, f, p);
    INFO(to_string(b) << " " << format << ": analytic " << analytic << " pipeline " << pipe.ae);
    CHECK(pipe.clipped == 0);
    CHECK(pipe.ae / analytic > 0.9);
    CHECK(pipe.ae / analytic < 1.1);
  }
}
