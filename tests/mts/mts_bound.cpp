// The guaranteed MTS (host/mts/mts_bound.h, docs/bound.md): never below the
// sampled worst case, never a fight at or above it in a dense scan of the rotation cube under the
// ideal and llvmpipe profiles (each under its own bound model), the models ordered as their
// freedoms are, and a row the model cannot bound says why.
#include "host/mts/mts_bound.h"

#include <fmt/format.h>

#include <catch2/catch.hpp>
#include <cmath>
#include <nlohmann/json.hpp>
#include <random>

#include "host/model/frame_setup.h"
#include "host/mts/refinement.h"
#include "host/mts/worst_case.h"
#include "tests/support/bound_scan_rows.h"
#include "tests/support/mts_fixture.h"
#include "tests/support/run_cli.h"

using namespace depthprec;
using namespace depthprec::test;

namespace {

// Orientations drawn uniformly from the rotation cube (each axis within +-rotation_range_deg).
std::vector<Angles> cube_sample(const Scene& s, size_t n, uint64_t seed) {
  std::mt19937_64 rng(seed);
  const double r = s.rotation_range_deg * M_PI / 180;
  std::uniform_real_distribution<double> u(-r, r);
  std::vector<Angles> out(n);
  for (auto& a : out) a = {u(rng), u(rng), u(rng)};
  return out;
}

// Whether any of the orientations fights (or is non-finite) at separation s of pair at z.
bool any_fight(Scene s, const EvalPair& pair, double z, const std::vector<double>& seps,
               std::vector<Angles> angles) {
  s.frames = static_cast<int>(angles.size());
  Orientations o;
  o.at[z] = std::move(angles);
  MtsEvaluator ev(runtime(), s, pair, o);
  std::vector<Probe> probes;
  for (const double sep : seps) probes.push_back({z, sep});
  for (const ProbeResult& r : ev.run(probes))
    if (r.outcome == Outcome::fight || r.outcome == Outcome::non_finite) return true;
  return false;
}

}  // namespace

TEST_CASE("the guaranteed MTS is at or above the sampled worst case on every resolved row",
          "[mts][bound]") {
  int resolved = 0, bounded = 0;
  for (const std::string prof :
       {"ideal", "llvmpipe", "softpipe", "gles_mediump", "gles2_highp", "d3d11", "vulkan_min"}) {
    std::vector<std::string> sets = profile(prof).sets;
    sets.insert(sets.end(),
                {"kernel=[32,32]", "viewport=[32,32]", "frames=16", "worst_case.round_size=32",
                 "worst_case.max_rounds=2", "distances=[1.005,3,100,5000,300000,2e7]"});
    const Scene s = load_scene("", sets);
    for (const Technique t :
         {Technique::standard, Technique::reversed, Technique::reversed_infinite,
          Technique::log_fragment, Technique::linear, Technique::w_buffer, Technique::layered})
      for (const std::string f : {"float32", "unorm24", "unorm16"}) {
        // mediump's vertex stage is the same for every fragment stage and format: two pairs,
        // and two whose fragment shader writes depth in mediump
        if ((prof == "gles_mediump" || prof == "gles2_highp") &&
            !(t == Technique::standard && f == "float32") &&
            !(t == Technique::reversed && f == "unorm24") &&
            !(t == Technique::log_fragment && f == "float32") &&
            !(t == Technique::linear && f == "unorm24"))
          continue;
        // an envelope's adversary (each row under the envelope's own bound model, which the
        // profile sets): its freedoms act on every technique alike, its codes on unorm alone
        if ((prof == "d3d11" || prof == "vulkan_min") && f == "unorm16" &&
            t != Technique::standard && t != Technique::log_fragment)
          continue;
        const EvalPair pair{t, f, s.range_for(t)};
        PairSource<ProbeEvaluator, MtsEvaluator> source(runtime(), pair);
        for (const MtsRow& r : search_sampled(source, s, pair, s.distances, {}, {})) {
          INFO(fmt::format("{} {} z = {}: mts {}, mts_bound {} ({})", prof, pair.label(), r.z,
                           r.mts, r.mts_bound, r.bound_note));
          if (r.verdict() != Verdict::resolved) {
            CHECK(std::isnan(r.mts_bound));
            continue;
          }
          ++resolved;
          if (std::isnan(r.mts_bound)) continue;
          ++bounded;
          CHECK(r.mts_bound >= r.mts);
          CHECK(r.mts_bound >= r.fight_max);
          CHECK(!r.bound_note.empty());
        }
      }
  }
  // Rows the model leaves without a number are the exception (A's fragments near a clip plane).
  CHECK(bounded >= resolved * 9 / 10);
}

