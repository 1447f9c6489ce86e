// depthprec bias: the r of each API and format, the offset formula against the conformance
// tests' figures, the kernel against the host reference pipeline probe by probe, the searches'
// answers (one unit less fights), known facts (a camera-facing decal in unorm24 needs a few
// units; under standard projection the eye-space separation a fixed bias amounts to grows as
// z^2 / n), and the command's errors. Journal, resume, shards and merge: tests/batch/batch.cpp,
// with every record batch.
#include <fmt/format.h>

#include <catch2/catch.hpp>
#include <cmath>
#include <nlohmann/json.hpp>

#include "host/base/errors.h"
#include "host/bias/bias_evaluator.h"
#include "host/bias/bias_reference.h"
#include "host/bias/bias_search.h"
#include "host/model/frame_setup.h"
#include "host/model/profile.h"
#include "host/model/tilt_limit.h"
#include "interface/bias_formula.h"
#include "tests/support/mts_fixture.h"
#include "tests/support/run_cli.h"

using namespace depthprec;
using Catch::Matchers::Contains;
using depthprec::test::kSmallScene;
using depthprec::test::run_cli;

namespace {

BiasOptions api(BiasApi a) {
  BiasOptions o;
  o.api = a;
  return o;
}

double r_of(const BiasOptions& o, const std::string& format) {
  return bias_rule(o, StorageFormat::parse(format)).r_fixed;
}

// llvmpipe: with the llvmpipe profile's settings (host/model/profile.cpp).
// facing: one frame, the planes exactly facing the camera (rotation 0 about every axis, the first
// orientation the worst case's rounds sample).
Scene bias_scene(const std::string& technique, const std::string& format, bool llvmpipe = false,
                 bool facing = false) {
  std::vector<std::string> sets = {
      "kernel=[32,32]",
      fmt::format(R"(evaluate=[{{"technique": "{}", "format": "{}"}}])", technique, format)};
  if (facing)
    for (const char* set : {"frames=1", "rotation_step=[0,0,0]", "rotation_offset=[0,0,0]"})
      sets.push_back(set);
  else
    sets.push_back("frames=6");
  if (llvmpipe)
    for (const std::string& set : profile("llvmpipe").sets) sets.push_back(set);
  return load_scene("", sets);
}

// The reference's verdict over every frame: the overlay passes when no frame fights and
// nothing was clipped, uncovered or non-finite.
bool reference_passes(const Scene& s, const EvalPair& pair, const BiasOptions& o,
                      const BiasProbe& p) {
  for (int f = 0; f < s.frames; ++f) {
    const BiasFrame fr = reference_bias_frame(s, pair, o, p, f);
    if (fr.fight || fr.clipped || fr.uncovered || fr.non_finite) return false;
  }
  return true;
}

// The smallest whole units that pass on the emulator, by the search `bias` runs.
BiasAnswer units_answer(BiasEvaluator& ev, const Scene& s, const EvalPair& pair, double z) {
  IntegerBiasSearch search(1 << 26);
  while (!search.done())
    search.record(ev.run({{z, bias_sign(s, pair) * search.next(), 0}}).front());
  return search.answer();
}

}  // namespace

