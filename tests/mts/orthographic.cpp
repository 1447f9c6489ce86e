// The orthographic technique (host/model/technique.h): its projection, its MTS where storage
// decides (one code of its linear map, the same at every distance) and its guaranteed MTS, and
// what it does not take yet (a tilt, the audit); its attribution's storage-limited MTS.
#include <catch2/catch.hpp>
#include <cmath>
#include <nlohmann/json.hpp>

#include "host/model/frame_setup.h"
#include "host/model/profile.h"
#include "host/mts/bound_plane.h"
#include "host/mts/mts_bound.h"
#include "host/mts/worst_case.h"
#include "tests/support/mts_fixture.h"
#include "tests/support/run_cli.h"

using namespace depthprec;
using depthprec::test::mts_rows;

TEST_CASE(
    "orthographic's projection: w is 1, the view at z is the perspective one's, depth is "
    "linear",
    "[mts][orthographic]") {
  const Scene scene = load_scene("", {"far=1000"});
  for (const DepthRange range : {DepthRange::gl, DepthRange::zero_to_one}) {
    const EvalPair ortho{Technique::orthographic, "float32", range};
    const EvalPair persp{Technique::standard, "float32", range};
    const ProbeConstants o = probe_constants(scene, ortho, 50),
                         p = probe_constants(scene, persp, 50);
    // The w row (0, 0, 0, 1); x and y scaled so the view's half-height at z = 50 is the
    // perspective view's there.
    CHECK(o.P[12] == 0.0f);
    CHECK(o.P[14] == 0.0f);
    CHECK(o.P[15] == 1.0f);
    CHECK(o.P[5] * 50 == Approx(p.P[5]).epsilon(1e-6));
    CHECK(o.P[0] * 50 == Approx(p.P[0]).epsilon(1e-6));
    // The window depth of eye distance w is (w - n) / (f - n) in both ranges.
    for (const double w : {1.0, 10.0, 500.0, 1000.0}) {
      const double ndc = o.P_full[10] * -w + o.P_full[11];
      const double d = range == DepthRange::gl ? 0.5 * ndc + 0.5 : ndc;
      CHECK(d == Approx((w - 1) / 999).margin(1e-6));
      CHECK(depth_of_distance(Technique::orthographic, 1, 1000, scene.params, w) ==
            Approx((w - 1) / 999).margin(1e-12));
    }
  }
}

TEST_CASE("orthographic unorm16 needs one code of its linear map at every distance",
          "[mts][orthographic]") {
  // A code of unorm16 over [1, 1000] spans 999 / 65535 = 0.0152 of eye distance, far more than
  // binary32 moves a depth: storage decides, and a linear map has the same spacing everywhere.
  const Scene scene = load_scene("", {"far=1000", "frames=12"});
  const double spacing = 999.0 / 65535;
  for (const MtsRow& r :
       mts_rows(scene, Technique::orthographic, "unorm16", DepthRange::gl, {2.0, 100.0, 900.0})) {
    INFO("z = " << r.z << ": mts " << r.mts);
    CHECK(r.mts >= spacing);
    CHECK(r.mts <= 1.05 * spacing);
    // Its guaranteed MTS: storage decides, and the bound is within a few per cent near the camera.
    MtsRow bounded = r;
    set_mts_bound(bounded, scene);
    CHECK(bounded.mts_bound >= r.mts);
    if (r.z == 2.0) CHECK(bounded.mts_bound <= 1.1 * r.mts);
  }
}

