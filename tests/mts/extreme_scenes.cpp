// The extreme suite (data/extreme/): every row of every scene ends as a number or a defined
// verdict, nothing prints NaN, nothing resolved lies below the vertex bound, and where the
// verdict is known in advance (data/extreme/expected.json) it is that one.
#include <catch2/catch.hpp>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <vector>

#include "tests/support/run_cli.h"

using depthprec::test::run_cli;
using nlohmann::json;

namespace {

const std::string kDir = std::string(DEPTHPREC_SOURCE_DIR) + "/data/extreme/";

double number(const json& v) {
  if (v.is_number()) return v.get<double>();
  if (v == "inf") return INFINITY;
  return NAN;  // "nan" or anything else: a failure below
}

// NaN in a JSON output is null (nlohmann) or the string "nan" (host/base/json_number.h).
int nan_values(const json& j) {
  if (j.is_null() || j == "nan" || (j.is_number_float() && std::isnan(j.get<double>()))) return 1;
  int n = 0;
  if (j.is_structured())
    for (const auto& v : j) n += nan_values(v);
  return n;
}

void check_scene(const std::string& name) {
  const auto r = run_cli("mts " + kDir + name + ".json --no-timing --format-out json");
  std::ifstream in(kDir + "expected.json");
  const json expected = json::parse(in);
  for (const auto& e : expected)
    if (e["scene"] == name &&
        e.contains("refused")) {  // a set-up with no measurement: exit 3, saying why
      INFO(r.output);
      CHECK(r.exit_code == 3);
      CHECK(r.output.find(e["refused"].get<std::string>()) != std::string::npos);
      return;
    }
  REQUIRE(r.exit_code == 0);
  const json out = json::parse(r.output);
  CHECK(nan_values(out) == 0);
  const std::set<std::string> verdicts = {
      "resolved",  "unresolvable",       "non_finite",       "clipped",
      "uncovered", "below vertex bound", "beyond far plane", "nearer than near plane"};
  REQUIRE(out["rows"].size() == out["scene"]["evaluate"].size() * out["scene"]["distances"].size());
  // Rows each expected verdict of this scene applied to: an entry that matches none asserts
  // nothing, and fails below.
  std::vector<int> matched(expected.size(), 0);
  for (const auto& row : out["rows"]) {
    const std::string where = row["technique"].get<std::string>() + "/" +
                              row["format"].get<std::string>() + "/" +
                              row["depth_range"].get<std::string>() + " z=" + row["z"].dump();
    INFO(name << ": " << where);
    const std::string v = row["verdict"];
    CHECK(verdicts.count(v) == 1);
    const double mts = number(row["mts"]);
    CHECK_FALSE(std::isnan(mts));
    if (v == "resolved") {
      CHECK(std::isfinite(mts));
      CHECK(mts >=
            row["vertex_bound"].get<double>());  // never a separation the vertices cannot hold
      CHECK(row["flags"].get<std::string>().find("clipped") == std::string::npos);
    } else {
      CHECK(std::isinf(mts));
    }
    // bounded: doubling, bisection, stiffness; under worst-case sampling as much again per chunk
    // of orientations (a probe of the chunk, and the search of an orientation that fought)
    const auto chunks = (row["orientations"].get<long>() - out["scene"]["frames"].get<long>()) /
                        out["scene"]["worst_case"]["round_size"].get<long>();
    CHECK(row["probes"].get<long>() <= 120 * (1 + chunks));
    for (size_t k = 0; k < expected.size(); ++k) {
      const json& e = expected[k];
      if (e["scene"] != name) continue;
      if (e.contains("technique") && e["technique"] != row["technique"]) continue;
      if (e.contains("format") && e["format"] != row["format"]) continue;
      if (e.contains("depth_range") && e["depth_range"] != row["depth_range"]) continue;
      if (e.contains("z_above") && !(row["z"].get<double>() > e["z_above"].get<double>())) continue;
      INFO("expected because " << e["why"].get<std::string>());
      CHECK(v == e["verdict"].get<std::string>());
      ++matched[k];
    }
  }
  for (size_t k = 0; k < expected.size(); ++k)
    if (expected[k]["scene"] == name) {
      INFO("data/extreme/expected.json entry " << k << ": " << expected[k].dump());
      CHECK(matched[k] > 0);
    }
}

}  // namespace

// One test per scene, so ctest -j spreads them.
TEST_CASE("extreme near_equals_far", "[extreme]") {
  check_scene("near_equals_far");
}
TEST_CASE("extreme far_1e12", "[extreme]") {
  check_scene("far_1e12");
}
TEST_CASE("extreme far_1e30", "[extreme]") {
  check_scene("far_1e30");
}
TEST_CASE("extreme far_infinite", "[extreme]") {
  check_scene("far_infinite");
}
TEST_CASE("extreme far_infinite_refused", "[extreme]") {
  check_scene("far_infinite_refused");
}
TEST_CASE("extreme near_tiny", "[extreme]") {
  check_scene("near_tiny");
}
TEST_CASE("extreme near_huge", "[extreme]") {
  check_scene("near_huge");
}
TEST_CASE("extreme log_k_small", "[extreme]") {
  check_scene("log_k_small");
}
TEST_CASE("extreme log_k_large", "[extreme]") {
  check_scene("log_k_large");
}
TEST_CASE("extreme denormal", "[extreme]") {
  check_scene("denormal");
}
TEST_CASE("extreme small_formats", "[extreme]") {
  check_scene("small_formats");
}
TEST_CASE("extreme beyond_far", "[extreme]") {
  check_scene("beyond_far");
}
