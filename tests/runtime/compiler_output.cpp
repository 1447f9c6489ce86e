// What the kernel compiler says reaches nobody unless it matters: a program that compiles with
// warnings leaves no warning in its log and nothing on stderr (PoCL's embedded clang otherwise
// prints "N warnings generated." there itself), a failing one still says why, and a cold run
// with -q prints nothing at all.
#include <fcntl.h>
#include <unistd.h>

#include <catch2/catch.hpp>
#include <cstdio>
#include <filesystem>
#include <string>

#include "host/base/errors.h"
#include "host/runtime/opencl_runtime.h"
#include "tests/support/mts_fixture.h"
#include "tests/support/run_cli.h"

using namespace depthprec;
using Catch::Matchers::Contains;
namespace fs = std::filesystem;

namespace {

// A kernel clang warns about by default: a float literal stored into an int changes its value
// (-Wliteral-conversion), once per line.
constexpr const char* kWarningSource = R"(
kernel void warns(global int* out) {
  out[0] = 1.5f;
  out[1] = 2.5f;
  out[2] = 3.5f;
}
)";

// What the process writes to file descriptor 2 while f runs (PoCL's clang writes there directly,
// past std::cerr and stdio).
template <class F>
std::string stderr_of(F&& f) {
  std::fflush(stderr);
  char name[] = "/tmp/depthprec_test_stderr_XXXXXX";
  const int capture = mkstemp(name);
  REQUIRE(capture >= 0);
  const int saved = dup(2);
  dup2(capture, 2);
  try {
    f();
  } catch (...) {
    dup2(saved, 2);
    close(saved);
    close(capture);
    std::remove(name);
    throw;
  }
  std::fflush(stderr);
  dup2(saved, 2);
  close(saved);
  close(capture);
  const std::string text = test::slurp(name);
  std::remove(name);
  return text;
}

}  // namespace

TEST_CASE("a program that compiles with warnings leaves them out of its log and off stderr",
          "[kernels][compiler]") {
  OpenClRuntime& rt = test::runtime();
  // The source does warn: built as the driver gets it without depthprec's options, its log
  // (compiled now, or read back from PoCL's cache) names the conversion.
  cl::Program plain(rt.context(), kWarningSource);
  plain.build({rt.device()}, "-cl-std=CL1.2");
  CHECK_THAT(plain.getBuildInfo<CL_PROGRAM_BUILD_LOG>(rt.device()), Contains("warning"));

  cl::Program quiet;
  const std::string said = stderr_of([&] {
    quiet = compile_program(rt.context(), rt.device(), kWarningSource, "-cl-std=CL1.2", "test");
  });
  CHECK(said.empty());
  CHECK_THAT(quiet.getBuildInfo<CL_PROGRAM_BUILD_LOG>(rt.device()), !Contains("warning"));
  CHECK(compiler_options("-cl-std=CL1.2 -DX=1") == "-cl-std=CL1.2 -DX=1 -w");

  // An error still says what is wrong, with the options it was built with.
  try {
    (void)stderr_of([&] {
      compile_program(rt.context(), rt.device(), "kernel void broken(global int* o) { o[0] = ; }",
                      "-cl-std=CL1.2", "broken.cl");
    });
    FAIL("a program that does not compile was built");
  } catch (const RuntimeError& e) {
    CHECK_THAT(e.what(), Contains("broken.cl") && Contains("error") && Contains("-w"));
  }
}

TEST_CASE("a cold compile with -q prints nothing on stderr", "[kernels][compiler][cli]") {
  // Nothing kept: PoCL's cache empty and depthprec's own off, so every program is compiled. The
  // rows go to a file, so whatever the run prints is stderr's.
  const fs::path pocl = fs::temp_directory_path() / "depthprec_test_cold_compile";
  fs::remove_all(pocl);
  fs::create_directories(pocl);
  const fs::path out = fs::temp_directory_path() / "depthprec_test_cold_compile.txt";
  const auto r = test::run_cli(
      "bias -t standard -f unorm24 --kernel 16x16 --frames 1 --distances 2 --no-timing -q -o " +
          test::fresh(out.string()),
      "POCL_CACHE_DIR=" + pocl.string() + " DEPTHPREC_KERNEL_CACHE=off");
  CHECK(r.exit_code == 0);
  CHECK(r.output.empty());
  CHECK_THAT(test::slurp(out.string()), Contains("standard"));
  fs::remove_all(pocl);
  std::remove(out.c_str());
}
