// The evaluator's certified shortcuts: mts_frame_bounds decides bands of kernel rows clean from
// code bounds before any row is rasterised, and a row takes plane B's coverage from plane A's
// when B lies within A's coverage margin. They may only save work: every probe result must be
// what the plain rows give.
#include <catch2/catch.hpp>
#include <cmath>
#include <string>
#include <tuple>

#include "host/model/profile.h"
#include "tests/support/mts_fixture.h"

using namespace depthprec;
using namespace depthprec::test;

namespace {

// Probes from s = z, where whole frames are decided from bounds, down past the MTS.
std::vector<Probe> descent() {
  std::vector<Probe> probes;
  for (double z : {1.005, 30.0, 3000.0, 2e6})
    for (double f = 1.0; f > 1e-7; f /= 8) probes.push_back({z, z * f});
  return probes;
}

}  // namespace

TEST_CASE("bands decided from code bounds and coverage taken from plane A change no probe result",
          "[mts][bounds]") {
  // margin 0.9: the planes leave the kernel's border uncovered, so no band may be decided (a square
  // viewport: the plane is sized to the vertical field of view)
  // and under llvmpipe's forms, which the bounds take as they are, without its clip stage and with
  // it (its fans' slivers cost the certificate the bands near them), and with vertices snapped to
  // 1/16 pixel
  for (const std::string margin : {"1.1", "0.9", "1.1 llvmpipe", "1.1 llvmpipe clip", "1.1 snap"}) {
    const bool llvmpipe = margin.find("llvmpipe") != std::string::npos;
    const bool clip = margin.find("clip") != std::string::npos;
    std::vector<std::string> sets = {"kernel=[48,48]", "viewport=[48,48]", "frames=12",
                                     "plane_margin=" + margin.substr(0, 3)};
    if (margin.find("snap") != std::string::npos) sets.push_back("pipeline.snap=4");
    if (llvmpipe)
      for (const std::string& s : llvmpipe_sets(clip)) sets.push_back(s);
    const Scene scene = load_scene("", sets);
    for (const auto& [t, format, range] :
         {std::tuple{Technique::standard, "unorm24", DepthRange::gl},
          std::tuple{Technique::reversed, "float32", DepthRange::zero_to_one},
          std::tuple{Technique::log_fragment, "unorm24", DepthRange::gl},
          std::tuple{Technique::log_threejs, "float32", DepthRange::gl},
          std::tuple{Technique::log_threejs_vertex, "unorm24", DepthRange::zero_to_one},
          std::tuple{Technique::log_cesium, "unorm24", DepthRange::gl},
          std::tuple{Technique::linear, "unorm16", DepthRange::gl},
          std::tuple{Technique::layered, "e4m12", DepthRange::gl}}) {
      const EvalPair pair{t, format, range};
      MtsEvaluator with(runtime(), scene, pair), without(runtime(), scene, pair, false);
      const std::vector<Probe> probes = descent();
      const auto a = with.run(probes), b = without.run(probes);
      for (size_t k = 0; k < probes.size(); ++k) {
        INFO(pair.label() << " margin " << margin << " z = " << probes[k].z
                          << " s = " << probes[k].s);
        CHECK(to_string(a[k].outcome) == std::string(to_string(b[k].outcome)));
        CHECK(a[k].frames == b[k].frames);
        CHECK(a[k].fragment_pairs == b[k].fragment_pairs);
        CHECK(a[k].any_clipped == b[k].any_clipped);
        CHECK(a[k].any_non_finite == b[k].any_non_finite);
        CHECK(a[k].any_uncovered == b[k].any_uncovered);
        if (margin == "0.9") CHECK(a[k].any_uncovered);
      }
      INFO(pair.label() << " margin " << margin);
      CHECK(without.pairs_decided_by_bounds() == 0);
      CHECK(without.rows_with_coverage_of_a() == 0);
      CHECK(with.rows_with_coverage_of_a() <= with.rows_rasterised());
      if (margin != "0.9") {
        CHECK(with.pairs_decided_by_bounds() > 0);
        CHECK(with.rows_with_coverage_of_a() > 0);
      } else {  // neither certificate holds when the planes leave pixels uncovered
        CHECK(with.pairs_decided_by_bounds() == 0);
        CHECK(with.rows_with_coverage_of_a() == 0);
      }
    }
  }
}