TEST_CASE("orthographic's guaranteed MTS is at or above its sampled worst case under each profile",
          "[mts][orthographic][bound]") {
  int bounded = 0;
  for (const std::string prof : {"ideal", "llvmpipe", "softpipe"}) {
    std::vector<std::string> sets = profile(prof).sets;
    sets.insert(sets.end(), {"far=1000", "kernel=[32,32]", "viewport=[32,32]", "frames=16",
                             "worst_case.round_size=32", "worst_case.max_rounds=2",
                             "distances=[1.5,3,40,300,950]"});
    const Scene s = load_scene("", sets);
    for (const std::string f : {"float32", "unorm24", "unorm16"}) {
      const EvalPair pair{Technique::orthographic, f, DepthRange::gl};
      PairSource<ProbeEvaluator, MtsEvaluator> source(depthprec::test::runtime(), pair);
      for (const MtsRow& r : search_sampled(source, s, pair, s.distances, {}, {})) {
        INFO(prof << " " << f << " z = " << r.z << ": mts " << r.mts << ", mts_bound "
                  << r.mts_bound << " (" << r.bound_note << ")");
        if (r.verdict() != Verdict::resolved || std::isnan(r.mts_bound)) continue;
        ++bounded;
        CHECK(r.mts_bound >= r.mts);
        CHECK(r.mts_bound >= r.fight_max);
      }
    }
  }
  CHECK(bounded >= 30);
}

TEST_CASE("orthographic's storage-limited MTS is one code of its linear map", "[attribution]") {
  // Attribution's binary64 pipeline with parallel rays: storage alone needs one code, 999 / 65535
  // in unorm16 and 999 / (2^24 - 1) in unorm24 over [1, 1000], at every distance.
  const auto r = depthprec::test::run_cli(
      "mts -t orthographic -f unorm16,unorm24 --far 1000 --distances 2,100,900 --attribute "
      "--frames 12 -q --no-timing --format-out json");
  REQUIRE(r.exit_code == 0);
  const auto j = nlohmann::json::parse(r.output);
  REQUIRE(j["rows"].size() == 6);
  for (const auto& row : j["rows"]) {
    INFO(row["format"] << " z = " << row["z"]);
    const double code = 999.0 / (row["format"] == "unorm16" ? 65535.0 : 16777215.0);
    CHECK(row["storage_mts"].get<double>() == Approx(code).epsilon(0.01));
  }
}

TEST_CASE("orthographic refuses what it does not take yet, naming it", "[mts][orthographic][cli]") {
  using depthprec::test::run_cli;
  const auto tilt = run_cli("bias -t orthographic -f unorm24 --distances 10 --tilt 30 -q");
  CHECK(tilt.exit_code == 3);
  CHECK(tilt.output.find("orthographic takes no tilt") != std::string::npos);
  const auto audit = run_cli("audit '" + std::string(DEPTHPREC_SOURCE_DIR) +
                             "/data/audit/decal_wall.gltf' -t orthographic -q");
  CHECK(audit.exit_code == 3);
  CHECK(audit.output.find("perspective") != std::string::npos);
}

TEST_CASE("orthographic's clip stage leaves w at 1: no error term of its bound is negative",
          "[mts][bound][orthographic]") {
  // The clip stage's w error was taken at the eye distance (33 at z = 2.6e8), which orthographic's
  // w = 1 cannot carry: the reciprocal's bound went negative and the clip term with it, and the
  // bound fell to 1.5e-8 where the search's MTS is 15270 (found over random scenes).
  const Scene s =
      load_scene("", {"kernel=[24,24]", "viewport=[24,24]", "near=0.05", "far=1e9", "fov_y_deg=90",
                      "rotation_range_deg=1.14", "world_position=[2000000,-1000000,500000]",
                      "pipeline.transform=relative_to_eye"});
  const EvalPair pair{Technique::orthographic, "unorm16", DepthRange::gl};
  const double z = 264795741.44542086;
  const bound::RowModel m = bound::row_model(s, pair, z);
  for (const double sep : {1e-3, 15000.0}) {
    const bound::PlaneGeometry g = bound::plane_geometry(m, bound::geometry_distance(m, z + sep));
    const bound::DepthError e = bound::depth_error(m, g);
    for (int t = 0; t < bound::kTermCount; ++t) {
      INFO(bound::term_name(t) << " at s = " << sep);
      CHECK(e.term[t] >= 0);
    }
  }
  CHECK(mts_bound(s, pair, z).s > 15270);
}