TEST_CASE(
    "no orientation of a dense scan fights at or above the guaranteed MTS, ideal and llvmpipe",
    "[mts][bound]") {
  // A dozen rows of the default scene (docs/mts.md has the scan over 10^5 orientations,
  // bench/bound_scan.sh); here 1,500 uniform orientations per row and profile, and the cube's
  // corners.
  const std::vector<std::pair<EvalPair, double>>& rows = test::bound_scan_rows();
  // softpipe is left out: its planes meet the clip stage's thinnest fan triangles, which the
  // model does not cover yet (docs/bound.md, "Not yet covered"; bench/bound_scan.sh finds them).
  for (const std::string prof : {"ideal", "llvmpipe"}) {
    std::vector<std::string> sets = profile(prof).sets;
    sets.push_back("bound_model=" + prof);  // the profile's own model, the tightest
    const Scene s = load_scene("", sets);
    uint64_t seed = 1;
    for (const auto& [pair, z] : rows) {
      const MtsBound b = mts_bound(s, pair, z);
      INFO(fmt::format("{} {} z = {}: mts_bound {} ({})", prof, pair.label(), z, b.s,
                       b.s == b.s ? b.dominant : b.why));
      REQUIRE(std::isfinite(b.s));
      std::vector<Angles> angles = cube_sample(s, 1500, seed++);
      const double r = s.rotation_range_deg * M_PI / 180;
      for (int c = 0; c < 8; ++c)
        angles.push_back({c & 1 ? r : -r, c & 2 ? r : -r, c & 4 ? r : -r});
      // at the bound and above it, where the error bounds step up at binade edges
      CHECK(!any_fight(s, pair, z, {b.s, 1.3 * b.s, 1.9 * b.s, 3.7 * b.s}, angles));
    }
  }
}

TEST_CASE("the guaranteed MTS holds at every separation above it, not only at its doublings",
          "[mts][bound]") {
  // The error bounds step up where a magnitude of plane B enters a higher binade: at z = 2^20,
  // standard/unorm24's check fails from 3.2394e7 to 3.2571e7, 1.89 times the bound a search that
  // rechecked only the doublings above it gave (1.71e7). Each pair at six distances under four
  // models: 500 separations evenly over [b, 2b], 300 geometrically over [2b, 64b].
  int rows = 0;
  for (const std::string model : {"binary32", "ideal", "softpipe", "d3d11"}) {
    const Scene s = load_scene("", {"bound_model=" + model});
    for (const EvalPair& pair : s.evaluate)
      for (const double z : {1.005, 64.0, 4096.0, 262144.0, 1048576.0, 16777216.0}) {
        const MtsBound b = mts_bound(s, pair, z);
        if (!std::isfinite(b.s)) continue;
        ++rows;
        int fails = 0;
        double first = 0;
        for (int k = 0; k <= 800; ++k) {
          const double t =
              k <= 500 ? b.s * (1 + k / 500.0) : 2 * b.s * std::pow(32.0, (k - 500) / 300.0);
          if (t > s.max_separation_factor * z) break;
          if (!bound_holds(s, pair, z, t) && fails++ == 0) first = t;
        }
        INFO(model << " " << pair.label() << " z = " << z << ": mts_bound " << b.s
                   << ", first failure " << first);
        CHECK(fails == 0);
      }
  }
  CHECK(rows > 250);
}

TEST_CASE("a row the bound model cannot bound says why, and its table cell is empty",
          "[mts][bound][cli]") {
  const MtsBound b =
      mts_bound(load_scene("", {"pipeline.compose=premultiplied", "world_position=[1e5,0,0]"}),
                {Technique::standard, "unorm24", DepthRange::gl}, 512);
  CHECK(std::isnan(b.s));
  CHECK_THAT(b.why, Catch::Contains("premultiplied"));
  // an API's envelope bounds the depth formats the API has: llvmpipe's 31-bit unorm32 lies
  // outside D3D 11's 0.6-ulp rule, and D3D has no such format
  // (bench/results/envelope_vs_rendered.txt)
  for (const std::string envelope : {"d3d11", "vulkan_min"}) {
    const MtsBound u32 = mts_bound(load_scene("", {"bound_model=" + envelope}),
                                   {Technique::reversed, "unorm32", DepthRange::zero_to_one}, 512);
    CHECK(std::isnan(u32.s));
    CHECK_THAT(u32.why, Catch::Contains("has no unorm32 depth format"));
    CHECK(std::isfinite(mts_bound(load_scene("", {"bound_model=" + envelope}),
                                  {Technique::reversed, "unorm24", DepthRange::zero_to_one}, 512)
                            .s));
  }
  const auto r = run_cli(
      "mts -t standard -f unorm24 --distances 512 --format-out csv --no-timing --set "
      "sampling=paper --set kernel=[16,16] --set viewport=[16,16] --set frames=4 --set "
      "pipeline.compose=premultiplied --set world_position=[1e5,0,0]");
  REQUIRE(r.exit_code == 0);
  CHECK_THAT(r.output, Catch::Contains(",binary32,no bound model for compose premultiplied"));
}

