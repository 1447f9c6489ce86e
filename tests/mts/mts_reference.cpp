// The kernel's stored codes against the plain C++ reference pipeline (host/reference_pipeline):
// bit for bit for every technique without transcendental functions, within one code for the log
// techniques (takes_shader_log).
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdlib>
#include <functional>

#include "host/model/frame_setup.h"
#include "host/model/profile.h"
#include "host/mts/reference_pipeline.h"
#include "interface/snap.h"
#include "tests/mts/reference_outcome.h"
#include "tests/support/mts_fixture.h"

using namespace depthprec;
using namespace depthprec::test;

namespace {

DP_SNAP_WINDOW_DEFINE(snap_window, std::fabs, std::rint)

struct Compared {
  size_t pixels = 0, ok_pixels = 0, differ = 0, status_differ = 0;
  long long largest_difference = 0;  // in codes
};

Compared compare(const Scene& scene, const EvalPair& pair, const Probe& probe, int frame) {
  MtsEvaluator ev(runtime(), scene, pair, true, MtsEvaluator::Kernels::with_tests);
  const FrameCodes k = ev.codes(probe, frame);
  const FrameCodes r = reference_frame(scene, pair, probe, frame);
  Compared c;
  c.pixels = k.code_a.size();
  for (size_t i = 0; i < c.pixels; ++i) {
    if (k.status_a[i] != r.status_a[i] || k.status_b[i] != r.status_b[i]) {
      ++c.status_differ;
      continue;
    }
    if (k.status_a[i] == 0 && k.status_b[i] == 0) ++c.ok_pixels;
    for (const auto& [x, y] :
         {std::pair{k.code_a[i], r.code_a[i]}, std::pair{k.code_b[i], r.code_b[i]}}) {
      if (x != y) ++c.differ;
      c.largest_difference = std::max(
          c.largest_difference, std::llabs(static_cast<long long>(x) - static_cast<long long>(y)));
    }
  }
  return c;
}

// Every probe's kernel codes against the reference's, frame frame_of(k) for the k-th probe: bit
// for bit, or within `codes` codes where the library log is involved (log_codes). Returns the
// pixels that were real depth comparisons in both.
size_t check_codes(const Scene& scene, const EvalPair& pair, const std::vector<Probe>& probes,
                   const std::function<int(size_t)>& frame_of, long long codes) {
  size_t compared = 0;
  for (size_t k = 0; k < probes.size(); ++k) {
    const Compared c = compare(scene, pair, probes[k], frame_of(k));
    INFO(pair.label() << " z = " << probes[k].z << " s = " << probes[k].s << ": " << c.differ
                      << " codes differ, by up to " << c.largest_difference);
    CHECK(c.status_differ == 0);
    CHECK(c.largest_difference <= codes);
    compared += c.ok_pixels;
  }
  return compared;
}

// How many codes the kernel's may lie from the reference's: none without a log; one with the
// library's log (the device's within 3 ulp, the host's within 1); two for the engines' log2 in
// float32, whose code is one ulp of d: for Cesium's log2((w - n) + 1) at w close to n, where d is
// small, PoCL's log2 and glibc's log2f differ by two ulp on a few hundred of 3840 pixels (measured
// at z = 1.005 and 3).
long long log_codes(const TechniqueInfo& ti, const std::string& format) {
  if (!takes_shader_log(ti)) return 0;
  return ti.map != DepthMap::log && format == "float32" ? 2 : 1;
}

// The raster kernel's probe outcomes and deciding frames against the reference's, for probes at
// the given distances and separations z * f.
void check_outcomes(const Scene& scene, const EvalPair& pair, const std::vector<double>& zs,
                    const std::vector<double>& fractions) {
  MtsEvaluator ev(runtime(), scene, pair);
  std::vector<Probe> probes;
  for (double z : zs)
    for (double f : fractions) probes.push_back({z, z * f});
  const auto results = ev.run(probes);
  for (size_t k = 0; k < probes.size(); ++k) {
    const ReferenceOutcome expect = reference_outcome(scene, pair, probes[k]);
    INFO(pair.label() << " z = " << probes[k].z << " s = " << probes[k].s);
    CHECK(to_string(results[k].outcome) == std::string(to_string(expect.outcome)));
    CHECK(results[k].frames == expect.frames);
  }
}

// Codes and probe outcomes of a projection pair (both depth ranges, unorm24 and float32) and a
// fragment-depth one, at distances from the near plane to 2^20.
void check_three_pairs(const Scene& scene) {
  for (const auto& [t, format, range] :
       {std::tuple{Technique::standard, "unorm24", DepthRange::gl},
        std::tuple{Technique::reversed, "float32", DepthRange::zero_to_one},
        std::tuple{Technique::linear, "float32", DepthRange::gl}}) {
    const EvalPair pair{t, format, range};
    INFO(pair.label());
    CHECK(check_codes(
              scene, pair, {{1.005, 3e-7}, {3.0, 1e-3}, {1000.0, 0.05}, {1048576.0, 5000.0}},
              [](size_t k) { return static_cast<int>(3 * k); }, 0) > 0);
    check_outcomes(scene, pair, {1.005, 7.0, 3000.0}, {1e-7, 1e-5, 1e-3, 0.1});
  }
}

// Sub-pixel snapping (pipeline.snap): the kernel follows the reference, codes and probe outcomes,
// with 8 bits on the grid's vertices, and with 4 on the new vertices of llvmpipe's clip stage too.
TEST_CASE("with snapped vertices the kernel follows the reference", "[mts][reference][snap]") {
  for (const auto& [bits, clip] : {std::pair{"8", "none"}, std::pair{"4", "llvmpipe"}}) {
    const Scene scene = load_scene(
        "", {"kernel=[48,40]", "viewport=[48,40]", "frames=12",
             std::string("pipeline.snap=") + bits, std::string("pipeline.clip=") + clip});
    INFO("snap " << bits << " clip " << clip);
    check_three_pairs(scene);
  }
}

// softpipe's plane (pipeline.plane = origin_quads), stepped across 2x2 quads: the kernel follows
// the reference, codes and probe outcomes, with the kernel at an odd offset in the viewport (so
// its first column and row are the odd ones of their quads) and with the clip stage's fans.
TEST_CASE("with quad-stepped planes the kernel follows the reference", "[mts][reference][quads]") {
  for (const auto& [viewport, clip] :
       {std::pair{"[51,43]", "none"}, std::pair{"[48,40]", "llvmpipe"}}) {
    const Scene scene =
        load_scene("", {"kernel=[48,40]", std::string("viewport=") + viewport, "frames=12",
                        "pipeline.plane=origin_quads", std::string("pipeline.clip=") + clip});
    INFO("viewport " << viewport << " clip " << clip);
    check_three_pairs(scene);
  }
}

// Away from the world origin (world_position, pipeline.transform): the kernel follows the
// reference, codes and probe outcomes, under each transform and both compositions (the view's
// translation on the GPU, or folded into P * V * MV on the host; relative to eye, the world
// positions in binary64 and their binary32 split).
TEST_CASE("away from the world origin the kernel follows the reference under every transform",
          "[mts][reference][world]") {
  for (const auto& [transform, compose, precision] :
       {std::tuple{"absolute", "separate", "float"},
        std::tuple{"absolute", "premultiplied", "float"},
        std::tuple{"absolute", "premultiplied", "double"},
        std::tuple{"camera_relative", "separate", "float"},
        std::tuple{"relative_to_eye", "separate", "float"}}) {
    const Scene scene = load_scene(
        "",
        {"kernel=[48,40]", "viewport=[48,40]", "frames=12", "world_position=[1e5,-2e5,3e5]",
         std::string("pipeline.transform=") + transform, std::string("pipeline.compose=") + compose,
         std::string("pipeline.matrix_precision=") + precision});
    INFO(transform << " " << compose << " " << precision);
    check_three_pairs(scene);
  }
}

// A GLSL ES mediump vertex shader (pipeline.shader_precision, interface/binary16.h): the kernel
// follows the reference, codes and probe outcomes, at the origin and away from it, under each
// transform it combines with and both compositions, with separate and fused rows.
TEST_CASE("under a mediump vertex shader the kernel follows the reference",
          "[mts][reference][mediump]") {
  for (const std::string precision : {"mediump", "es2_highp"})
    for (const auto& [transform, compose, vertex, world] :
         {std::tuple{"absolute", "separate", "separate", "[0,0,0]"},
          std::tuple{"absolute", "separate", "fma", "[1000,-500,3000]"},
          std::tuple{"absolute", "premultiplied", "separate", "[1000,-500,3000]"},
          std::tuple{"camera_relative", "separate", "separate", "[1000,-500,3000]"}}) {
      const Scene scene = load_scene(
          "",
          {"kernel=[48,40]", "viewport=[48,40]", "frames=12",
           "pipeline.shader_precision=" + precision, std::string("world_position=") + world,
           std::string("pipeline.transform=") + transform,
           std::string("pipeline.compose=") + compose, std::string("pipeline.vertex=") + vertex});
      INFO(precision << " " << transform << " " << compose << " " << vertex << " " << world);
      check_three_pairs(scene);
    }
}

// A fragment shader that writes depth in mediump (interface/mediump_fragment.h): the kernel follows
// the reference bit for bit where the shader has no log, and within one binary16 step of d where
// the log's last binary32 bit (the device's and the host's differ by up to 3 ulp) decides which
// way it rounds, on few pixels. far = 1000 keeps linear's range within mediump's.
TEST_CASE("under a mediump fragment shader the kernel follows the reference",
          "[mts][reference][mediump]") {
  for (const std::string precision : {"mediump", "es2_highp"}) {
    const Scene scene = load_scene("", {"kernel=[48,40]", "viewport=[48,40]", "frames=12",
                                        "far=1000", "pipeline.shader_precision=" + precision});
    // one step of d in [0.5, 1) at the precision: 2^13 unorm24 codes or binary32 ulps in binary16,
    // 2^7 at 17 bits
    const long long step = precision == "mediump" ? 8192 : 128;
    for (const auto& [t, format] :
         {std::pair{Technique::linear, "unorm24"}, std::pair{Technique::w_buffer, "float32"},
          std::pair{Technique::log_fragment, "unorm24"},
          std::pair{Technique::log_threejs, "float32"},
          std::pair{Technique::log_cesium, "float32"}}) {
      const EvalPair pair{t, format, DepthRange::gl};
      INFO(precision << " " << pair.label());
      const bool log = takes_shader_log(info(t));
      size_t differ = 0, pixels = 0;
      for (const Probe& p : {Probe{1.5, 1e-3}, Probe{30.0, 0.1}, Probe{700.0, 2.0}}) {
        const Compared c = compare(scene, pair, p, 4);
        CHECK(c.status_differ == 0);
        CHECK(c.largest_difference <= (log ? step : 0));
        differ += c.differ;
        pixels += c.ok_pixels;
      }
      CHECK(pixels > 0);
      CHECK(differ * 50 <= pixels);
      // a binary16 step that differs can decide a probe: outcomes where the shader has no log
      if (!log) check_outcomes(scene, pair, {1.5, 30.0, 700.0}, {1e-4, 1e-2, 1e-1});
    }
  }
}

}  // namespace

