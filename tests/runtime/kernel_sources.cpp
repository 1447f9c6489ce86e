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

namespace {

// The defines kernels/mts/defines.h checks, in the order it checks them: the set-up's, then the
// per-pixel programs' (from its second #if on).
std::vector<std::string> checked_defines(bool setup_only) {
  const std::string text = embedded_sources().at("kernels/mts/defines.h");
  const size_t per_pixel = text.find("#ifndef MTS_SETUP_STAGE");
  std::vector<std::string> names;
  for (size_t at = text.find("!defined("); at != std::string::npos;
       at = text.find("!defined(", at + 1)) {
    if (setup_only && at > per_pixel) break;
    const size_t from = at + 9;
    names.push_back(text.substr(from, text.find(')', from) - from));
  }
  return names;
}

// The options without -DNAME=...
std::string options_without(const std::string& options, const std::string& name) {
  const auto at = options.find("-D" + name + "=");
  REQUIRE(at != std::string::npos);
  const auto end = options.find(' ', at);
  return options.substr(0, at) + (end == std::string::npos ? "" : options.substr(end));
}

}  // namespace

TEST_CASE("an MTS variant without any one of its defines does not build", "[kernels]") {
  const Scene scene = load_scene("", {});
  const KernelVariant v = mts_variant(scene, scene.evaluate.front());
  const auto names = checked_defines(false);
  REQUIRE(names.size() == 15);  // GRID .. RELATIVE_TO_EYE, then FRAG_DEPTH .. DF_KIND
  for (const std::string& name : names) {
    INFO(name);
    CHECK_THROWS_WITH(test::runtime().program(v.program, options_without(v.options, name)),
                      Contains("kernels/mts/defines.h"));
    CHECK_THROWS_WITH(test::runtime().program("kernels/bias.cl", options_without(v.options, name)),
                      Contains("kernels/mts/defines.h"));
  }
  for (const std::string& name : checked_defines(true)) {
    INFO(name);
    CHECK_THROWS_WITH(
        test::runtime().program(v.setup_program, options_without(v.setup_options, name)),
        Contains("the emulated pipeline needs GRID"));
  }
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
}
