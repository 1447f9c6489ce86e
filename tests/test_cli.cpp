#include <catch2/catch.hpp>

#include "run_cli.h"

using depthprec::test::run_cli;
using Catch::Matchers::Contains;

TEST_CASE("formats prints bits, range and spacing, and round-trips on the device", "[cli]") {
  const auto r = run_cli("formats unorm24 float32 --value 0.5 --on-device");
  REQUIRE(r.exit_code == 0);
  CHECK_THAT(r.output, Contains("spacing@0.5"));
  CHECK_THAT(r.output, Contains("16777216"));   // unorm24 has 2^24 codes
  CHECK_THAT(r.output, Contains("0x800000"));   // 0.5 rounds to 8388608 in unorm24 (tie to even)
  CHECK_THAT(r.output, Contains("0x3f000000")); // float32 stores the bits of 0.5
  CHECK_THAT(r.output, Contains("agrees"));
}

TEST_CASE("a bad format name is an input error naming what is allowed", "[cli][errors]") {
  const auto r = run_cli("formats unorm33");
  CHECK(r.exit_code == 3);
  CHECK_THAT(r.output, Contains("unorm takes 1 to 32 bits"));
  const auto r2 = run_cli("formats e9m60");
  CHECK(r2.exit_code == 3);
  CHECK_THAT(r2.output, Contains("E = 1..8"));
}

TEST_CASE("no OpenCL platform gives a one-line error naming the package", "[cli][errors]") {
  // The ICD loader reads vendor files from OCL_ICD_VENDORS: an empty directory means no platform.
  const auto r = run_cli("devices", "OCL_ICD_VENDORS=/nonexistent-depthprec-icd");
  CHECK(r.exit_code == 4);
  CHECK_THAT(r.output, Contains("no OpenCL platform found"));
  CHECK_THAT(r.output, Contains("pocl-opencl-icd"));
}

TEST_CASE("devices lists the PoCL CPU device with its capabilities", "[cli]") {
  const auto r = run_cli("devices");
  REQUIRE(r.exit_code == 0);
  CHECK_THAT(r.output, Contains("Portable Computing Language"));
  CHECK_THAT(r.output, Contains("*0:0"));
  CHECK_THAT(r.output, Contains("OpenCL C"));
}

TEST_CASE("an unknown device selector is a runtime error listing devices", "[cli][errors]") {
  const auto r = run_cli("formats --value 0.5 --on-device", "DEPTHPREC_DEVICE=no-such-gpu");
  CHECK(r.exit_code == 4);
  CHECK_THAT(r.output, Contains("no OpenCL device matches 'no-such-gpu'"));
}

TEST_CASE("an unknown option is a usage error", "[cli][errors]") {
  const auto r = run_cli("formats --bogus");
  CHECK(r.exit_code == 2);
}