TEST_CASE("snapping moves window coordinates to the 2^-n pixel grid, half to even", "[snap]") {
  CHECK(snap_window(0.3f, 2) == 0.25f);
  CHECK(snap_window(0.375f, 2) == 0.5f);  // 1.5 quarters: to the even 2
  CHECK(snap_window(0.625f, 2) == 0.5f);  // 2.5 quarters: to the even 2
  CHECK(snap_window(-0.3f, 2) == -0.25f);
  CHECK(snap_window(100.00195f, 8) == 100.0f);
  CHECK(snap_window(100.00196f, 8) == 100.00390625f);
  CHECK(snap_window(0.3f, 0) == 0.3f);          // none
  CHECK(snap_window(65537.5f, 8) == 65537.5f);  // every binary32 from 2^15 is on the grid
  CHECK(std::isnan(snap_window(NAN, 8)));
  CHECK(std::isinf(snap_window(INFINITY, 8)));
  // and the pipeline's depths follow the snapped positions
  const Scene plain = load_scene("", {"kernel=[48,40]", "viewport=[48,40]"});
  const Scene snapped = load_scene("", {"kernel=[48,40]", "viewport=[48,40]", "pipeline.snap=8"});
  const EvalPair pair{Technique::standard, "float32", DepthRange::gl};
  CHECK(reference_frame(plain, pair, {3.0, 1e-3}, 5).code_a !=
        reference_frame(snapped, pair, {3.0, 1e-3}, 5).code_a);
}

