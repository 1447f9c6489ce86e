// What a user types, read strictly: each mistake gets a message that names the option and what
// is allowed, and the documented exit code (2 usage, 3 bad input, 5 output); engineers' names
// for formats, buffers and commands get a "did you mean".
#include <catch2/catch.hpp>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "tests/support/run_cli.h"

using Catch::Matchers::Contains;
using Catch::Matchers::StartsWith;
using depthprec::test::fresh;
using depthprec::test::run_cli;
using depthprec::test::slurp;

namespace {

const std::string kSmallMts = "mts -t reversed -f float32 --kernel 24x24 --frames 4 --no-timing";

}  // namespace

TEST_CASE("repeated distances are refused at once, not waited on", "[cli][errors]") {
  for (const char* list : {"100,100", "100,1e2", "100,200,100"}) {
    INFO(list);
    const auto t0 = std::chrono::steady_clock::now();
    // Under a time limit: before they were refused, repeats waited forever (exit 124 here).
    const auto r = run_cli(kSmallMts + " --distances " + list, "timeout -s KILL 20");
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    CHECK(r.exit_code == 3);
    CHECK_THAT(r.output, Contains("--distances " + std::string(list)) && Contains("twice"));
    CHECK(seconds < 20);
  }
  for (const char* cmd : {"table", "cost"})
    CHECK(run_cli(std::string(cmd) +
                      " -t standard -f unorm24 --kernel 24x24 --frames 4 --distances 8,8",
                  "timeout -s KILL 20")
              .exit_code == 3);
}

TEST_CASE("a technique named without a depth range runs in its own, and the row says which",
          "[cli][mts]") {
  const auto r = run_cli(kSmallMts + " --distances 500 --format-out csv");
  REQUIRE(r.exit_code == 0);
  CHECK_THAT(r.output, Contains("reversed,float32,zero_to_one,500,"));
  const auto gl = run_cli(kSmallMts + " --distances 500 --format-out csv --depth-range gl");
  CHECK_THAT(gl.output, Contains("reversed,float32,gl,500,"));
}

TEST_CASE("set-ups without a measurement are refused or get a verdict up front", "[cli][errors]") {
  const auto far_inf = run_cli("mts -t standard -f float32 --far inf --distances 10");
  CHECK(far_inf.exit_code == 3);
  CHECK_THAT(far_inf.output, Contains("far = inf: standard/float32/gl needs a finite far plane"));
  CHECK(run_cli("mts -t infinite -f float32 --far inf --distances 10 --kernel 16x16 --frames 2")
            .exit_code == 0);
  const auto huge = run_cli(kSmallMts + " --distances 1e300");
  CHECK(huge.exit_code == 3);
  CHECK_THAT(huge.output, StartsWith("depthprec: --distances 1e300:"));
  const auto near = run_cli(kSmallMts + " --near 10 --distances 5,20 --format-out json");
  REQUIRE(near.exit_code == 0);
  const auto rows = nlohmann::json::parse(near.output)["rows"];
  CHECK(rows[0]["verdict"] == "nearer than near plane");
  CHECK(rows[0]["probes"] == 0);
  CHECK(rows[1]["verdict"] == "resolved");
  for (const char* d : {"20000", "0.01"}) {
    const auto res =
        run_cli(std::string("resolve -t standard -f unorm24 --near 0.1 --far 1e4 --distance ") + d);
    INFO(d);
    CHECK(res.exit_code == 3);
    CHECK_THAT(res.output, Contains("standard clips it"));
  }
}

