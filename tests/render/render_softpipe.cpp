// Mesa's softpipe, a second real rasterizer, against the softpipe profile (docs/validation.md):
// rows where the profile's own choices decide the MTS, rendered on softpipe through the system's
// OpenGL and emulated under both profiles.
#include <fmt/format.h>

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "host/model/profile.h"
#include "host/mts/worst_case.h"
#include "tests/support/mts_fixture.h"
#include "tests/support/run_cli.h"

using namespace depthprec;
using namespace depthprec::test;

TEST_CASE("the softpipe profile measures what Mesa's softpipe renders", "[render][softpipe]") {
  // softpipe, a second Mesa rasterizer, draws through llvmpipe's draw module but sets the depth
  // plane up from the vertex of least y, steps it across 2x2 quads (pipeline.plane = origin_quads)
  // and truncates unorm codes (pipeline.conversion = softpipe). Rows where each of those decides
  // the MTS: the softpipe profile gives softpipe's, the llvmpipe profile does not.
  // (softpipe's depth does not read back through glReadPixels, so rows, not pixels, are compared.)
  const auto rendered = [](const char* technique, const char* format, const std::string& zs) {
    const auto r = run_cli(
        fmt::format(
            "render -t {} -f {} --distances {} --frames 20 --format-out json --no-timing -q",
            technique, format, zs),
        "GALLIUM_DRIVER=softpipe MESA_GL_VERSION_OVERRIDE=4.5 MESA_GLSL_VERSION_OVERRIDE=450");
    REQUIRE(r.exit_code == 0);
    const auto j = nlohmann::json::parse(r.output);
    REQUIRE(j["gl_renderer"] == "softpipe");
    std::vector<double> mts;
    for (const auto& row : j["rows"]) mts.push_back(row["mts"]);
    return mts;
  };
  const auto emulated = [](const char* name, Technique t, const char* format, DepthRange range,
                           const std::vector<double>& zs) {
    std::vector<std::string> sets = profile(name).sets;
    sets.push_back("frames=20");
    const Scene scene = load_scene("", sets);
    // render samples the worst case's orientations too: the profile must agree over all of them
    std::vector<double> mts;
    for (const MtsRow& r : search_sampled(runtime(), scene, EvalPair{t, format, range}, zs))
      mts.push_back(r.mts);
    return mts;
  };
  const std::vector<
      std::tuple<const char*, Technique, const char*, DepthRange, std::string, std::vector<double>>>
      cases = {
          {"standard", Technique::standard, "float32", DepthRange::gl, "64,256", {64, 256}},
          {"linear", Technique::linear, "unorm24", DepthRange::gl, "2,256", {2, 256}},
          {"reversed", Technique::reversed, "unorm32", DepthRange::zero_to_one, "1024", {1024}}};
  for (const auto& [name, t, format, range, list, zs] : cases) {
    const auto real = rendered(name, format, list);
    const auto softpipe = emulated("softpipe", t, format, range, zs);
    const auto llvmpipe = emulated("llvmpipe", t, format, range, zs);
    REQUIRE(real.size() == zs.size());
    for (size_t k = 0; k < zs.size(); ++k) {
      INFO(name << "/" << format << " z = " << zs[k] << ": softpipe " << real[k]
                << ", softpipe profile " << softpipe[k] << ", llvmpipe profile " << llvmpipe[k]);
      CHECK(softpipe[k] == real[k]);
      CHECK(llvmpipe[k] != real[k]);
    }
  }
}
