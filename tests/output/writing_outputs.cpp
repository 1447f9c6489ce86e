// Where results go: a result that cannot be delivered ends in exit 5 naming the place (standard
// output as much as a file), and an output never replaces what the command reads.
#include <catch2/catch.hpp>
#include <cstdlib>
#include <fstream>
#include <string>

#include "tests/support/run_cli.h"

using Catch::Matchers::Contains;
using depthprec::test::run_cli;
using depthprec::test::run_cli_stdout_to;

namespace {

const std::string kTiny =
    "-t standard -f unorm24 --distances 2,4 --kernel 32x32 --frames 4 --no-timing -q";

// Two shards of one tiny run, made once per process (GENERATE runs a test case again for each of
// its values) beside the first caller's dir (ctest runs each case in a process of its own, side
// by side), and copied to dir/a.json and dir/b.json for each value.
void tiny_shards(const std::string& dir) {
  static const std::string made = [&dir] {
    const std::string d = dir + "_shards";
    std::system(("rm -rf " + d + " && mkdir -p " + d).c_str());
    REQUIRE(
        run_cli("mts " + kTiny + " --format-out json --shard 1/2 -o " + d + "/a.json").exit_code ==
        0);
    REQUIRE(
        run_cli("mts " + kTiny + " --format-out json --shard 2/2 -o " + d + "/b.json").exit_code ==
        0);
    return d;
  }();
  REQUIRE(std::system(("cp " + made + "/a.json " + made + "/b.json " + dir + "/").c_str()) == 0);
}

}  // namespace