TEST_CASE("options are read strictly and blamed by name", "[cli][errors]") {
  const auto empty = run_cli(kSmallMts + " --distances 1,,2");
  CHECK(empty.exit_code == 2);
  CHECK_THAT(empty.output, Contains("--distances: an empty entry in '1,,2'"));
  const auto frames = run_cli("mts --frames 0");
  CHECK(frames.exit_code == 3);
  CHECK_THAT(frames.output, StartsWith("depthprec: --frames 0: 'frames' must be 1..1000000"));
  CHECK(run_cli("mts --frames 1.5").exit_code == 2);
  const auto twice = run_cli("mts --near 0.1 --set near=5");
  CHECK(twice.exit_code == 2);
  CHECK_THAT(twice.output, Contains("--near 0.1 and --set near=5 both set 'near'"));
  const auto set = run_cli("mts --set frames=0");
  CHECK_THAT(set.output, StartsWith("depthprec: --set frames=0: 'frames'"));
  // A whole number too large for an integer is out of range, not "no whole number".
  const auto huge = run_cli("mts --set frames=1e12");
  CHECK(huge.exit_code == 3);
  CHECK_THAT(huge.output, Contains("'frames' must be 1..1000000, not 1000000000000.0 (too large)"));
  std::ofstream("/tmp/depthprec_test_huge_frames.json") << "{\n  \"frames\": 1e12\n}\n";
  const auto file = run_cli("mts /tmp/depthprec_test_huge_frames.json");
  CHECK(file.exit_code == 3);
  CHECK_THAT(file.output, Contains("depthprec_test_huge_frames.json:2:3: 'frames' must be "
                                   "1..1000000, not 1000000000000.0 (too large)"));
  CHECK_THAT(run_cli("mts --set frames=18446744073709551615").output, Contains("(too large)"));
  CHECK_THAT(run_cli("mts --set frames=4.5").output, Contains("'frames' must be a whole number"));
  const auto value = run_cli("formats unorm24 --value 1.5");
  CHECK(value.exit_code == 3);
  CHECK_THAT(value.output, Contains("--value 1.5: depth values are in [0, 1]"));
}

TEST_CASE("a bad block, a range turned inside out and a key given twice are refused by name",
          "[cli][errors]") {
  std::ofstream("/tmp/depthprec_test_null_pipeline.json") << "{\"pipeline\": null}\n";
  struct Refused {
    std::string command;
    int exit_code;
    std::string says;
  };
  const std::vector<Refused> refused = {
      // A block of settings that is not an object replaced the whole block (and crashed on it).
      {"mts -t standard -f unorm24 --distances 2 --set pipeline=1", 3,
       "'pipeline' must be an object"},
      {"mts /tmp/depthprec_test_null_pipeline.json", 3, ":1:2: 'pipeline' must be an object"},
      {"mts --set worst_case=3", 3, "'worst_case' must be an object"},
      // The key the user set is the one blamed, with the one it conflicts with.
      {"mts --set worst_case.max_rounds=1", 3,
       "'worst_case.max_rounds' must be at least worst_case.min_rounds (2), not 1"},
      // A negative range turned the cube inside out, and its guaranteed MTS with it.
      {"mts --set rotation_range_deg=-1", 3,
       "'rotation_range_deg' must be 0 up to below 45 degrees"},
      {"mts --set near=1e400", 3, "'near' must be a number; 1e400 is beyond binary64's range"},
      {"mts --set near=0.1 --set near=0.2", 2, "--set near=0.1 and --set near=0.2 both set 'near'"},
      {"mts --set pipeline.divide=exact --set pipeline={}", 2, "both set 'pipeline.divide'"},
      {"resolve -t log_vertex --code 3 --log-k 0", 3, "--log-k must be a finite k > 0"},
      {"resolve -t log_vertex --code 3 --log-k -1", 3, "--log-k must be a finite k > 0"},
      {"resolve -t log_vertex --code 3 --log-k nan", 3, "--log-k must be a finite k > 0"},
      {"shadow --source bound --camera-near -1 -q", 3, "--camera-near -1: the camera's near plane"},
      {"world -t standard -f unorm24 --separation 0.01 --distance 0.5 -q", 3,
       "--distance 0.5: the content must lie beyond the near plane"},
      // Option errors the parser finds name the option.
      {"bias --source bogus", 2, "--source: bogus not in {emulated,rendered}"},
      // An --up the file's camera would drop is refused, not ignored.
      {"audit '" DEPTHPREC_SOURCE_DIR "/data/audit/shelf_wall.gltf' --up 0,0,1 -q", 2,
       "--up orients the views of --eye and --target or of --path"}};
  for (const Refused& r : refused) {
    INFO(r.command);
    const auto run = run_cli(r.command);
    CHECK(run.exit_code == r.exit_code);
    CHECK_THAT(run.output, Contains(r.says) && !Contains("internal"));
  }
  // ... and are said by depthprec, as every error is.
  const auto jobs = run_cli("mts --jobs 0");
  CHECK(jobs.exit_code == 2);
  CHECK_THAT(jobs.output, StartsWith("depthprec: --jobs: Value 0 not in range"));
}

