// The orthographic technique on the system's OpenGL: the llvmpipe profile's emulation gives
// llvmpipe's MTS, within 0.1 %, on every row compared (`compare`).
#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "tests/support/run_cli.h"

TEST_CASE("orthographic renders on llvmpipe the MTS its llvmpipe profile emulates",
          "[render][orthographic]") {
  const auto r = depthprec::test::run_cli(
      "compare -t orthographic -f unorm24,float32 --distances 10,100,1e4 --profile llvmpipe "
      "--frames 20 -q --no-timing --format-out json");
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  const auto j = nlohmann::json::parse(r.output);
  size_t compared = 0;
  for (const auto& rec : j.at("records")) {
    INFO(rec.value("key", std::string()));
    CHECK(rec.at("ratio").get<double>() == Approx(1.0).epsilon(1e-3));
    ++compared;
  }
  CHECK(compared == 6);
}