TEST_CASE("r per API and format follows the specifications", "[bias]") {
  // fixed point: GL and D3D one code step, Vulkan (depthBiasExact) 2^-n
  CHECK(r_of(api(BiasApi::gl), "unorm24") == 1.0 / 16777215.0);
  CHECK(r_of(api(BiasApi::d3d), "unorm16") == 1.0 / 65535.0);
  CHECK(r_of(api(BiasApi::vulkan), "unorm16") == std::ldexp(1.0, -16));
  CHECK(r_of(api(BiasApi::vulkan), "unorm24") == std::ldexp(1.0, -24));
  CHECK(r_of(api(BiasApi::gl), "unorm32") == 1.0 / 4294967295.0);
  BiasOptions mesa = api(BiasApi::gl);
  mesa.unorm_r = UnormR::double_step;  // llvmpipe: units * mrd * 2
  CHECK(r_of(mesa, "unorm24") == 2.0 / 16777215.0);
  BiasOptions nvidia = api(BiasApi::vulkan);
  nvidia.unorm_r = UnormR::double_pow2;
  CHECK(r_of(nvidia, "unorm16") == std::ldexp(1.0, -15));
  // floating point: the primitive's exponent rule; Vulkan's representations override it
  CHECK(bias_rule(api(BiasApi::d3d), StorageFormat::parse("float32")).float_rule);
  BiasOptions force = api(BiasApi::vulkan);
  force.representation = VulkanRepresentation::force_unorm;
  CHECK(r_of(force, "float32") == std::ldexp(1.0, -24));
  force.representation = VulkanRepresentation::float_value;
  CHECK(r_of(force, "float32") == 1.0);
  CHECK(r_of(force, "unorm16") == 1.0);
  // formats without a rule, named with what is allowed
  CHECK_THROWS_WITH(bias_rule(api(BiasApi::d3d), StorageFormat::parse("unorm32")),
                    Contains("unorm16, unorm24 and float32"));
  CHECK_THROWS_AS(bias_rule(api(BiasApi::gl), StorageFormat::parse("float16")), InputError);
  CHECK_THROWS_AS(bias_rule(api(BiasApi::vulkan), StorageFormat::parse("e4m12")), InputError);
}

TEST_CASE("the offset formula reproduces the conformance tests' figures", "[bias]") {
  // VK-GL-CTS calcMinResolvableDiff, float: 2^(exponent(z) - 23)
  CHECK(depth_bias_float_r(0.25f) == std::ldexp(1.0f, -25));
  CHECK(depth_bias_float_r(0.3125f) == std::ldexp(1.0f, -25));
  CHECK(depth_bias_float_r(0.489742279053f) == std::ldexp(1.0f, -25));
  CHECK(depth_bias_float_r(0.625f) == std::ldexp(1.0f, -24));
  CHECK(depth_bias_float_r(0.125f) == std::ldexp(1.0f, -26));
  CHECK(depth_bias_float_r(0.0f) == std::ldexp(1.0f, -149));
  // WebGPU CTS depth_bias.spec.ts, depth32float: z = 0.25 with bias 8388608 ends at 0.5, with a
  // clamp of 0.125 at 0.375; a quad of slope 0.5 with slope scale 1 ends at 0.75
  CHECK(0.25f + depth_bias(8388608.0f, 1, 0, 0, 0, 0.25f, 0.25f, 0.25f) == 0.5f);
  CHECK(0.25f + depth_bias(8388608.0f, 1, 0, 0.125f, 0, 0.25f, 0.25f, 0.25f) == 0.375f);
  CHECK(0.25f + depth_bias(0, 1, 1.0f, 0, depth_bias_slope(0.5f, 0, BIAS_SLOPE_MAX), 0.25f, 0.25f,
                           0.25f) ==
        0.75f);
  // the slope forms, and a negative clamp limiting a negative bias
  CHECK(depth_bias_slope(3e-3f, -4e-3f, BIAS_SLOPE_MAX) == 4e-3f);
  CHECK(depth_bias_slope(3.0f, -4.0f, BIAS_SLOPE_SQRT) == 5.0f);
  CHECK(depth_bias(-1e-3f, 0, 0, -1e-4f, 0, 0.5f, 0.5f, 0.5f) == -1e-4f);
}

