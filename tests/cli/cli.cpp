#include <catch2/catch.hpp>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>

#include "tests/support/run_cli.h"

using Catch::Matchers::Contains;
using depthprec::test::run_cli;

TEST_CASE("formats prints bits, range and spacing, and round-trips on the device", "[cli]") {
  const auto r = run_cli("formats unorm24 float32 --value 0.5 --on-device");
  REQUIRE(r.exit_code == 0);
  CHECK_THAT(r.output, Contains("spacing@0.5"));
  CHECK_THAT(r.output, Contains("16777216"));    // unorm24 has 2^24 codes
  CHECK_THAT(r.output, Contains("0x800000"));    // 0.5 rounds to 8388608 in unorm24 (tie to even)
  CHECK_THAT(r.output, Contains("0x3f000000"));  // float32 stores the bits of 0.5
  CHECK_THAT(r.output, Contains("agrees"));
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

TEST_CASE("devices with a selector that matches nothing lists the devices and fails",
          "[cli][errors]") {
  const auto r = run_cli("devices --device 9:9");
  CHECK(r.exit_code == 4);
  CHECK_THAT(r.output, Contains("0:0  CPU"));  // the list, no device marked
  CHECK_THAT(r.output, !Contains("*0:0"));
  CHECK_THAT(r.output, Contains("no OpenCL device matches '9:9'"));
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

// Every way of getting the input wrong: the message says what, where and what is allowed, and the
// exit code is the documented one (docs/cli.md).
TEST_CASE("bad input gets a specific message and the documented exit code", "[cli][errors]") {
  {
    std::ofstream("/tmp/depthprec_bad.json") << "{\n  \"near\": 1,\n  \"far\": [1,\n}\n";
    std::ofstream("/tmp/depthprec_unknown.json") << "{\n  \"kernal\": [10, 10]\n}\n";
    std::ofstream("/tmp/depthprec_dup.json")
        << "{\n  \"near\": 1,\n  \"far\": 100,\n  \"near\": 2\n}\n";
    std::ofstream("/tmp/depthprec_dup_nested.json")
        << R"({"evaluate": [{"technique": "standard", "format": "unorm24"},)"
        << R"( {"technique": "reversed", "format": "float32", "format": "unorm24"}]})";
  }
  // One generated run per case, so a failure names its case.
  const auto [args_in, code, says] = GENERATE(table<std::string, int, std::string>({
      {"mts /tmp/depthprec_bad.json", 3, "depthprec_bad.json:4:1: malformed JSON"},
      {"mts /tmp/depthprec_unknown.json", 3, "depthprec_unknown.json:2:3: unknown key 'kernal'"},
      {"mts /nonexistent/scene.json", 3, "cannot read scene file '/nonexistent/scene.json'"},
      {"mts /tmp", 3, "scene file '/tmp' is a directory"},  // not "malformed JSON"
      {"mts /tmp/depthprec_dup.json", 3,
       "depthprec_dup.json:4:3: key 'near' given twice (first at 2:3)"},
      {"mts /tmp/depthprec_dup_nested.json", 3, "key 'evaluate[1].format' given twice"},
      {"merge /tmp", 3, "shard '/tmp' is a directory"},
      {"report --from /tmp", 3, "--from file '/tmp' is a directory"},
      {"mts -t zbuffer", 3,
       "unknown technique 'zbuffer' (did you mean standard?): expected one of standard"},
      {"mts -f unorm40", 3, "unorm takes 1 to 32 bits"},
      {"mts -f e9m30", 3, "E = 1..8"},
      {"mts --near 0", 3, "'near' must be > 0"},
      {"mts --near -2", 3, "'near' must be > 0"},
      {"mts --near nan", 2, "--near 'nan': expected a finite number"},
      {"mts --far 0.5", 3, "'far' must be > near"},
      {"mts --frames 0", 3, "'frames' must be 1..1000000"},
      {"mts --frames -5", 3, "'frames' must be 1..1000000"},
      {"mts --kernel 0x10", 3, "'kernel' sides must be 1..16384"},
      {"mts --kernel 100000x100000", 3, "'kernel' sides must be 1..16384"},
      {"mts --log-k 0", 3, "'log_k' must be > 0"},
      {"mts --set rotation_step=[1,2]", 3, "'rotation_step' must be three numbers"},
      {"mts --set nonsense=1", 3, "unknown key 'nonsense'"},
      {"mts -o /nonexistent-dir/out.txt", 5, "cannot write output '/nonexistent-dir/out.txt'"},
      {"lj --near 10 --far 5", 3, "--far must be finite and > near"},
      {"lj --buffer q", 3, "unknown buffer type 'q'"},
      {"resolve --code 1 --distance 2", 2, "exactly one of --code N, --distance w or --curve"},
      {"resolve --code -1", 3, "--code -1: unorm24's codes are the whole numbers 0 to 16777215"},
      {"resolve -f unorm16 --code 65536", 3, "unorm16's codes are the whole numbers 0 to 65535"},
      {"resolve --distance -5", 3, "--distance must be a finite eye distance > 0, not -5"},
      {"resolve --technique layered --code 1", 3, "layered has one mapping per layer"},
      {"readback -t log_cesium --distances 0.5", 3,
       "--distances 0.5 is nearer than the near plane 1: log_cesium clips it"},
      {"readback -t standard --distances 2e9", 3,
       "--distances 2000000000 is beyond the far plane 1000000000: standard clips it"},
      {"readback -t standard -f float32 --far inf", 3,
       "far = inf: standard/float32/gl needs a finite far plane"},
      {"readback -t cesium", 3, "unknown technique 'cesium' (did you mean log_cesium?)"},
      {"readback --distances 0", 3, "'distances' must hold finite eye distances > 0, not 0"},
      {"readback --kernel 8x8", 2, "readback: --kernel has no effect: readback maps depths"},
      {"readback --profile llvmpipe", 2, "readback: --profile has no effect"},
      {"world --distances 5,10", 2, "world: --distances has no effect"},
      {"mts -t reversed standard", 3, "each option takes one value: list several with commas"},
      {"select --bits 40", 3, "--bits must be 2..32"},
      {"mts --bogus", 2, "--bogus"},
      {"mts --kernel 20", 2, "--kernel '20': expected WxH"},
      {"formats unorm33", 3, "unorm takes 1 to 32 bits"},
      {"formats e9m60", 3, "E = 1..8"},
  }));
  std::string args = args_in;  // mts cases run small, where the case itself does not set it
  if (args.rfind("mts", 0) == 0)
    for (const char* opt : {"--distances 2", "--frames 2", "--kernel 8x8"})
      if (args.find(std::string(opt).substr(0, std::string(opt).find(' '))) == std::string::npos)
        args += std::string(" ") + opt;
  const auto r = run_cli(args);
  INFO(args_in << "\n" << r.output);
  CHECK(r.exit_code == code);
  CHECK_THAT(r.output, Contains(says));
}

// Before, merge --help left out render, bias and --profiles, all of which it joins.
TEST_CASE("merge --help names every batch whose shards it joins", "[cli][batch]") {
  const auto r = run_cli("merge --help");
  REQUIRE(r.exit_code == 0);
  for (const char* batch : {"`mts`", "`table`", "`render`", "`compare`", "`lj-table`", "`tradeoff`",
                            "`cost`", "`pipelines`", "`advise`", "`bias`", "`mts --profiles`"}) {
    INFO(batch);
    CHECK_THAT(r.output, Contains(batch));
  }
}

// Before, a value binary32 cannot hold showed a relative error of 0: relative to d = 0.
TEST_CASE("formats says a value below binary32's range is lost whole, not stored exactly",
          "[cli]") {
  const auto r = run_cli("formats unorm24 float32 --value 1e-50");
  REQUIRE(r.exit_code == 0);
  CHECK_THAT(r.output,
             Contains("float32  1e-50             0     0         0x0       0  -1.000e+00"));
  CHECK_THAT(r.output, Contains("-1.000e+00") && !Contains("0.000e+00"));
  CHECK_THAT(r.output, Contains("--value 1e-50: below binary32's smallest positive value"));
  const auto j =
      nlohmann::json::parse(run_cli("formats float32 --value 1e-50 --format-out json").output);
  CHECK(j["round_trips"][0]["rel_error"] == -1.0);
  // 0 itself is stored exactly
  CHECK(nlohmann::json::parse(run_cli("formats float32 --value 0 --format-out json")
                                  .output)["round_trips"][0]["rel_error"] == 0.0);
}

TEST_CASE("bias says a slope factor has no slope to scale, not that it is unresolvable",
          "[cli][bias]") {
  // At tilt 0 the planes face the camera: 2 units separate them at 10^5, and no slope factor up
  // to 2^24 does, since their slope is all but 0 there. The same in every format.
  const std::string args =
      "bias --tilt 0 -t standard -f unorm24 --distances 1e5 --kernel 24x24 "
      "--frames 4 --no-timing -q";
  const auto json = run_cli(args + " --format-out json");
  REQUIRE(json.exit_code == 0);
  const auto row = nlohmann::json::parse(json.output).at("records").at(0).at("rows").at(0);
  CHECK(row.at("verdict") == "resolved");
  CHECK(row.at("factor").is_null());
  CHECK(row.at("factor_verdict") == "no_slope");
  const auto csv = run_cli(args + " --format-out csv");
  REQUIRE(csv.exit_code == 0);
  CHECK_THAT(csv.output, Contains(",resolved,no_slope,resolved") && !Contains("unresolvable"));
  const auto text = run_cli(args);
  REQUIRE(text.exit_code == 0);
  CHECK_THAT(text.output, Contains("  no_slope  ") && !Contains("unresolvable"));
  CHECK_THAT(text.output, Contains("the factor has nothing to scale"));
  // tilted, the slope is there to scale: a factor, and no such verdict
  const auto tilted = run_cli(
      "bias --tilt 45 -t standard -f unorm24 --distances 1e5 --kernel "
      "24x24 --frames 4 --no-timing -q --format-out json");
  REQUIRE(tilted.exit_code == 0);
  const auto t = nlohmann::json::parse(tilted.output).at("records").at(0).at("rows").at(0);
  CHECK(t.at("factor_verdict") == "resolved");
  CHECK(t.at("factor").get<double>() < 0);
}

// pipelines --list: every profile and every bound model once, the envelopes among them named as
// both, in each format; it measures nothing, so scene options are refused.
TEST_CASE("pipelines --list gives every profile and bound model, the envelopes as both",
          "[cli][envelope]") {
  const auto r = run_cli("pipelines --list --format-out json");
  REQUIRE(r.exit_code == 0);
  const auto list = nlohmann::json::parse(r.output);
  std::map<std::string, std::string> kind;
  for (const auto& i : list) {
    CHECK(kind.count(i["name"]) == 0);
    kind[i["name"]] = i["kind"];
    CHECK_FALSE(i["what"].get<std::string>().empty());
    CHECK_FALSE(i["source"].get<std::string>().empty());
  }
  for (const char* both :
       {"ideal", "llvmpipe", "softpipe", "gles_mediump", "gles2_highp", "d3d11", "vulkan_min"})
    CHECK(kind[both] == "profile and bound model");
  CHECK(kind["binary32"] == "bound model");
  CHECK(kind.size() == 8);
  const auto md = run_cli("pipelines --list --format-out markdown");
  REQUIRE(md.exit_code == 0);
  CHECK_THAT(md.output,
             Catch::Matches(R"([\s\S]*\| d3d11 +\| profile and bound model +\|[\s\S]*)"));
  CHECK_THAT(md.output, Contains("15.16 (8-bit snapping)"));
  const auto refused = run_cli("pipelines --list -t standard");
  CHECK(refused.exit_code == 2);
  CHECK_THAT(refused.output, Contains("takes no scene options"));
}