// /dev/full takes every write as a full disk does: the data is buffered, and the flush fails.
// Before, each of these exited 0 with its result lost.
TEST_CASE("a result standard output cannot take is an output error naming standard output",
          "[cli][output][errors]") {
  const std::string dir = "/tmp/depthprec_test_full";
  std::system(("mkdir -p " + dir).c_str());
  tiny_shards(dir);
  const std::string part1 = dir + "/a.json", part2 = dir + "/b.json";
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

// Before, `mts ow.json ... -o ow.json` put the results where the scene was (exit 0), and
// `merge a.json b.json -o a.json` a merge over a shard.
TEST_CASE("an output that names an input is refused before any work", "[cli][output][errors]") {
  const std::string dir = "/tmp/depthprec_test_ow";
  std::system(("rm -rf " + dir + " && mkdir -p " + dir).c_str());
  const std::string scene = dir + "/ow.json", scene_text = "{\"frames\": 4}\n";
  std::ofstream(scene) << scene_text;
  std::system(("ln -s ow.json " + dir + "/soft.json && ln " + scene + " " + dir + "/hard.json && " +
               "cp " + scene + " " + dir + "/x.json.tmp")
                  .c_str());
  const std::string a = dir + "/a.json", b = dir + "/b.json";
  tiny_shards(dir);
  const std::string shard_text = depthprec::test::slurp(a);
  const auto [args, input] = GENERATE_COPY(table<std::string, std::string>({
      {"mts " + scene + " " + kTiny + " -o " + scene, scene},
      {"mts " + scene + " " + kTiny + " -o " + dir + "/soft.json", scene},  // a symbolic link
      {"mts " + dir + "/hard.json " + kTiny + " -o " + scene, scene},       // a hard link
      {"mts " + dir + "/x.json.tmp " + kTiny + " -o " + dir + "/x.json", dir + "/x.json.tmp"},
      {"table " + scene + " " + kTiny + " -o " + scene, scene},
      {"mts " + scene + " " + kTiny + " --profiles ideal,llvmpipe -o " + scene, scene},
      {"cost " + scene + " " + kTiny + " -o " + scene, scene},
      {"tradeoff " + scene + " " + kTiny + " -o " + scene, scene},
      {"pipelines " + scene + " " + kTiny + " -o " + scene, scene},
      {"advise " + scene + " --range 1,10 --separation 0.1 -o " + scene, scene},
      {"bias " + scene + " " + kTiny + " -o " + scene, scene},
      {"compare " + scene + " " + kTiny + " -o " + scene, scene},
      {"report " + scene + " " + kTiny + " -o " + scene, scene},
      {"merge " + a + " " + b + " -o " + a, a},
      {"merge " + a + " " + b + " -o " + dir + "/./a.json", a},
      {"report --from " + a + " -o " + a, a},
      {"plot " + a + " -o " + a, a},
      {"compare --emulated " + a + " --rendered " + b + " -o " + a, a},
  }));
  INFO(args);
  const auto r = run_cli(args);
  INFO(r.output);
  CHECK(r.exit_code == 3);
  CHECK_THAT(r.output, Contains(input) && Contains("which this command reads"));
  CHECK(depthprec::test::slurp(scene) == scene_text);
  CHECK(depthprec::test::slurp(dir + "/x.json.tmp") == scene_text);
  CHECK(depthprec::test::slurp(a) == shard_text);
}

// Before, `plot OUT.json` without -o replaced any ./mts.png (and `report` any ./report.html).
TEST_CASE("plot and report without -o never replace a file of their default name",
          "[cli][output][plot]") {
  const std::string dir = "/tmp/depthprec_test_default_out";
  std::system(("rm -rf " + dir + " && mkdir -p " + dir).c_str());
  const std::string rows = dir + "/rows.json";
  REQUIRE(run_cli("mts " + kTiny + " --format-out json -o " + rows).exit_code == 0);
  const std::string in_dir = "cd " + dir + " && '" + std::string(DEPTHPREC_EXE) + "' ";
  for (const auto& [cmd, name] : {std::pair<std::string, std::string>{"plot rows.json", "mts.png"},
                                  {"report --from rows.json -q", "report.html"}}) {
    INFO(cmd);
    const std::string path = dir + "/" + name;
    std::remove(path.c_str());
    CHECK(depthprec::test::run_shell(in_dir + cmd + " 2>&1").exit_code == 0);  // a new file
    CHECK(depthprec::test::slurp(path).size() > 1000);
    std::ofstream(path) << "someone's file\n";
    const auto again = depthprec::test::run_shell(in_dir + cmd + " 2>&1");
    INFO(again.output);
    CHECK(again.exit_code == 5);
    CHECK_THAT(again.output, Contains("'" + name + "' exists") && Contains("-o " + name));
    CHECK(depthprec::test::slurp(path) == "someone's file\n");
    // named with -o, it is replaced
    CHECK(depthprec::test::run_shell(in_dir + cmd + " -o " + name + " 2>&1").exit_code == 0);
    CHECK(depthprec::test::slurp(path).size() > 1000);
  }
}

// Before, gnuplot drew straight into the output: a run that failed half way left a broken image
// under the name asked for (and exit 5 beside it).
TEST_CASE("a plot gnuplot fails to draw leaves neither a broken image nor a temporary file",
          "[cli][output][plot]") {
  const std::string dir = "/tmp/depthprec_test_fake_gnuplot";
  std::system(("rm -rf " + dir + " && mkdir -p " + dir).c_str());
  // A gnuplot that writes part of its output, then fails as a real one can.
  std::ofstream(dir + "/gnuplot") << "#!/bin/sh\n"
                                     "out=$(sed -n 's/^set output \"\\(.*\\)\"$/\\1/p' \"$1\")\n"
                                     "echo 'half a plot' > \"$out\"\n"
                                     "echo 'fake gnuplot: it failed' >&2\n"
                                     "exit 1\n";
  std::system(("chmod +x " + dir + "/gnuplot").c_str());
  const std::string rows = dir + "/rows.json", png = dir + "/mts.png";
  REQUIRE(run_cli("mts " + kTiny + " --format-out json -o " + rows).exit_code == 0);
  const auto r = run_cli("plot " + rows + " -o " + png, "PATH=" + dir + ":$PATH");
  INFO(r.output);
  CHECK(r.exit_code == 5);
  CHECK_THAT(r.output, Contains("gnuplot failed writing '" + png + "'"));
  CHECK_FALSE(std::ifstream(png).good());
  CHECK_FALSE(std::ifstream(png + ".tmp").good());
  // with the real gnuplot the same plot is drawn
  CHECK(run_cli("plot " + rows + " -o " + png).exit_code == 0);
  CHECK(depthprec::test::slurp(png).substr(1, 3) == "PNG");
  CHECK_FALSE(std::ifstream(png + ".tmp").good());
}