TEST_CASE("shadow keeps its progress off a log, as every command does", "[cli][shadow]") {
  const auto r = run_cli("shadow --source bound -o /dev/null");
  REQUIRE(r.exit_code == 0);
  CHECK(r.output.empty());  // stderr is not a terminal here
}

TEST_CASE("engineers' names get a did-you-mean", "[cli][errors]") {
  for (const auto& [typed, meant] : {std::pair{"d24", "unorm24"},
                                     {"D24", "unorm24"},
                                     {"UNORM24", "unorm24"},
                                     {"D32F", "float32"},
                                     {"d16", "unorm16"}}) {
    const auto r = run_cli(std::string("formats ") + typed);
    INFO(typed);
    CHECK(r.exit_code == 3);
    CHECK_THAT(r.output, Contains(std::string("(did you mean ") + meant + "?)"));
  }
  CHECK_THAT(run_cli("lj --buffer reversed").output, Contains("(did you mean complementary_z?)"));
  for (const auto& [typed, meant] : {std::pair{"zbuffer", "z"},
                                     {"z-buffer", "z"},
                                     {"wbuffer", "w"},
                                     {"W_BUFFER", "w"},
                                     {"1/w", "inverse_w"}}) {
    INFO(typed);
    const auto r = run_cli(std::string("lj --buffer ") + typed);
    CHECK(r.exit_code == 3);
    CHECK_THAT(r.output, Contains(std::string("(did you mean ") + meant + "?)"));
  }
  CHECK_THAT(run_cli("mts -t standrd").output, Contains("(did you mean standard?)"));
  const auto cmd = run_cli("mst");
  CHECK(cmd.exit_code == 2);
  CHECK_THAT(cmd.output, Contains("unknown command 'mst' (did you mean mts?)"));
  const auto sub = run_cli("cache shwo");
  CHECK(sub.exit_code == 2);
  CHECK_THAT(sub.output, Contains("unknown cache subcommand 'shwo' (did you mean show?)"));
  CHECK_THAT(sub.output, Contains("the cache subcommands are show, clear"));
}

TEST_CASE("the output file's extension chooses the format", "[cli]") {
  const std::string json = fresh("/tmp/depthprec_test_ext.json"),
                    csv = fresh("/tmp/depthprec_test_ext.csv");
  REQUIRE(run_cli(kSmallMts + " --distances 64 -o " + json).exit_code == 0);
  CHECK(nlohmann::json::parse(slurp(json))["rows"].size() == 1);
  REQUIRE(run_cli(kSmallMts + " --distances 64 -o " + csv).exit_code == 0);
  CHECK_THAT(slurp(csv), StartsWith("technique,format,depth_range,z,"));
  const auto forced = run_cli(kSmallMts + " --distances 64 --format-out text -o " + json);
  CHECK_THAT(forced.output, Contains("gets --format-out text, not the json its name suggests"));
  CHECK_THAT(slurp(json), StartsWith("technique  format"));
}

