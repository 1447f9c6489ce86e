// `depthprec shadow` as a user runs it: the emulation below the proven biases (clean at them,
// acne 10 % below), the rendered check on the system's OpenGL, the three output formats and the
// errors bad input gets.
#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "tests/support/run_cli.h"

namespace depthprec::test {

namespace {

nlohmann::json shadow_json(const std::string& args) {
  const CliResult r = run_cli("shadow -q --format-out json " + args);
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  return nlohmann::json::parse(r.output);
}

}  // namespace

TEST_CASE("the emulation finds acne just below each proven bias and none at it", "[shadow]") {
  for (const std::string args :
       {"--format unorm16 --filter nearest", "--format float32 --reversed --filter pcf3",
        "--format unorm24 --filter tent5 --api d3d --slope-max 60"}) {
    INFO(args);
    const nlohmann::json j = shadow_json(args + " --splits 10,150 --planes 256 --engines bevy");
    REQUIRE(j["cascades"].size() == 2);
    for (const auto& c : j["cascades"]) {
      const auto& w = c["witnessed"];
      const auto& b = c["bound"];
      CHECK(w["bound_clean"].get<bool>());
      CHECK(w["acne_at_90_percent"].get<uint64_t>() > 0);
      // Tight: the emulation reaches within 5 % of each proven value.
      CHECK(w["constant_units"].get<double>() >= 0.95 * b["constant_units"].get<double>());
      CHECK(w["slope_factor"].get<double>() >= 0.95 * b["slope_factor"].get<double>());
      CHECK(w["normal_metres"].get<double>() >= 0.95 * b["normal_metres"].get<double>());
    }
  }
}

TEST_CASE("a shadow pass on the system's OpenGL has no acne at the proven biases",
          "[shadow][render]") {
  const nlohmann::json j =
      shadow_json("--source rendered --splits 10 --planes 64 --format unorm24 --filter pcf2x2");
  REQUIRE(j.contains("renderer"));
  const auto& r = j["cascades"][0]["rendered"];
  CHECK(r["clean_at_bound"].get<bool>());
  for (const char* recipe : {"constant", "slope", "normal"}) {
    INFO(recipe);
    CHECK(r[recipe]["acne_at_bound"].get<uint64_t>() == 0);
    CHECK(r[recipe]["acne_at_90_percent"].get<uint64_t>() > 0);
  }
  // The gap the constant costs a wall on level ground: the formula is the ray cast's, and the
  // rendered shadow's edge lies within 5 % of it (the gap spans several texels here).
  const auto& gap = r["gap"];
  const double raycast = gap["raycast"].get<double>();
  CHECK(gap["formula"].get<double>() == Approx(raycast).epsilon(1e-9));
  CHECK(gap["rendered"].get<double>() == Approx(raycast).epsilon(0.05));
  CHECK(raycast > 3 * j["cascades"][0]["texel"].get<double>());

  // The text output shows the same check: counts per recipe at the bound and at 90 % of it.
  const CliResult text = run_cli(
      "shadow -q --no-timing --source rendered --splits 10 --planes 64 --format unorm24 "
      "--filter pcf2x2");
  INFO(text.output);
  REQUIRE(text.exit_code == 0);
  CHECK_THAT(text.output, Catch::Contains("Rendered on " + j["renderer"].get<std::string>()));
  CHECK_THAT(text.output, Catch::Contains("acne at bound c/s/n"));
  const std::string at_90 = std::to_string(r["constant"]["acne_at_90_percent"].get<uint64_t>()) +
                            "/" + std::to_string(r["slope"]["acne_at_90_percent"].get<uint64_t>()) +
                            "/" + std::to_string(r["normal"]["acne_at_90_percent"].get<uint64_t>());
  CHECK_THAT(text.output, Catch::Contains("0/0/0") && Catch::Contains(at_90));
}

TEST_CASE("a spot light's proven biases hold in the emulation and on OpenGL", "[shadow][spot]") {
  const nlohmann::json j = shadow_json(
      "--light spot --spot-angle 60 --light-near 0.1 --light-far 50 --distances 2,10 "
      "--planes 256 --filter tent5 --source rendered");
  REQUIRE(j["cascades"].size() == 2);
  CHECK(j["light"] == "spot");
  for (const auto& c : j["cascades"]) {
    INFO("d = " << c["distance"]);
    CHECK(c["witnessed"]["bound_clean"].get<bool>());
    CHECK(c["rendered"]["clean_at_bound"].get<bool>());
    CHECK(c["engines"].empty());  // the engines' conversions are their directional lights'
  }
  // Near the light the proof is tight: the emulation reaches 90 % of the constant (94 % measured).
  const auto& near = j["cascades"][0];
  CHECK(near["witnessed"]["constant_units"].get<double>() >=
        0.9 * near["bound"]["constant_units"].get<double>());
  CHECK(near["rendered"]["constant"]["acne_at_90_percent"].get<uint64_t>() > 0);
}

TEST_CASE("shadow writes its cascades as text, CSV and JSON", "[shadow][cli]") {
  const std::string args = "shadow -q --source bound --engines bevy,unity ";
  const CliResult text = run_cli(args);
  REQUIRE(text.exit_code == 0);
  CHECK(text.output.find("150-600") != std::string::npos);
  CHECK(text.output.find("unity") != std::string::npos);
  const CliResult csv = run_cli(args + "--format-out csv");
  REQUIRE(csv.exit_code == 0);
  // A header and one row per cascade and engine.
  CHECK(std::count(csv.output.begin(), csv.output.end(), '\n') == 1 + 4 * 2);
  const nlohmann::json j = shadow_json("--source bound --engines bevy,unity");
  CHECK(j["cascades"].size() == 4);
  CHECK_FALSE(j["cascades"][0].contains("witnessed"));
  CHECK(j["cascades"][3]["engines"].size() == 2);
  // A spot light's rows are receiver distances, and the columns say so.
  const CliResult spot = run_cli(
      "shadow -q --source bound --light spot --light-near 0.1 --light-far 50 --distances 2,10");
  REQUIRE(spot.exit_code == 0);
  CHECK(spot.output.find("row  receiver d m") != std::string::npos);
  CHECK(spot.output.find("camera m") == std::string::npos);
}

TEST_CASE("shadow refuses bad input with exit 3 and says what is allowed", "[shadow][cli]") {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"--extent 0 --light-near -10 --light-far 10", "extent 0 m"},
      {"--extent 10 --light-near 5 --light-far 5", "near must lie below far"},
      {"--slope-max 90", "below 90"},
      {"--engines cryengine", "unknown engine 'cryengine'"},
      {"--filter pcf4", "odd N"},
      {"--format unorm32", "unorm16 (D16), unorm24 (D24) or float32"},
      {"--splits 10,5", "not beyond 10 m"},
      {"--splits 10 --extent 5 --light-near 0 --light-far 1", "not both"},
      {"--light lamp", "unknown light 'lamp'"},
      {"--light spot --splits 10", "--splits and --extent are a directional light's"},
      {"--light spot --distances 60 --light-far 50", "outside the spot light's near"},
      {"--light spot --spot-angle 180", "--spot-angle 180"},
      {"--distances 5", "--distances are a spot light's"},
      {"--spot-angle 30", "--spot-angle is a spot light's cone"},
  };
  for (const auto& [args, message] : cases) {
    INFO(args);
    const CliResult r = run_cli("shadow -q --source bound " + args);
    CHECK(r.exit_code == 3);
    CHECK(r.output.find(message) != std::string::npos);
  }
}

}  // namespace depthprec::test