TEST_CASE("a bound model that allows more never bounds lower", "[mts][bound]") {
  // binary32 holds every profile's choices, d3d11 and vulkan_min more still.
  const std::vector<std::pair<EvalPair, double>> rows = {
      {{Technique::standard, "unorm24", DepthRange::gl}, 512},
      {{Technique::reversed, "float32", DepthRange::zero_to_one}, 4096},
      {{Technique::log_fragment, "float32", DepthRange::gl}, 64},
      {{Technique::linear, "unorm16", DepthRange::gl}, 1000}};
  const auto at = [](const std::string& model, const EvalPair& pair, double z) {
    return mts_bound(load_scene("", {"bound_model=" + model}), pair, z).s;
  };
  for (const auto& [pair, z] : rows) {
    INFO(pair.label() << " z = " << z);
    const double all = at("binary32", pair, z);
    for (const std::string prof : {"ideal", "llvmpipe", "softpipe"})
      CHECK(at(prof, pair, z) <= all);
    CHECK(at("ideal", pair, z) < all);
    CHECK(at("vulkan_min", pair, z) >= all);
    // mediump: larger, or none where plane B would pass 2^14 before the bound holds (linear
    // unorm16 at 1000 needs 15,432)
    const double mediump = at("gles_mediump", pair, z);
    CHECK((std::isnan(mediump) || mediump > all));
  }
  // mediump shaders far from the origin along the view: binary16's spacing at 3000 (2) moves the
  // vertices, which camera-relative rendering avoids; past 2^14 nothing can be drawn.
  const EvalPair standard{Technique::standard, "unorm24", DepthRange::gl};
  const auto far_out = [&](const std::string& transform) {
    return mts_bound(load_scene("", {"bound_model=gles_mediump", "world_position=[0,0,3000]",
                                     "pipeline.transform=" + transform}),
                     standard, 100)
        .s;
  };
  CHECK(far_out("absolute") > 2 * far_out("camera_relative"));
  const MtsBound beyond = mts_bound(load_scene("", {"bound_model=gles_mediump"}), standard, 20000);
  CHECK(std::isnan(beyond.s));
  CHECK_THAT(beyond.why, Catch::Contains("shaders' range"));
  CHECK_THROWS_WITH(load_scene("", {"bound_model=gpu"}),
                    Catch::Contains("binary32, ideal, llvmpipe, softpipe, d3d11, vulkan_min, "
                                    "gles_mediump"));
}

