// `depthprec compare`: emulated against rendered (llvmpipe here and in CI), from a scene and from
// two JSON outputs, summarised, sharded and merged like every batch.
#include "host/analysis/compare.h"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "tests/support/run_cli.h"

using namespace depthprec;
using namespace depthprec::test;
using Catch::Matchers::Contains;
using nlohmann::json;

namespace {

const std::string kScene =
    "-t standard -f unorm16,float32 --distances 16,1024 --frames 4 --kernel 64x64";

const json* record_at(const json& doc, const std::string& format, double z) {
  for (const auto& r : doc.at("records"))
    if (r.at("format") == format && r.at("z").get<double>() == z) return &r;
  return nullptr;
}

}  // namespace

TEST_CASE("compare runs both and pairs them: storage-limited agrees, binary32 is optimistic",
          "[compare][render][cli]") {
  const std::string out = fresh("compare_scene.json");
  const CliResult r = run_cli("compare " + kScene + " --format-out json -o " + out);
  REQUIRE(r.exit_code == 0);
  const json j = json::parse(slurp(out));
  CHECK_THAT(j.at("gl_renderer").get<std::string>(), Contains("llvmpipe"));
  REQUIRE(j.at("records").size() == 4);
  for (const auto& rec : j.at("records")) {
    CHECK(rec.at("emulated").at("source") == "emulated");
    CHECK(rec.at("rendered").at("source") == "rendered");
    CHECK(rec.at("ratio").get<double>() ==
          rec.at("emulated_mts").get<double>() / rec.at("rendered_mts").get<double>());
  }
  // unorm16 at z = 16: one code is far wider than binary32 moves a depth; both agree.
  const json* storage = record_at(j, "unorm16", 16);
  REQUIRE(storage);
  CHECK(std::abs(storage->at("ratio").get<double>() - 1) < 0.01);
  // float32 at z = 1024: llvmpipe's set-up loses bits the idealised pipeline keeps.
  const json* arithmetic = record_at(j, "float32", 1024);
  REQUIRE(arithmetic);
  CHECK(arithmetic->at("ratio").get<double>() < 0.9);
  const json& s = j.at("summary");
  CHECK(s.at("rows") == 4);
  CHECK(s.at("both_resolved") == 4);
  CHECK(s.at("optimistic").get<int>() >= 1);
  CHECK(s.at("worst_ratio").get<double>() <= arithmetic->at("ratio").get<double>());
  REQUIRE(j.at("pairs").size() == 2);
}

TEST_CASE("compare pairs the rows of an mts and a render output", "[compare][render][cli]") {
  const std::string e = fresh("compare_emulated.json"), d = fresh("compare_rendered.json"),
                    whole = fresh("compare_whole.csv"), paired = fresh("compare_paired.csv");
  REQUIRE(run_cli("mts " + kScene + " --format-out json -o " + e).exit_code == 0);
  REQUIRE(run_cli("render " + kScene + " --format-out json -o " + d).exit_code == 0);
  REQUIRE(run_cli("compare --emulated " + e + " --rendered " + d + " --no-timing -o " + paired)
              .exit_code == 0);
  REQUIRE(run_cli("compare " + kScene + " --no-timing -o " + whole).exit_code == 0);
  CHECK(slurp(paired) == slurp(whole));
  // The CSV header names each column once: emulated and rendered MTS, ratio, both verdicts.
  const std::string csv = slurp(paired);
  CHECK(csv.substr(0, csv.find('\n')) ==
        "technique,format,depth_range,z,emulated,rendered,emu/rend,emu verdict,rend verdict");

  SECTION("the files must hold what their options say") {
    const CliResult swapped = run_cli("compare --emulated " + d + " --rendered " + e);
    CHECK(swapped.exit_code == 3);
    CHECK_THAT(swapped.output, Contains("holds rendered rows where emulated ones belong"));
    const CliResult alone = run_cli("compare --emulated " + e);
    CHECK(alone.exit_code == 2);
    CHECK_THAT(alone.output, Contains("--emulated and --rendered go together"));
    const CliResult with_scene =
        run_cli("compare --emulated " + e + " --rendered " + d + " -t linear");
    CHECK(with_scene.exit_code == 2);
    CHECK_THAT(with_scene.output, Contains("drop the scene options"));
  }
}