TEST_CASE("the bias kernel decides every probe as the host reference pipeline does",
          "[bias][reference]") {
  struct Case {
    const char* technique;
    const char* format;
    double z;
    double tilt;
    bool llvmpipe;  // under the llvmpipe profile's plane, viewport and conversion
    bool facing;    // one frame facing the camera: llvmpipe's clip stage makes empty fan triangles
  };
  for (const Case c : {Case{"standard", "unorm24", 100, 0, false, false},
                       Case{"reversed", "float32", 1000, 0, false, false},
                       Case{"standard", "float32", 10, 45, false, false},
                       Case{"log_vertex", "unorm16", 50, 0, false, false},
                       Case{"infinite", "unorm24", 3000, 30, false, false},
                       Case{"standard", "unorm24", 100, 0, true, false},
                       Case{"reversed", "unorm32", 1000, 20, true, false},
                       Case{"standard", "unorm24", 500, 0, true, true}}) {
    INFO(c.technique << " " << c.format << " z=" << c.z << " tilt=" << c.tilt
                     << (c.llvmpipe ? " llvmpipe" : "") << (c.facing ? " facing" : ""));
    const Scene s = bias_scene(c.technique, c.format, c.llvmpipe, c.facing);
    const EvalPair pair = s.evaluate[0];
    BiasOptions o;
    o.tilt_deg = c.tilt;
    BiasEmulator ev(test::runtime(), s, pair, o);
    const BiasAnswer u = units_answer(ev, s, pair, c.z);
    REQUIRE(u.resolved());
    const double sign = bias_sign(s, pair);
    // the answer, one unit less, one more; the slope factor alone; both
    std::vector<BiasProbe> probes = {{c.z, sign * u.value, 0},
                                     {c.z, sign * (u.value + 1), 0},
                                     {c.z, 0, sign * 0.5},
                                     {c.z, 0, sign * 4},
                                     {c.z, sign * std::max(0.0, u.value - 2), sign}};
    if (u.value > 0) probes.push_back({c.z, sign * (u.value - 1), 0});
    const auto results = ev.run(probes);
    for (size_t i = 0; i < probes.size(); ++i) {
      INFO("units " << probes[i].units << " factor " << probes[i].factor);
      CHECK(bias_passes(results[i]) == reference_passes(s, pair, o, probes[i]));
    }
    CHECK(bias_passes(results[0]));
    if (u.value > 0) CHECK_FALSE(bias_passes(results.back()));  // one unit less fights
  }
}

TEST_CASE("a camera-facing decal needs a few units, and its eye-space reach grows as z^2 / n",
          "[bias]") {
  const auto r = run_cli("bias -t standard,reversed -f unorm24 --distances 100,1000,10000 " +
                         kSmallScene + "--format-out json");
  REQUIRE(r.exit_code == 0);
  const auto j = nlohmann::json::parse(r.output);
  CHECK(j["kind"] == "bias");
  CHECK(j["api"] == "gl");
  REQUIRE(j["records"].size() == 2);
  const auto& standard = j["records"][0]["rows"];
  const auto& reversed = j["records"][1]["rows"];
  REQUIRE(standard.size() == 3);
  for (const auto& row : standard) {
    // LESS: a negative bias moves the overlay toward the camera; a small whole number of units
    const double u = row["units"];
    CHECK(u <= -1);
    CHECK(u >= -4);
    CHECK(u == std::round(u));
    CHECK(row["units_fails"].get<double>() == u + 1);
  }
  for (const auto& row : reversed) CHECK(row["units"].get<double>() >= 1);  // GREATER: positive
  // Under the guaranteed MTS's model the constant bias is at least the one the search found, of
  // the same sign: it covers every orientation and implementation, the search its samples.
  for (const auto* rows : {&standard, &reversed})
    for (const auto& row : *rows) {
      INFO(row.dump());
      const double u = row["units"], ub = row["units_bound"];
      CHECK(ub * u > 0);
      CHECK(std::fabs(ub) >= std::fabs(u));
      CHECK(ub == std::round(ub));
    }
  // a fixed offset in window depth is a fixed step of 1/w, so its eye-space reach is about
  // z^2 / n times it: z 10 times farther, 100 times the separation
  const double units100 = standard[0]["units"], units1e4 = standard[2]["units"];
  const double per_unit100 = standard[0]["eye_separation"].get<double>() / std::fabs(units100),
               per_unit1e4 = standard[2]["eye_separation"].get<double>() / std::fabs(units1e4);
  CHECK(per_unit1e4 / per_unit100 == Approx(1e4).epsilon(0.02));
  const double n = j["scene"]["near"];
  CHECK(per_unit100 == Approx(100.0 * 100.0 / n / 16777215.0).epsilon(0.02));
}

