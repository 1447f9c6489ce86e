// The engines' log depths (docs/spec.md 3: log_threejs, log_threejs_vertex, log_cesium): every
// fragment the kernel stores against the technique's closed form, and their MTS beside Gilg's log
// of the same curve.
#include <catch2/catch.hpp>
#include <cmath>

#include "host/model/resolve.h"
#include "tests/support/mts_fixture.h"

using namespace depthprec;
using namespace depthprec::test;

namespace {

// A plane facing the eye (no rotation in any frame): every fragment of plane A at z has the exact
// eye distance w = z (z a binary32, so the matrices hold it exactly), and the closed form gives
// one depth D(z) for all of them.
Scene facing_scene() {
  return load_scene("", {"kernel=[40,40]", "viewport=[40,40]", "rotation_range_deg=0"});
}

// How far the kernel's binary32 depth may lie from D(z), and why: the fragment forms compute d from
// the fragment's w through a log2 (<= 3 ulp in OpenCL), a product with a binary32 constant and
// the interpolated 1/w (a few u relative in w, which the log shrinks), within 8 u relative; the
// vertex form writes z_ndc in [-1, 1], whose errors are absolute (u each for the log's product,
// the - 1, the product with w and the divide), and the window transform 0.5 z + 0.5 keeps them,
// so 8 u absolute.
double depth_tolerance(const TechniqueInfo& ti, double depth) {
  const double u = 0x1.0p-24;
  return ti.from == DepthFrom::vertex_log ? 8 * u : 8 * u * depth;
}

}  // namespace

TEST_CASE("the engines' log depths store their closed form at every fragment",
          "[mts][reference][engine_log]") {
  const Scene scene = facing_scene();
  for (const Technique t :
       {Technique::log_threejs, Technique::log_threejs_vertex, Technique::log_cesium}) {
    const TechniqueInfo& ti = info(t);
    for (const DepthRange range : {DepthRange::gl, DepthRange::zero_to_one}) {
      for (const char* format : {"float32", "unorm24"}) {
        const EvalPair pair{t, format, range};
        const StorageFormat f = scene.storage_format(pair);
        MtsEvaluator ev(runtime(), scene, pair, true, MtsEvaluator::Kernels::with_tests);
        for (const double z : {2.0, 100.0, 12345.0, 1048576.0, 3e8}) {
          const double w = static_cast<float>(z);
          const double exact = depth_of_distance(t, scene.near, scene.far, scene.params, w);
          const double tolerance = depth_tolerance(ti, exact);
          const FrameCodes k = ev.codes({z, z}, 3);
          size_t stored = 0, worst_i = 0;
          double worst = 0;
          for (size_t i = 0; i < k.code_a.size(); ++i) {
            if (k.status_a[i] != 0) continue;
            ++stored;
            const double err = std::fabs(f.decode(k.code_a[i]) - exact);
            if (err > worst) {
              worst = err;
              worst_i = i;
            }
          }
          // A stored code stands for its depth to within its own spacing (half of it rounding,
          // all of it truncating: the larger of its neighbours' distances bounds both).
          const uint32_t c = k.code_a[worst_i];
          const double spacing = std::max(c > 0 ? f.decode(c) - f.decode(c - 1) : 0.0,
                                          c < f.max_code() ? f.decode(c + 1) - f.decode(c) : 0.0);
          INFO(pair.label() << " z = " << z << " D(z) = " << exact << " worst error " << worst
                            << " tolerance " << tolerance << " + code spacing " << spacing);
          CHECK(stored == k.code_a.size());  // the whole kernel is covered and unclipped
          CHECK(worst <= tolerance + spacing);
        }
      }
    }
  }
}

// The three curves are Gilg's log with k = 1 (three.js: log2(1 + w) / log2(1 + f) is ln(1 + w) /
// ln(1 + f)) or, for Cesium with near 1, log2(w) / log2(f), within 1 % of it from z = 100 on: one
// code spans the same eye distance in all of them, so their MTS may differ only by the arithmetic
// (log2 and a product where Gilg has ln and a division), which moves it by a few ulp of depth: well
// inside a factor of 2, and far from the factor 10^4 and more that separates a log curve from
// standard's at z = 10^4.
TEST_CASE("the engines' log depths resolve as Gilg's log of the same curve", "[mts][engine_log]") {
  const Scene scene = load_scene("", {"near=1", "far=1e9", "log_k=1"});
  const std::vector<double> zs = {100, 1e4};
  for (const auto& [engine, gilg, format] :
       {std::tuple{Technique::log_threejs, Technique::log_fragment, "float32"},
        std::tuple{Technique::log_cesium, Technique::log_fragment, "float32"},
        std::tuple{Technique::log_threejs, Technique::log_fragment, "unorm24"},
        std::tuple{Technique::log_threejs_vertex, Technique::log_vertex, "unorm24"}}) {
    const auto a = mts_rows(scene, engine, format, DepthRange::gl, zs);
    const auto b = mts_rows(scene, gilg, format, DepthRange::gl, zs);
    for (size_t i = 0; i < zs.size(); ++i) {
      INFO(info(engine).name << "/" << format << " z = " << zs[i] << ": " << a[i].mts << " vs "
                             << info(gilg).name << " " << b[i].mts);
      REQUIRE(a[i].verdict() == Verdict::resolved);
      REQUIRE(b[i].verdict() == Verdict::resolved);
      CHECK(a[i].mts < 2 * b[i].mts);
      CHECK(b[i].mts < 2 * a[i].mts);
    }
  }
}
