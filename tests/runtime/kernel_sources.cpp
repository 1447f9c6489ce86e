// The embedded kernel programs: every quoted #include is resolved from the embedded sources
// (none reaches the OpenCL compiler, which would resolve it against the working directory), and
// a program variant missing a define is refused by its #error instead of reading it as 0.
#include <catch2/catch.hpp>

#include "host/base/embedded_sources.h"
#include "host/base/errors.h"
#include "host/runtime/kernel_variant.h"
#include "tests/support/mts_fixture.h"

using namespace depthprec;
using Catch::Matchers::Contains;

TEST_CASE("kernel programs expand to sources without a quoted include", "[kernels]") {
  for (const char* program :
       {"kernels/mts.cl", "kernels/mts_setup.cl", "kernels/mts_test.cl", "kernels/mts_exact.cl",
        "kernels/lj.cl", "kernels/encode.cl", "kernels/bias.cl"}) {
    INFO(program);
    const std::string source = expand_embedded(program);
    CHECK(source.find("#include \"") == std::string::npos);
    CHECK(source.size() > 1000);
  }
}

TEST_CASE("an MTS variant without one of its defines does not build", "[kernels]") {
  const Scene scene = load_scene("", {});
  const KernelVariant v = mts_variant(scene, scene.evaluate.front());
  const std::string options = v.options;
  const auto at = options.find("-DCACHE_A_CODES=");
  REQUIRE(at != std::string::npos);
  const std::string without = options.substr(0, at) + options.substr(options.find(' ', at));
  CHECK_THROWS_WITH(test::runtime().program(v.program, without),
                    Contains("kernels/mts.cl needs GRID"));
}

TEST_CASE("the set-up program is shared by the variants that differ only past the set-up",
          "[kernels]") {
  // standard and reversed differ in the compare, unorm24 and float32 in the storage format: neither
  // reaches mts_setup
  const Scene scene = load_scene("", {});
  const auto setup = [&](Technique t, const char* format) {
    return mts_variant(scene, EvalPair{t, format, DepthRange::gl}).setup_options;
  };
  const std::string standard = setup(Technique::standard, "unorm24");
  CHECK(setup(Technique::reversed, "float32") == standard);
  CHECK(setup(Technique::standard, "float16") == standard);
  CHECK(mts_variant(scene, EvalPair{Technique::reversed, "float32", DepthRange::gl}).options !=
        mts_variant(scene, EvalPair{Technique::standard, "unorm24", DepthRange::gl}).options);
  // the depth path's class does
  CHECK(setup(Technique::log_vertex, "unorm24") != standard);
  CHECK(setup(Technique::linear, "unorm24") != standard);
  CHECK(setup(Technique::linear, "unorm24") == setup(Technique::log_fragment, "float32"));
  // and without a define the set-up program is refused as mts.cl is
  const auto at = standard.find("-DCLIP_SLOTS=");
  REQUIRE(at != std::string::npos);
  CHECK_THROWS_WITH(test::runtime().program("kernels/mts_setup.cl", standard.substr(0, at)),
                    Contains("kernels/mts_setup.cl needs GRID"));
}
