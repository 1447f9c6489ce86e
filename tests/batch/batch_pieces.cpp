// The pieces every batch command is made of (host/batch/batch.h), without the command line
// around them: shards, the journal of finished rows, the batch loop, and how two runs' JSON
// differ. The frame batches of the probe loop are another batch: tests/mts/probe.cpp.
#include <catch2/catch.hpp>
#include <cstdio>
#include <fstream>

#include "host/base/errors.h"
#include "host/batch/batch.h"
#include "tests/support/run_cli.h"

using namespace depthprec;
using Catch::Matchers::Contains;

TEST_CASE("a shard holds every N-th unit from its index", "[batch][unit]") {
  const Shard s = Shard::parse("2/3");
  CHECK(s.index == 1);
  CHECK(s.count == 3);
  std::vector<size_t> held;
  for (size_t k = 0; k < 9; ++k)
    if (s.holds(k)) held.push_back(k);
  CHECK(held == std::vector<size_t>{1, 4, 7});
  CHECK(Shard::parse("").count == 1);
  for (const char* bad : {"0/3", "4/3", "1/0", "a/b", "1/2/3"}) {
    INFO(bad);
    CHECK_THROWS_AS(Shard::parse(bad), Error);
  }
}

TEST_CASE("the journal keeps finished records, refuses to be overwritten and resumes",
          "[batch][unit]") {
  const std::string out = test::fresh("/tmp/depthprec_test_pieces.json");
  const nlohmann::json run = {{"kind", "test"}, {"scene", {{"frames", 10}}}};
  {
    RowJournal j(out, false, run);
    REQUIRE(j.active());
    j.append({{"key", "a"}, {"v", 1}});
    j.append({{"key", "b"}, {"v", 2}});
  }
  std::ofstream(out + ".rows.jsonl", std::ios::app)
      << "{\"key\": \"c\", \"v\"";  // a line cut by a crash
  CHECK_THROWS_WITH(RowJournal(out, false, run), Contains("--resume"));
  // Another run's journal is refused, naming what differs.
  const nlohmann::json other = {{"kind", "test"}, {"scene", {{"frames", 100}}}};
  CHECK_THROWS_WITH(RowJournal(out, true, other),
                    Contains("written by another run") && Contains("scene.frames: 10 against 100"));
  RowJournal resumed(out, true, run);
  REQUIRE(resumed.earlier().size() == 2);  // the incomplete line is not a record
  CHECK(resumed.earlier()[1]["v"] == 2);
  // run_batch computes only what the journal lacks and returns every record in unit order
  int computed = 0;
  std::vector<BatchUnit> units;
  for (const char* key : {"a", "b", "c"})
    units.push_back({key, [&computed, key]() {
                       ++computed;
                       return nlohmann::json{{"v", std::string(key)}};
                     }});
  const auto records = run_batch(units, resumed, Shard{}, "test", false, {});
  CHECK(computed == 1);
  REQUIRE(records.size() == 3);
  CHECK(records[2]["key"] == "c");
  resumed.remove();
  CHECK_FALSE(std::ifstream(out + ".rows.jsonl").good());
  CHECK_FALSE(RowJournal("", false, run).active());
  // A file that does not start by naming its run is no journal of this program.
  std::ofstream(out + ".rows.jsonl") << "{\"key\": \"a\", \"v\": 1}\n";
  CHECK_THROWS_WITH(RowJournal(out, true, run), Contains("not a journal this depthprec wrote"));
  std::remove((out + ".rows.jsonl").c_str());
}

TEST_CASE("first_difference names the first field two JSON values differ in", "[batch][unit]") {
  const nlohmann::json a = {{"scene", {{"near", 1}, {"far", 1e9}}}, {"shard", ""}};
  CHECK(first_difference(a, a).empty());
  nlohmann::json b = a;
  b["scene"]["far"] = 1e4;
  CHECK(first_difference(a, b) == "scene.far: 1000000000.0 against 10000.0");
  b = a;
  b.erase("shard");
  CHECK(first_difference(a, b) == "shard: \"\" against nothing");
  b = a;
  b["extra"] = true;
  CHECK(first_difference(a, b) == "extra: nothing against true");
}