TEST_CASE("plane B's coverage is taken from plane A's only where it is the same", "[mts][bounds]") {
  // Plane B is plane A scaled with its distance, so its window triangles match A's up to rounding
  // and its coverage differs from A's only at pixel centres within ~1e-5 px of an edge: rare (17
  // rows in 1.2 million here), so the paper's full kernel, every frame, 20 distances and
  // separations of every size, to meet some. A margin 30 times too large already fails this.
  // Under llvmpipe's profile its clip stage cuts every row's end triangles into fans, whose new
  // vertices and records the margin must cover too.
  for (const auto& [t, range, profile_name] :
       {std::tuple{Technique::standard, DepthRange::gl, "ideal"},
        std::tuple{Technique::reversed, DepthRange::zero_to_one, "ideal"},
        std::tuple{Technique::standard, DepthRange::gl, "llvmpipe"}}) {
    const Scene scene = load_scene("", profile(profile_name).sets);
    const EvalPair pair{t, "float32", range};
    MtsEvaluator ev(runtime(), scene, pair, true, MtsEvaluator::Kernels::with_tests);
    std::vector<Probe> probes;
    for (int i = 0; i < 20; ++i)
      for (double f : {1.0, 1e-3, 1e-6})
        probes.push_back({1.005 * std::pow(2.3, i), 1.005 * std::pow(2.3, i) * f});
    const CoverageAudit a = ev.audit_coverage(probes);
    INFO(pair.label() << " " << profile_name << ": " << a.rows << " rows, B differs in "
                      << a.b_differs << ", certified " << a.certified << ", from the reference "
                      << a.from_reference);
    CHECK(a.certified_but_differs == 0);
    // Rows at the 19 distances after the first take its segments where they are provably theirs
    CHECK(a.a_differs == 0);
    CHECK(a.from_reference > a.rows / 2);
    CHECK(a.b_differs > 0);           // the audit meets rows where the shortcut must refuse
    CHECK(a.certified > a.rows / 2);  // and the shortcut still serves most rows
  }
}

TEST_CASE("a vertex near a pixel centre takes only its own row out of its band's verdict",
          "[mts][bounds]") {
  // The plane faces the camera (no rotation) and the viewport is 201 pixels wide, so the grid's
  // centre vertex projects onto the centre of pixel (100, 100) and no other vertex comes near a
  // pixel centre (the grid's spacing, 201 * 1.1 / 4 = 55.3 px, leaves the rest 0.2-0.3 px off).
  // At s = z every band is clean from its code bounds; row 100 alone may have a pixel with two
  // owners or none, so it is rasterised, and the other 31 rows of its band are not.
  const Scene scene = load_scene(
      "", {"kernel=[201,201]", "viewport=[201,201]", "frames=1", "rotation_range_deg=0"});
  const EvalPair pair{Technique::standard, "unorm24", DepthRange::gl};
  MtsEvaluator with(runtime(), scene, pair), without(runtime(), scene, pair, false);
  const std::vector<Probe> probes = {{1.005, 1.005}};
  const auto a = with.run(probes), b = without.run(probes);
  CHECK(to_string(a[0].outcome) == std::string(to_string(b[0].outcome)));
  CHECK(a[0].outcome == Outcome::clean);
  CHECK(a[0].fragment_pairs == b[0].fragment_pairs);
  CHECK(with.rows_rasterised() == 1);
  CHECK(with.pairs_decided_by_bounds() == 200u * 201u);
}