TEST_CASE("compare shards merge into the whole comparison", "[compare][render][cli][batch]") {
  const std::string a = fresh("compare_part1.json"), b = fresh("compare_part2.json"),
                    merged = fresh("compare_merged.json"), whole = fresh("compare_all.json");
  const std::string common = "compare " + kScene + " --no-timing --format-out json ";
  REQUIRE(run_cli(common + "--shard 1/2 -o " + a).exit_code == 0);
  REQUIRE(run_cli(common + "--shard 2/2 -o " + b).exit_code == 0);
  REQUIRE(run_cli(common + "-o " + whole).exit_code == 0);
  REQUIRE(
      run_cli("merge " + a + " " + b + " --no-timing --format-out json -o " + merged).exit_code ==
      0);
  json m = json::parse(slurp(merged)), w = json::parse(slurp(whole));
  CHECK(m.at("records").size() == 4);
  CHECK(m.at("summary") == w.at("summary"));
  CHECK(m.at("pairs") == w.at("pairs"));
  for (size_t i = 0; i < 4; ++i)
    CHECK(m["records"][i]["rendered_mts"] == w["records"][i]["rendered_mts"]);
}

TEST_CASE("the summary counts ratios against 1.1x, 2x and the bisection's precision", "[compare]") {
  const auto rec = [](double z, double ratio) {
    json r = {{"technique", "standard"},
              {"format", "float32"},
              {"depth_range", "gl"},
              {"z", z},
              {"emulated_mts", ratio},
              {"rendered_mts", 1.0},
              {"emulated_verdict", "resolved"},
              {"rendered_verdict", "resolved"},
              {"emulated", json::object()},
              {"rendered", json::object()}};
    r["ratio"] = ratio;
    return r;
  };
  std::vector<json> records = {rec(1, 1.0), rec(2, 0.95), rec(4, 0.5), rec(8, 3.0),
                               rec(16, 1.0005)};
  json unresolved = rec(32, 1);
  unresolved.erase("ratio");
  unresolved["rendered_verdict"] = "unresolvable";
  records.push_back(unresolved);
  const CompareSummary s = summarise(records, 1.0 / 1024);
  CHECK(s.rows == 6);
  CHECK(s.both_resolved == 5);
  CHECK(s.within_1_1 == 3);
  CHECK(s.within_2 == 4);
  CHECK(s.optimistic == 2);   // 0.95 and 0.5; 1.0005 is within the bisection's precision
  CHECK(s.pessimistic == 1);  // 3.0
  CHECK(s.verdicts_differ == 1);
  CHECK(s.worst_ratio == 3.0);
  CHECK(s.median_ratio == 1.0);
}

// Found by the shard fuzzer (tests/fuzz/shard_fuzzer.cpp): a compare shard whose record lacks a
// field, and a shard whose "shard" is a number, made merge end in an internal error (exit 1); a
// row count of 4.8e58 was undefined behaviour.
TEST_CASE("fuzzer regressions: damaged shards are input errors naming what is wrong",
          "[compare][fuzz]") {
  const auto number = run_cli("merge '" + std::string(DEPTHPREC_SOURCE_DIR) +
                              "/tests/fuzz/regressions/shard-with-a-number-for-its-shard.json'");
  CHECK(number.exit_code == 3);
  CHECK_THAT(number.output, Contains("not a JSON output it can merge"));
  // A count of 4.8e58 was converted to an integer with undefined behaviour (UBSan).
  const auto huge = run_cli("merge '" + std::string(DEPTHPREC_SOURCE_DIR) +
                            "/tests/fuzz/regressions/shard-with-a-count-of-4.8e58.json'");
  CHECK(huge.exit_code == 3);
  CHECK_THAT(huge.output, Contains("must be a count"));
  const auto r = run_cli("merge '" + std::string(DEPTHPREC_SOURCE_DIR) +
                         "/tests/fuzz/regressions/shard-compare-record-without-verdict.json'");
  CHECK(r.exit_code == 3);
  CHECK_THAT(r.output, Contains("compare record") && Contains("is missing or not a string"));
  json record = {{"technique", "standard"},
                 {"format", "unorm24"},
                 {"depth_range", "gl"},
                 {"z", 2},
                 {"emulated_mts", 1},
                 {"rendered_mts", 2},
                 {"emulated_verdict", "resolved"},
                 {"rendered_verdict", "resolved"},
                 {"emulated", json::object()},
                 {"rendered", json::object()}};
  CHECK_NOTHROW(check_compare_record(record));
  record["ratio"] = "0.5";
  CHECK_THROWS_WITH(check_compare_record(record), Contains("'ratio' is not a number"));
  record.erase("ratio");
  record["z"] = "2";
  CHECK_THROWS_WITH(check_compare_record(record), Contains("'z' is missing or not a number"));
}