TEST_CASE("random scenes under ideal and llvmpipe: no fight at or above the guaranteed MTS",
          "[mts][bound][property]") {
  // Wider than the default scene: fields of view to 90 degrees, rotations to 20, margins to
  // 1.5, viewports of 16 to 64 pixels, the kernel filling them, any distance from 2^0.5 to 2^20;
  // 1,500 orientations each and the cube's corners. (40 + 100 such scenes at 3,000 orientations
  // found no fight while this was written.)
  std::mt19937 rng(7);
  const auto pick = [&rng](const auto& v) {
    return v[std::uniform_int_distribution<size_t>(0, v.size() - 1)(rng)];
  };
  int scenes = 0;
  for (int k = 0; k < 24; ++k) {
    const int vw = std::uniform_int_distribution<int>(16, 64)(rng);
    const double fov = pick(std::vector<double>{10, 30, 60, 90});
    const double rot = pick(std::vector<double>{0.5, 1, 5, 20});
    const double margin = pick(std::vector<double>{1.05, 1.1, 1.5});
    const std::string prof = pick(std::vector<std::string>{"ideal", "llvmpipe"});
    const Technique t = pick(std::vector<Technique>{
        Technique::standard, Technique::reversed, Technique::reversed_infinite,
        Technique::log_fragment, Technique::linear, Technique::layered, Technique::log_vertex,
        Technique::inverse_w, Technique::w_buffer});
    const std::string f = pick(std::vector<std::string>{"float32", "unorm24", "unorm16"});
    const double z = std::pow(2.0, std::uniform_real_distribution<double>(0.5, 20)(rng));
    std::vector<std::string> sets = profile(prof).sets;
    for (const std::string& s :
         {fmt::format("viewport=[{},{}]", vw, vw), fmt::format("kernel=[{},{}]", vw, vw),
          fmt::format("fov_y_deg={}", fov), fmt::format("rotation_range_deg={}", rot),
          fmt::format("plane_margin={}", margin), "bound_model=" + prof})
      sets.push_back(s);
    const Scene s = load_scene("", sets);
    const EvalPair pair{t, f, s.range_for(t)};
    const MtsBound b = mts_bound(s, pair, z);
    INFO(fmt::format("{} {} z = {} fov {} rotation {} margin {} viewport {}: mts_bound {} ({})",
                     prof, pair.label(), z, fov, rot, margin, vw, b.s,
                     b.s == b.s ? b.dominant : b.why));
    if (!std::isfinite(b.s)) continue;  // beyond far, A clipped, ...: nothing to check
    ++scenes;
    std::vector<Angles> angles = cube_sample(s, 1500, 100 + k);
    const double r = s.rotation_range_deg * M_PI / 180;
    for (int c = 0; c < 8; ++c) angles.push_back({c & 1 ? r : -r, c & 2 ? r : -r, c & 4 ? r : -r});
    CHECK(!any_fight(s, pair, z, {b.s, 1.9 * b.s}, angles));
  }
  CHECK(scenes >= 16);
}

// Vulkan states its interpolation precision loosely (1 part in 10^5); a user who measured a device
// sets interpolation_tolerance, and both the envelope's bound and its adversary follow it.
TEST_CASE("the interpolation tolerance is a setting the bound and the adversary follow",
          "[mts][bound][envelope]") {
  std::vector<std::pair<double, double>> at;  // (mts, mts_bound) per tolerance, largest first
  for (const std::string tolerance : {"model", "1e-6", "0"}) {
    const auto r = run_cli(
        "mts --profile vulkan_min -t standard -f unorm24 --distances 100 --set sampling=paper "
        "--set frames=8 --format-out json --no-timing --set interpolation_tolerance=" +
        tolerance);
    REQUIRE(r.exit_code == 0);
    const auto row = nlohmann::json::parse(r.output)["rows"].at(0);
    INFO(tolerance << ": " << row.dump());
    CHECK(row["mts_bound"].get<double>() >= row["mts"].get<double>());
    at.emplace_back(row["mts"].get<double>(), row["mts_bound"].get<double>());
  }
  CHECK(at[0].first > 5 * at[1].first);
  CHECK(at[1].first > at[2].first);
  CHECK(at[0].second > 5 * at[1].second);
  CHECK(at[1].second > at[2].second);
}

TEST_CASE("a float format that flushes denormals gets no bound where its depths are subnormal",
          "[mts][bound]") {
  // reversed/float16 at z = 32768 writes depths near 3.05e-5, below float16's smallest normal
  // (6.1e-5): flushed, both planes store code 0 at every pixel, whatever the separation.
  const EvalPair pair{Technique::reversed, "float16", DepthRange::zero_to_one};
  const MtsBound kept = mts_bound(load_scene("", {"pipeline.denormals=keep"}), pair, 32768);
  const MtsBound flushed = mts_bound(load_scene("", {"pipeline.denormals=flush"}), pair, 32768);
  CHECK(std::isfinite(kept.s));
  CHECK(std::isinf(flushed.s));
}

TEST_CASE("under binary64 matrices the bound holds at the binary32 distances the GPU draws",
          "[mts][bound]") {
  // The model-view reaches the GPU in binary32 either way, so the planes lie at fl32(z) and
  // fl32(z + s): at z = 3, standard/float32's bound was 5.8375e-6 where the GPU's planes are
  // 5.722e-6 apart, and the model's own check fails there.
  const Scene doubles = load_scene("", {"pipeline.matrix_precision=double"});
  const Scene floats = load_scene("", {});
  int checked = 0;
  for (const EvalPair& pair : doubles.evaluate)
    for (const double z : {1.005, 3.0, 5.0, 100.3, 4097.0}) {
      const MtsBound b = mts_bound(doubles, pair, z);
      if (!std::isfinite(b.s)) continue;
      ++checked;
      INFO(pair.label() << " z = " << z << ": mts_bound " << b.s);
      CHECK(bound_holds(floats, pair, z, b.s));
    }
  CHECK(checked > 50);
}