TEST_CASE("bias refuses what has no bias rule and says why", "[bias][cli][errors]") {
  const std::string base = "bias --distances 100 " + kSmallScene;
  const auto d3d32 = run_cli(base + "-t standard -f unorm32 --api d3d");
  CHECK(d3d32.exit_code == 3);
  CHECK_THAT(d3d32.output, Contains("unorm16, unorm24 and float32"));
  CHECK(run_cli(base + "-t standard -f float16").exit_code == 3);
  CHECK(run_cli(base + "-t standard -f unorm24 --tilt 95").exit_code == 3);
  CHECK(run_cli(base + "-t standard -f unorm24 --tilt -5").exit_code == 3);
  CHECK(run_cli(base + "-t standard -f unorm24 --api d3d --slope sqrt").exit_code == 3);
  CHECK(run_cli(base + "-t standard -f unorm24 --vulkan-representation float").exit_code == 3);
  CHECK(run_cli(base + "-t standard -f unorm24 --api metal").exit_code == 3);
  CHECK(run_cli(base + "-t standard -f unorm24 --set-factor -1").exit_code == 3);
  // an envelope's adversary: no advice that leads to a second refusal
  const auto envelope = run_cli(base + "-t standard -f unorm24 --profile d3d11");
  CHECK(envelope.exit_code == 3);
  CHECK_THAT(envelope.output, Contains("bias has no d3d11 emulation") &&
                                  Contains("--set bound_model=d3d11") && !Contains("--r-unorm"));
  // a technique whose fragment stage writes depth gets a row saying so, not a number
  const auto frag = run_cli(base + "-t log_fragment,standard -f unorm24 --format-out json");
  REQUIRE(frag.exit_code == 0);
  const auto j = nlohmann::json::parse(frag.output);
  CHECK(j["records"][0]["applicable"] == false);
  CHECK_THAT(j["records"][0]["reason"].get<std::string>(), Contains("fragment stage"));
  CHECK(j["records"][1]["applicable"] == true);
}