TEST_CASE("merge refuses a missing or repeated shard, naming it", "[cli][batch][errors]") {
  const std::string args = kSmallMts + " --distances 2,64,2048 --format-out json";
  for (int i = 1; i <= 2; ++i)
    REQUIRE(run_cli(args + " --shard " + std::to_string(i) + "/2 -o " +
                    fresh("/tmp/depthprec_test_sh" + std::to_string(i) + ".json"))
                .exit_code == 0);
  const auto missing = run_cli("merge /tmp/depthprec_test_sh1.json --format-out json");
  CHECK(missing.exit_code == 3);
  CHECK_THAT(missing.output, Contains("shard 2/2 is missing"));
  const auto twice = run_cli("merge /tmp/depthprec_test_sh1.json /tmp/depthprec_test_sh1.json");
  CHECK(twice.exit_code == 3);
  CHECK_THAT(twice.output, Contains("shard 1/2 given twice"));
  CHECK(run_cli("merge /tmp/depthprec_test_sh1.json /tmp/depthprec_test_sh2.json").exit_code == 0);
}

TEST_CASE("an unwritable plot is refused before the batch runs", "[cli][plot][errors]") {
  for (const char* cmd :
       {"cost -t standard -f unorm24 --distances 2 --kernel 16x16 --frames 2",
        "tradeoff -t reversed -f float32 --distances 2", "lj-table --samples 1000"}) {
    INFO(cmd);
    const auto t0 = std::chrono::steady_clock::now();
    const auto r = run_cli(std::string(cmd) + " --plot /nonexistent/dir/p.png");
    CHECK(r.exit_code == 5);
    CHECK_THAT(r.output, Contains("cannot write output '/nonexistent/dir/p.png'"));
    CHECK(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() < 5);
    CHECK(run_cli(std::string(cmd) + " --plot /tmp/p.pdf").exit_code == 3);
  }
}

TEST_CASE("a row never counts more launches than its run made", "[cli][mts]") {
  const auto r = run_cli(
      "mts -t reversed -f float32 --distances 2,1024,1048576 --kernel 40x40 --frames 20 "
      "--format-out json");
  REQUIRE(r.exit_code == 0);
  const auto j = nlohmann::json::parse(r.output);
  uint64_t sum = 0;
  for (const auto& row : j["rows"]) {
    CHECK(row["kernel_launches"].get<uint64_t>() <= j["kernel_launches"].get<uint64_t>());
    sum += row["kernel_launches"].get<uint64_t>();
  }
  CHECK(sum > j["kernel_launches"].get<uint64_t>());  // rows share launches
}

TEST_CASE("lj and select write their errors as JSON numbers, as mts does", "[cli]") {
  const auto lj = run_cli(
      "lj --buffer z --format unorm16 --far 100 --samples 1000 --no-timing --format-out json");
  REQUIRE(lj.exit_code == 0);
  const auto j = nlohmann::json::parse(lj.output);
  for (const char* key : {"ae_host", "ae_device", "ae_pipeline"}) {
    INFO(key);
    REQUIRE(j.at(key).is_number());
    CHECK(j.at(key).get<double>() > 0);
  }
  CHECK(j.at("format_version") == 1);
  const auto sel =
      run_cli("select --buffer inverse_w --bits 16 --far 500 --samples 1000 --format-out json");
  REQUIRE(sel.exit_code == 0);
  const auto ranking = nlohmann::json::parse(sel.output).at("ranking");
  REQUIRE(ranking.size() == 9);
  CHECK(ranking[0].at("ae").is_number());
  CHECK(ranking[0].at("ae").get<double>() <= ranking[8].at("ae").get<double>());
  CHECK(j.at("rounding") == "nearest_even");
  // Where no format has a finite error, select says so, and ranks no ratio of infinities.
  const auto none = run_cli("select --buffer z --bits 16 --far 1e6 --samples 1000");
  REQUIRE(none.exit_code == 0);
  CHECK_THAT(none.output, Contains("No 16-bit format gives the z buffer a finite average error"));
  CHECK_THAT(none.output, !Contains("nan"));
  const auto none_json =
      run_cli("select --buffer z --bits 16 --far 1e6 --samples 1000 --format-out json");
  REQUIRE(none_json.exit_code == 0);
  CHECK(nlohmann::json::parse(none_json.output).at("ranking")[0].at("x_best").is_null());
}

