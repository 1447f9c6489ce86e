// The embedded kernel programs: every quoted #include is resolved from the embedded sources
// (none reaches the OpenCL compiler, which would resolve it against the working directory), and
// a program variant missing a define is refused by its #error instead of reading it as 0.
#include <catch2/catch.hpp>

#include "host/base/errors.h"
#include "host/runtime/embedded_sources.h"
#include "host/runtime/kernel_variant.h"
#include "mts_fixture.h"

using namespace depthprec;
using Catch::Matchers::Contains;

TEST_CASE("kernel programs expand to sources without a quoted include", "[kernels]") {
  for (const char* program : {"kernels/mts.cl", "kernels/mts_test.cl", "kernels/mts_exact.cl",
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