TEST_CASE("kernel codes equal the host reference for every technique and depth range",
          "[mts][reference]") {
  const Scene scene = load_scene("", {"kernel=[48,40]", "viewport=[48,40]"});
  const std::vector<Probe> probes = {
      {1.005, 3e-7}, {3.0, 1e-3}, {1000.0, 0.05}, {1048576.0, 5000.0}, {3e8, 3e8}};
  const int frames[] = {0, 37, 99};
  for (const auto& ti : technique_table()) {
    for (const DepthRange range : {DepthRange::gl, DepthRange::zero_to_one}) {
      for (const char* format : {"float32", "unorm24", "e4m12"}) {
        const EvalPair pair{ti.id, format, range};
        const size_t compared = check_codes(
            scene, pair, probes, [&](size_t k) { return frames[k % 3]; }, log_codes(ti, format));
        INFO(pair.label());
        CHECK(compared > 0);  // some pixels were real depth comparisons, not all clipped
      }
    }
  }
}

TEST_CASE("the same run gives bit-identical rows", "[mts]") {
  const Scene scene = load_scene("", {"kernel=[40,40]", "viewport=[40,40]", "frames=20"});
  const std::vector<double> z = {1.005, 100, 1e6};
  for (const Technique t : {Technique::standard, Technique::log_vertex, Technique::layered}) {
    const auto a = mts_rows(scene, t, "unorm24", DepthRange::gl, z);
    const auto b = mts_rows(scene, t, "unorm24", DepthRange::gl, z);
    for (size_t i = 0; i < a.size(); ++i) {
      INFO(info(t).name << " z = " << z[i]);
      CHECK(a[i].mts == b[i].mts);
      CHECK(a[i].lo == b[i].lo);
      CHECK(a[i].probes == b[i].probes);
      CHECK(a[i].frames == b[i].frames);
      CHECK(a[i].fragment_pairs == b[i].fragment_pairs);
      CHECK(a[i].flags() == b[i].flags());
    }
  }
}