TEST_CASE("resolve writes JSON when asked, with the OpenGL wiki's figure as a number", "[cli]") {
  const auto r = run_cli(
      "resolve -t standard -f unorm16 --near 0.01 --far 1000 --code 65534 --format-out json");
  REQUIRE(r.exit_code == 0);
  const auto j = nlohmann::json::parse(r.output);
  CHECK(j.at("kind") == "resolve");
  REQUIRE(j.at("rows").size() == 1);
  CHECK_THAT(j["rows"][0].at("distance").get<double>(),
             Catch::Matchers::WithinRel(395.90054, 1e-7));
  CHECK(j["rows"][0].at("code") == 65534);
}

TEST_CASE("on a terminal the progress line is erased before the output", "[cli]") {
  // script(1) (bsdutils, part of every Debian) gives the command a terminal.
  const std::string cmd = std::string("script -qfc \"'") + DEPTHPREC_EXE +
                          "' mts -t standard -f unorm24 --distances 2,4 --kernel 8x8 --frames 2 "
                          "--no-timing\" /dev/null";
  FILE* p = popen(cmd.c_str(), "r");
  REQUIRE(p != nullptr);
  std::string out;
  char buf[4096];
  size_t n;
  while ((n = fread(buf, 1, sizeof buf, p)) > 0) out.append(buf, n);
  REQUIRE(pclose(p) == 0);
  CHECK_THAT(out, Contains("mts: 2/2 rows"));              // the progress line was drawn
  CHECK_THAT(out, Contains("\r\x1b[Ktechnique  format"));  // and erased before the header
}

TEST_CASE("a profile sets its implementation forms as --sets do, and render refuses them",
          "[cli][profile]") {
  const std::string small = " -t standard -f float32 --distances 100 --kernel 16x16 --frames 2 -q";
  const auto llvmpipe = run_cli("mts --profile llvmpipe --format-out json --no-timing" + small);
  REQUIRE(llvmpipe.exit_code == 0);
  const auto j = nlohmann::json::parse(llvmpipe.output);
  CHECK(j["scene"]["pipeline"]["plane"] == "origin_fma");
  CHECK(j["scene"]["pipeline"]["viewport"] == "fma");
  CHECK(j["scene"]["pipeline"]["vertex"] == "fma");
  CHECK(j["scene"]["pipeline"]["profile"] == "llvmpipe");
  const auto unknown = run_cli("mts --profile nvidia" + small);
  CHECK(unknown.exit_code == 3);
  CHECK_THAT(unknown.output, Contains("ideal, llvmpipe"));
  const auto twice = run_cli("mts --profile llvmpipe --set pipeline.plane=vertex" + small);
  CHECK(twice.exit_code == 2);
  CHECK_THAT(twice.output, Contains("--profile"));
  const auto render = run_cli("render --profile llvmpipe" + small);
  CHECK(render.exit_code == 3);
  CHECK_THAT(render.output, Contains("pipeline.plane: the driver sets up"));
  // softpipe's depth bias is no rule of --r-unorm: bias asks for one instead of guessing
  const auto bias = run_cli("bias --profile softpipe" + small);
  CHECK(bias.exit_code == 3);
  CHECK_THAT(bias.output, Contains("choose one with --r-unorm"));
  CHECK(run_cli("bias --profile softpipe --r-unorm step" + small).exit_code == 0);
}