TEST_CASE("bias clamps are signed as the APIs define them, and so is the offset", "[bias][cli]") {
  // D3D (DepthBiasClamp), Vulkan (depthBiasClamp) and GL (glPolygonOffsetClamp): min(o, c) for
  // c > 0, max(o, c) for c < 0. Under LESS (standard) the bias is negative, so only a negative
  // clamp limits it; under GREATER (reversed) only a positive one.
  CHECK(depth_bias(-1e-3f, 0, 0, 1e-4f, 0, 0.5f, 0.5f, 0.5f) == -1e-3f);
  CHECK(depth_bias(1e-3f, 0, 0, 1e-4f, 0, 0.5f, 0.5f, 0.5f) == 1e-4f);
  CHECK(depth_bias(1e-3f, 0, 0, -1e-4f, 0, 0.5f, 0.5f, 0.5f) == 1e-3f);
  CHECK(clamped(-1e-3, 1e-4) == -1e-3);
  CHECK(clamped(1e-3, 1e-4) == 1e-4);
  CHECK(clamped(-1e-3, -1e-4) == -1e-4);
  CHECK(clamped(1e-3, -1e-4) == 1e-3);
  CHECK(clamped(-1e-3, 0) == -1e-3);

  const std::string base =
      "bias -t standard,reversed -f unorm24 --distances 100 " + kSmallScene + "--format-out json";
  const auto json_of = [](const std::string& output) {
    // the JSON, without the note on stderr before it
    return nlohmann::json::parse(
        output.substr(output.find('{'), output.rfind('}') - output.find('{') + 1));
  };
  const auto plain = run_cli(base);
  REQUIRE(plain.exit_code == 0);
  const auto p = json_of(plain.output);
  const auto& standard = p["records"][0]["rows"][0];
  const auto& reversed = p["records"][1]["rows"][0];
  REQUIRE(standard["verdict"] == "resolved");
  REQUIRE(reversed["verdict"] == "resolved");
  // the offset carries the units' sign: negative under LESS, positive under GREATER
  const double r24 = 1.0 / 16777215.0;
  CHECK(standard["units"].get<double>() < 0);
  CHECK(standard["offset"].get<double>() ==
        Approx(standard["units"].get<double>() * r24).epsilon(1e-12));
  CHECK(reversed["offset"].get<double>() ==
        Approx(reversed["units"].get<double>() * r24).epsilon(1e-12));
  CHECK(reversed["offset"].get<double>() > 0);

  // A clamp far below the bias needed: it limits the pairs whose bias has its sign (no bias
  // passes: unresolvable), and leaves the others as without it, saying so.
  for (const double c : {-1e-9, 1e-9}) {
    INFO("--clamp " << c);
    const auto r = run_cli(base + fmt::format(" --clamp {}", c));
    REQUIRE(r.exit_code == 0);
    const auto j = json_of(r.output);
    CHECK(j["clamp"] == c);
    const auto& limited = j["records"][c < 0 ? 0 : 1]["rows"][0];
    const auto& unlimited = j["records"][c < 0 ? 1 : 0]["rows"][0];
    const auto& unlimited_plain = c < 0 ? reversed : standard;
    CHECK(limited["verdict"] == "unresolvable");
    CHECK(limited["factor_verdict"] == "unresolvable");
    CHECK(limited["set_verdict"] == "unresolvable");
    CHECK(unlimited["units"] == unlimited_plain["units"]);
    CHECK(unlimited["factor"] == unlimited_plain["factor"]);
    CHECK(unlimited["set_units"] == unlimited_plain["set_units"]);
    CHECK(unlimited["offset"] == unlimited_plain["offset"]);
    CHECK_THAT(r.output, Contains(fmt::format(
                             "--clamp {} has no effect on {}", c < 0 ? "-1e-09" : "1e-09",
                             c < 0 ? "reversed/unorm24/zero_to_one" : "standard/unorm24/gl")));
  }
  // A clamp beyond the bias needed changes nothing, and is not called ineffective.
  const auto loose = run_cli(base + " --clamp -1e-6");
  REQUIRE(loose.exit_code == 0);
  const auto l = json_of(loose.output);
  CHECK(l["records"][0]["rows"][0]["units"] == standard["units"]);
  CHECK(l["records"][0]["rows"][0]["offset"] == standard["offset"]);
  CHECK_THAT(loose.output, !Contains("no effect on standard"));
}