// The raster kernel decides most pieces of a row from their ends; its probe outcomes (fight,
// clean, clipped, and the frame that decided) must be what the reference's per-pixel codes say.
TEST_CASE("probe outcomes of the raster kernel follow the reference codes", "[mts][reference]") {
  const Scene scene = load_scene("", {"kernel=[48,40]", "viewport=[48,40]", "frames=12"});
  for (const auto& [t, format, range] :
       {std::tuple{Technique::standard, "unorm24", DepthRange::gl},
        std::tuple{Technique::reversed, "float32", DepthRange::zero_to_one},
        std::tuple{Technique::linear, "unorm16", DepthRange::gl},
        std::tuple{Technique::log_vertex, "e4m12", DepthRange::zero_to_one},
        std::tuple{Technique::log_fragment, "unorm24", DepthRange::gl},
        std::tuple{Technique::log_fragment, "float32", DepthRange::gl},
        std::tuple{Technique::log_threejs, "unorm24", DepthRange::gl},
        std::tuple{Technique::log_threejs_vertex, "float32", DepthRange::gl},
        std::tuple{Technique::log_cesium, "float32", DepthRange::gl}}) {
    check_outcomes(scene, {t, format, range}, {1.005, 7.0, 3000.0, 2e6},
                   {1e-9, 1e-7, 1e-5, 1e-3, 0.1, 1.0});
  }
}

