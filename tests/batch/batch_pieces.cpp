// The pieces every batch is made of, without the command line around them: shards, the journal
// of finished rows, the batch loop, and the fold of a launch's row words into probe outcomes.
#include <catch2/catch.hpp>
#include <cstdio>
#include <fstream>

#include "host/base/errors.h"
#include "host/batch/batch.h"
#include "host/mts/mts_evaluator.h"
#include "kernels/mts_layout.h"
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

TEST_CASE("a launch's row words fold into each probe's first deciding frame", "[batch][unit]") {
  // two active probes (results 0 and 2 of three), two frames, two kernel rows each
  const size_t kh = 2;
  const uint32_t pairs = 10u << R_COUNT_SHIFT;
  const std::vector<uint32_t> rows = {
      pairs,
      pairs,  // probe 0, frame 0: clean
      pairs | R_FIGHT,
      pairs,  // probe 0, frame 1: a fight
      pairs | R_CLIPPED,
      pairs,  // probe 2, frame 0: clipped
      pairs,
      pairs | R_NONFINITE,  // probe 2, frame 1: non-finite
  };
  std::vector<ProbeResult> results(3);
  std::vector<bool> decided(3, false);
  uint64_t after = 0;
  const auto per_probe = fold_launch(rows, {0, 2}, 0, 2, kh, results, decided, after);
  CHECK(per_probe == std::vector<uint64_t>{40, 40});
  CHECK(results[0].outcome == Outcome::fight);
  CHECK(results[0].frames == 2);
  CHECK(results[2].outcome == Outcome::non_finite);
  CHECK(results[2].any_clipped);
  CHECK(decided == std::vector<bool>{true, false, true});
  CHECK(after == 0);  // both were decided in their last frame
  CHECK(undecided(decided) == std::vector<size_t>{1});
}