TEST_CASE(
    "tilted planes cover the whole view in every frame, their near side in front of the camera",
    "[bias][tilt]") {
  // Independent of how the plane is sized: the corner rays of the viewport meet the plane the
  // matrix builds inside its unit square, and every corner of the plane lies in front of the
  // camera. Checked on the default scene (kernel = viewport) and a wide one.
  for (const Scene& s :
       {load_scene("", {}), load_scene("", {"viewport=[320,180]", "kernel=[320,180]"})}) {
    const double ty = std::tan(s.fov_y_deg * M_PI / 360);
    const double tx = ty * s.viewport_w / s.viewport_h;
    REQUIRE(s.pipeline.compose == Compose::separate);  // plane_matrix gives the model-view
    CHECK(max_tilt_deg(s) >= 80);
    for (const double tilt : {10.0, 45.0, 60.0, 80.0, max_tilt_deg(s)}) {
      for (const double z : {2.0, 1000.0}) {
        const ProbeConstants pc = probe_constants(s, s.evaluate[0], z);
        for (int k = 0; k < s.frames; ++k) {
          INFO("viewport " << s.viewport_w << "x" << s.viewport_h << " tilt " << tilt << " z " << z
                           << " frame " << k);
          const Mat4f m = plane_matrix(s, pc, z, k, tilt * M_PI / 180);
          // eye position of object point (x, y): columns 0, 1, 3 of the row-major model-view
          const auto eye = [&m](double x, double y, int r) {
            return m[r * 4 + 0] * x + m[r * 4 + 1] * y + m[r * 4 + 3];
          };
          for (const double x : {-0.5, 0.5})
            for (const double y : {-0.5, 0.5}) CHECK(eye(x, y, 2) < 0);
          // ray t (rx, ry, -1) meets origin + x e_x + y e_y: solve the 3x3 system by Cramer's rule
          for (const double rx : {-tx, tx})
            for (const double ry : {-ty, ty}) {
              const double a[3][3] = {{m[0], m[1], -rx}, {m[4], m[5], -ry}, {m[8], m[9], 1}};
              const double b[3] = {-m[3], -m[7], -m[11]};
              const auto det = [](const double q[3][3]) {
                return q[0][0] * (q[1][1] * q[2][2] - q[1][2] * q[2][1]) -
                       q[0][1] * (q[1][0] * q[2][2] - q[1][2] * q[2][0]) +
                       q[0][2] * (q[1][0] * q[2][1] - q[1][1] * q[2][0]);
              };
              double sol[3];
              const double d = det(a);
              REQUIRE(d != 0);
              for (int c = 0; c < 3; ++c) {
                double q[3][3];
                for (int i = 0; i < 3; ++i)
                  for (int j = 0; j < 3; ++j) q[i][j] = j == c ? b[i] : a[i][j];
                sol[c] = det(q) / d;
              }
              CHECK(std::fabs(sol[0]) < 0.5);
              CHECK(std::fabs(sol[1]) < 0.5);
              CHECK(sol[2] > 0);  // in front of the camera
            }
        }
      }
    }
  }
}

TEST_CASE("bias measures tilted planes up to 80 degrees and refuses what it cannot cover",
          "[bias][tilt][cli]") {
  // The --help example's case: the default kernel (the whole viewport) and frames. Every search
  // resolves, and the steeper the plane the smaller the slope factor that separates it.
  double factor_before = INFINITY;
  for (const int tilt : {45, 60, 80}) {
    INFO("--tilt " << tilt);
    const auto r = run_cli(fmt::format(
        "bias -t standard -f unorm24 --api d3d --distances 100 --tilt {} --no-timing -q "
        "--format-out json",
        tilt));
    REQUIRE(r.exit_code == 0);
    const auto j = nlohmann::json::parse(r.output);
    const auto& row = j["records"][0]["rows"][0];
    CHECK(row["verdict"] == "resolved");
    CHECK(row["factor_verdict"] == "resolved");
    CHECK(row["set_verdict"] == "resolved");
    const double factor = -row["factor"].get<double>();
    CHECK(factor > 0);
    CHECK(factor < factor_before);
    factor_before = factor;
  }
  // refused before anything runs; the default scene's frames decide its limit
  const std::string base = "bias -t standard -f unorm24 --distances 100 -q ";
  const auto steep = run_cli(base + "--tilt 85");
  CHECK(steep.exit_code == 3);
  CHECK_THAT(steep.output, Contains("at most 82.4 degrees"));
  const auto edge_on = run_cli(base + "--tilt 90");
  CHECK(edge_on.exit_code == 3);
  CHECK_THAT(edge_on.output, Contains("[0, 90)"));
  // a wider view (fov 40 degrees) lowers the limit: its lower edge runs parallel sooner
  const auto wide = run_cli(base + "--tilt 80 --set fov_y_deg=40");
  CHECK(wide.exit_code == 3);
  CHECK_THAT(wide.output, Contains("at most"));
}