TEST_CASE(
    "a scene names its profile as pipeline.profile; the header and every emulated row name the one "
    "it matches",
    "[cli][profile]") {
  const std::string small =
      " -t standard -f float32 --distances 100,4096 --kernel 16x16 --frames 2 -q --no-timing "
      "--format-out json";
  const std::string file = "/tmp/depthprec_test_profiled_scene.json";
  std::ofstream(file) << R"({"pipeline": {"profile": "llvmpipe"}})";
  const auto from_file = run_cli("mts " + file + small);
  const auto from_option = run_cli("mts --profile llvmpipe" + small);
  REQUIRE(from_file.exit_code == 0);
  REQUIRE(from_option.exit_code == 0);
  const auto a = nlohmann::json::parse(from_file.output),
             b = nlohmann::json::parse(from_option.output);
  CHECK(a["rows"] == b["rows"]);
  CHECK(a["scene"]["pipeline"] == b["scene"]["pipeline"]);
  for (const auto& row : a["rows"]) CHECK(row["profile"] == "llvmpipe");
  // a pipeline that is no profile's is "custom"; the defaults are "ideal"
  const auto custom = run_cli("mts --set pipeline.vertex=fma" + small);
  REQUIRE(custom.exit_code == 0);
  CHECK(nlohmann::json::parse(custom.output)["scene"]["pipeline"]["profile"] == "custom");
  CHECK(nlohmann::json::parse(custom.output)["rows"][0]["profile"] == "custom");
  const auto ideal = run_cli("mts" + small);
  REQUIRE(ideal.exit_code == 0);
  CHECK(nlohmann::json::parse(ideal.output)["scene"]["pipeline"]["profile"] == "ideal");
  CHECK(nlohmann::json::parse(ideal.output)["rows"][0]["profile"] == "ideal");
  // the profile's key given another value in the same file is refused, naming the file
  std::ofstream(file) << R"({"pipeline": {"profile": "llvmpipe", "viewport": "separate"}})";
  const auto clash = run_cli("mts " + file + small);
  CHECK(clash.exit_code == 3);
  CHECK_THAT(clash.output, Contains("pipeline.viewport") && Contains(file));
  std::ofstream(file) << R"({"pipeline": {"profile": "nvidia"}})";
  const auto unknown = run_cli("mts " + file + small);
  CHECK(unknown.exit_code == 3);
  CHECK_THAT(unknown.output, Contains("ideal, llvmpipe"));
}

TEST_CASE("profiles side by side: each one's MTS and the spread", "[cli][profile]") {
  const std::string small =
      " -t standard,reversed -f float32 --distances 2,1024 --kernel 24x24 "
      "--frames 4 -q --no-timing --format-out json";
  const auto both = run_cli("mts --profiles ideal,llvmpipe" + small);
  REQUIRE(both.exit_code == 0);
  const auto j = nlohmann::json::parse(both.output);
  CHECK(j["kind"] == "profiles");
  CHECK(j["profiles"] == nlohmann::json({"ideal", "llvmpipe"}));
  REQUIRE(j["records"].size() == 2);
  // each profile's column is that profile's own run
  const auto ideal = nlohmann::json::parse(run_cli("mts" + small).output);
  const auto llvmpipe = nlohmann::json::parse(run_cli("mts --profile llvmpipe" + small).output);
  size_t k = 0;
  for (const auto& rec : j["records"])
    for (const auto& row : rec["rows"]) {
      INFO(rec["technique"] << " z = " << row["z"]);
      const double a = row["mts"]["ideal"], b = row["mts"]["llvmpipe"];
      CHECK(a == ideal["rows"][k]["mts"].get<double>());
      CHECK(b == llvmpipe["rows"][k]["mts"].get<double>());
      CHECK(row["spread"].get<double>() == std::max(a, b) / std::min(a, b));
      ++k;
    }
  CHECK(run_cli("table --profiles ideal" + small).exit_code == 2);
  CHECK(run_cli("table --profiles ideal,ideal" + small).exit_code == 2);
  CHECK(run_cli("table --profile llvmpipe --profiles ideal,llvmpipe" + small).exit_code == 2);
  CHECK(run_cli("table --profiles ideal,nvidia" + small).exit_code == 3);
}

