// Where results go: a result that cannot be delivered ends in exit 5 naming the place (standard
// output as much as a file), and an output never replaces what the command reads.
#include <catch2/catch.hpp>
#include <fstream>
#include <string>

#include "run_cli.h"

using Catch::Matchers::Contains;
using depthprec::test::fresh;
using depthprec::test::run_cli;
using depthprec::test::run_cli_stdout_to;

namespace {

const std::string kTiny =
    "-t standard -f unorm24 --distances 2,4 --kernel 32x32 --frames 4 --no-timing -q";

}  // namespace

// /dev/full takes every write as a full disk does: the data is buffered, and the flush fails.
// Before, each of these exited 0 with its result lost.
TEST_CASE("a result standard output cannot take is an output error naming standard output",
          "[cli][output][errors]") {
  const std::string part1 = fresh("/tmp/depthprec_test_full_part1.json"),
                    part2 = fresh("/tmp/depthprec_test_full_part2.json");
  REQUIRE(run_cli("mts " + kTiny + " --format-out json --shard 1/2 -o " + part1).exit_code == 0);
  REQUIRE(run_cli("mts " + kTiny + " --format-out json --shard 2/2 -o " + part2).exit_code == 0);
  const auto args = GENERATE_COPY(values<std::string>({
      "mts " + kTiny + " --format-out json",
      "table " + kTiny,
      "merge " + part1 + " " + part2,
      "merge " + part1 + " " + part2 + " --format-out csv",
      "formats",
      "resolve -t standard -f unorm16 --near 0.01 --far 1000 --code 1",
      "lj --far 100 --samples 1000 --no-timing",
      "devices",
      "--help",
      "mts --help",
      "--version",
  }));
  INFO(args);
  // the same command with somewhere to write succeeds: the failure is the output's alone
  CHECK(run_cli_stdout_to(args, "/dev/null").exit_code == 0);
  const auto r = run_cli_stdout_to(args, "/dev/full");
  INFO(r.output);
  CHECK(r.exit_code == 5);
  CHECK_THAT(r.output, Contains("cannot write standard output: No space left on device"));
}
