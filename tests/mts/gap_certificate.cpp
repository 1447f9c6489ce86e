// The gap certificate (kernels/mts/bounds.cl plane_gap_range, frag_gap_clear) decides bands clean
// from the distance between the planes and a rounding-error bound. Its margin is thinnest just
// above the MTS, so that is where it is checked: from just below the MTS to 16x above it, every
// probe result must be what the plain rows give, and the certificate must decide bands the code
// bounds do not. Checked by temporary edits of kernels/mts.cl: with no rounding-error bound (E = 0,
// err = 0, and the fragment test allowed a code step short) 168 assertions fail; a bound 8x too
// small still passes here, so that part rests on the derivation in the kernel's comments.
#include <catch2/catch.hpp>
#include <string>
#include <tuple>

#include "tests/support/mts_fixture.h"

using namespace depthprec;
using namespace depthprec::test;

TEST_CASE("the gap certificate changes no probe result from just below the MTS upwards",
          "[mts][bounds]") {
  // and under llvmpipe's profile: its plane form and unorm conversions, without its clip stage and
  // with it (whose slivers withhold the coverage certificate from the bands near them: in this
  // kernel of two bands, from many); and softpipe's truncating unorm conversion, whose code width
  // is 2 for unorm24 (its quad-stepped planes have no certificate at all)
  const std::string profile_name =
      GENERATE("ideal", "llvmpipe without clip", "llvmpipe", "softpipe conversion");
  const bool llvmpipe = profile_name.rfind("llvmpipe", 0) == 0, clip = profile_name == "llvmpipe";
  std::vector<std::string> sets = {"kernel=[64,64]", "viewport=[64,64]", "frames=16"};
  if (llvmpipe)
    for (const std::string& s : llvmpipe_sets(clip)) sets.push_back(s);
  const bool softpipe = profile_name == "softpipe conversion";
  if (softpipe) sets.push_back("pipeline.conversion=softpipe");
  const Scene scene = load_scene("", sets);
  for (const auto& [t, format, range] :
       {std::tuple{Technique::standard, "unorm24", DepthRange::gl},
        std::tuple{Technique::reversed, "float32", DepthRange::zero_to_one},
        std::tuple{Technique::log_fragment, "unorm24", DepthRange::gl},
        std::tuple{Technique::log_threejs, "unorm24", DepthRange::gl},
        std::tuple{Technique::log_cesium, "unorm24", DepthRange::gl},
        std::tuple{Technique::linear, "unorm24", DepthRange::gl}}) {
    const EvalPair pair{t, format, range};
    const std::vector<MtsRow> rows = mts_rows(scene, t, format, range, {1.005, 2.0, 64.0, 4096.0});
    std::vector<Probe> near, above;
    for (const MtsRow& row : rows) {
      REQUIRE(row.verdict() == Verdict::resolved);
      for (const double f : {0.9, 0.97, 0.99, 1.0, 1.01, 1.03, 1.1, 1.3})
        near.push_back({row.z, row.mts * f});
      for (const double f : {2.0, 3.0, 4.0, 6.0, 8.0, 16.0}) above.push_back({row.z, row.mts * f});
    }
    MtsEvaluator with(runtime(), scene, pair), without(runtime(), scene, pair, false);
    for (const auto* probes : {&near, &above}) {
      const uint64_t decided_before = with.pairs_decided_by_bounds(),
                     pairs_before = with.fragment_pairs();
      const auto a = with.run(*probes), b = without.run(*probes);
      for (size_t k = 0; k < probes->size(); ++k) {
        INFO(pair.label() << " " << profile_name << " z = " << (*probes)[k].z
                          << " s = " << (*probes)[k].s);
        CHECK(to_string(a[k].outcome) == std::string(to_string(b[k].outcome)));
        CHECK(a[k].frames == b[k].frames);
        CHECK(a[k].any_clipped == b[k].any_clipped);
        CHECK(a[k].any_uncovered == b[k].any_uncovered);
      }
      if (probes == &above) {
        // the code bounds alone decide next to nothing at these distances so close to the MTS
        const uint64_t decided = with.pairs_decided_by_bounds() - decided_before;
        const uint64_t pairs = with.fragment_pairs() - pairs_before;
        INFO(pair.label() << " " << profile_name << ": " << decided << " of " << pairs
                          << " pairs decided without rasterising above the MTS");
        // (a coarser code width leaves the certificate less room: softpipe's unorm24 48 %)
        CHECK(decided > (clip ? pairs / 8 : softpipe ? pairs / 3 : pairs / 2));
      }
    }
  }
}