// Before, one shard drew as if it were the whole run ("distances 3" with one row, gnuplot's
// "empty x range"), and a --profiles output was called no output of mts at all.
TEST_CASE("report and plot refuse one shard of a run and say what a --profiles output is",
          "[cli][errors]") {
  const std::string args = kSmallMts + " --distances 2,64,2048 -q --format-out json";
  for (int i = 1; i <= 2; ++i)
    REQUIRE(run_cli(args + " --shard " + std::to_string(i) + "/2 -o " +
                    fresh("/tmp/depthprec_test_rs" + std::to_string(i) + ".json"))
                .exit_code == 0);
  const std::string part = "/tmp/depthprec_test_rs1.json";
  for (const std::string& cmd :
       {"report --from " + part + " -o " + fresh("/tmp/depthprec_test_rs.html"),
        "plot " + part + " -o " + fresh("/tmp/depthprec_test_rs.png"),
        "compare --emulated " + part + " --rendered " + part}) {
    INFO(cmd);
    const auto r = run_cli(cmd);
    CHECK(r.exit_code == 3);
    CHECK_THAT(r.output, Contains("is shard 1/2 of a batch") && Contains("depthprec merge"));
  }
  // merged, the same files draw
  const std::string whole = fresh("/tmp/depthprec_test_rs_whole.json");
  REQUIRE(run_cli("merge " + part + " /tmp/depthprec_test_rs2.json --format-out json -o " + whole)
              .exit_code == 0);
  CHECK(run_cli("plot " + whole + " -o " + fresh("/tmp/depthprec_test_rs.png")).exit_code == 0);
  CHECK(run_cli("report --from " + whole + " -o " + fresh("/tmp/depthprec_test_rs.html") + " -q")
            .exit_code == 0);
  // a --profiles output: its shard is refused by plot, and report says what it is
  const std::string profiles = fresh("/tmp/depthprec_test_rs_prof.json");
  REQUIRE(run_cli(args + " --profiles ideal,llvmpipe -o " + profiles).exit_code == 0);
  const auto report = run_cli("report --from " + profiles + " -o /tmp/depthprec_test_rs.html");
  CHECK(report.exit_code == 3);
  CHECK_THAT(report.output, Contains("--profiles` output") && Contains("depthprec plot"));
  const std::string profiles_part = fresh("/tmp/depthprec_test_rs_prof1.json");
  REQUIRE(run_cli(args + " --profiles ideal,llvmpipe --shard 1/2 -o " + profiles_part).exit_code ==
          0);
  const auto plot = run_cli("plot " + profiles_part + " -o " + fresh("/tmp/depthprec_test_rs.png"));
  CHECK(plot.exit_code == 3);
  CHECK_THAT(plot.output, Contains("is shard 1/2 of a batch"));
}

// Before, --far given to a technique without a far plane changed nothing without a word, and
// resolve's header echoed it (or the default far 100) as if the mapping used it.
TEST_CASE("a far plane a technique has no use for is pointed out, and resolve does not echo it",
          "[cli][errors]") {
  const std::string small = " -f float32 --distances 2 --kernel 8x8 --frames 2 -q --no-timing";
  const auto infinite = run_cli("mts -t infinite --far 500" + small);
  REQUIRE(infinite.exit_code == 0);
  CHECK_THAT(infinite.output, Contains("note: --far 500: infinite has no far plane"));
  const auto set = run_cli("mts -t reversed_infinite,standard --set far=500" + small);
  CHECK_THAT(set.output, Contains("note: --set far=500: reversed_infinite has no far plane"));
  CHECK_THAT(run_cli("mts -t standard --far 500" + small).output, !Contains("note"));
  const auto res = run_cli("resolve -t infinite -f float32 --far 500 --distance 2");
  REQUIRE(res.exit_code == 0);
  CHECK_THAT(res.output, Contains("note: --far 500: infinite has no far plane"));
  CHECK_THAT(res.output, Contains("near 1, no far plane:") && !Contains(", far 500"));
  const auto json = run_cli("resolve -t infinite -f float32 --distance 5000 --format-out json");
  REQUIRE(json.exit_code == 0);
  CHECK_FALSE(nlohmann::json::parse(json.output).contains("far"));
  CHECK_THAT(run_cli("resolve -t standard -f float32 --far 500 --distance 2").output,
             Contains("near 1, far 500:") && !Contains("note"));
}