// llvmpipe's forms (every setting of the llvmpipe profile: vertex stage, log, clip stage, set-up,
// viewport, conversion): the kernel follows the reference in them too, codes and probe outcomes.
TEST_CASE("kernel codes and outcomes equal the reference under llvmpipe's forms",
          "[mts][reference][llvmpipe]") {
  std::vector<std::string> sets = {"kernel=[48,40]", "viewport=[48,40]", "frames=12"};
  for (const std::string& s : profile("llvmpipe").sets) sets.push_back(s);
  const Scene scene = load_scene("", sets);
  for (const auto& [t, format, range] :
       {std::tuple{Technique::standard, "float32", DepthRange::gl},
        std::tuple{Technique::standard, "unorm24", DepthRange::gl},
        std::tuple{Technique::reversed, "float32", DepthRange::zero_to_one},
        std::tuple{Technique::infinite, "unorm16", DepthRange::zero_to_one},
        std::tuple{Technique::reversed, "unorm32", DepthRange::zero_to_one},
        std::tuple{Technique::linear, "float32", DepthRange::gl},
        std::tuple{Technique::log_fragment, "float32", DepthRange::gl},
        std::tuple{Technique::log_vertex, "unorm24", DepthRange::gl},
        std::tuple{Technique::log_threejs, "float32", DepthRange::gl},
        std::tuple{Technique::log_threejs_vertex, "unorm24", DepthRange::gl},
        std::tuple{Technique::log_cesium, "float32", DepthRange::gl}}) {
    const EvalPair pair{t, format, range};
    INFO(pair.label());
    CHECK(check_codes(
              scene, pair, {{1.005, 3e-7}, {3.0, 1e-3}, {1000.0, 0.05}, {1048576.0, 5000.0}},
              [](size_t) { return 5; }, info(t).from == DepthFrom::vertex_log ? 1 : 0) > 0);
    check_outcomes(scene, pair, {1.005, 7.0, 3000.0, 2e6}, {1e-8, 1e-6, 1e-4, 1e-2, 1.0});
  }
}

// The envelopes' adversaries (pipeline.envelope, interface/adversary.h): the kernel follows the
// reference, codes and probe outcomes, with every freedom each takes (D3D 11.3: the reciprocal's
// faithful rounding, 0.6-code conversion, 8 sub-pixel bits; Vulkan: 1 part in 10^5 of the
// interpolated depth or 1/w, either nearest code, 4 bits), on both sides of each depth test and
// through the fragment stage's 1/w.
TEST_CASE("under each envelope's adversary the kernel follows the reference",
          "[mts][reference][envelope]") {
  for (const std::string envelope : {"d3d11", "vulkan_min"}) {
    std::vector<std::string> sets = {"kernel=[48,40]", "viewport=[48,40]", "frames=12"};
    for (const std::string& s : profile(envelope).sets) sets.push_back(s);
    const Scene scene = load_scene("", sets);
    for (const auto& [t, format, range] :
         {std::tuple{Technique::standard, "unorm24", DepthRange::gl},
          std::tuple{Technique::standard, "unorm16", DepthRange::zero_to_one},
          std::tuple{Technique::reversed, "unorm24", DepthRange::zero_to_one},
          std::tuple{Technique::reversed, "float32", DepthRange::zero_to_one},
          std::tuple{Technique::linear, "unorm24", DepthRange::gl},
          std::tuple{Technique::log_vertex, "unorm24", DepthRange::gl}}) {
      const EvalPair pair{t, format, range};
      INFO(envelope << " " << pair.label());
      CHECK(check_codes(
                scene, pair, {{1.005, 3e-7}, {3.0, 1e-3}, {1000.0, 0.05}, {1048576.0, 5000.0}},
                [](size_t k) { return static_cast<int>(3 * k); }, log_codes(info(t), format)) > 0);
      check_outcomes(scene, pair, {1.005, 7.0, 3000.0, 2e6}, {1e-8, 1e-6, 1e-4, 1e-2, 1.0});
    }
  }
}
