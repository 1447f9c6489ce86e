// The bound's term for softpipe's 16-bit fast path (host/mts/mts_bound.h, stepped_code_drift)
// against that path's own arithmetic (Mesa's sp_quad_depth_test_tmp.h): a run of quads stores
// its first quad's codes, (ushort)(z0 * 65535.0f) for each of its pixels, plus dx times
// (ushort)(dzdx * 65535.0f), dx the quad's offset in the run (0, 2, ..., 14: flush_spans' chunks
// of 16 pixels). Over random planes the stored code never lies further from z N than the
// conversion's own width (softpipe's truncation, 1 + 2^-8 codes) plus the drift term.
#include <fmt/format.h>

#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <random>
#include <string>

#include "host/model/bound_model.h"
#include "host/model/scene.h"
#include "host/mts/mts_bound.h"

using namespace depthprec;

namespace {

// C's (ushort) of a float as x86's compilers do it: through a signed integer, wrapping.
uint16_t to_ushort(float v) {
  return static_cast<uint16_t>(static_cast<int32_t>(v));
}

}  // namespace

TEST_CASE("softpipe's stepped 16-bit codes stay within the bound's drift term", "[bound][proof]") {
  std::mt19937_64 rng(20261128);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const double n = 65535.0, width = 1.00390625;  // softpipe's unorm16 width (bound_model.cpp)
  const int kSteps = 14;
  // the models that hold softpipe's choices take this path's run length
  CHECK(bound_model("softpipe").unorm16_step_pixels == kSteps);
  CHECK(bound_model("binary32").unorm16_step_pixels == kSteps);
  CHECK(bound_model("llvmpipe").unorm16_step_pixels == 0);
  double worst = 0;  // the largest share of the allowance taken
  long checked = 0, beyond = 0;
  std::string first_beyond;
  for (int trial = 0; trial < 2000000; ++trial) {
    const float z0 = static_cast<float>(unit(rng));
    // gradients from 10^-4 to 10^2 codes per pixel, either sign
    const double codes = std::pow(10.0, -4 + 6 * unit(rng)) * (unit(rng) < 0.5 ? -1 : 1);
    const float dzdx = static_cast<float>(codes / n);
    const float dzdy = static_cast<float>(std::pow(10.0, -4 + 6 * unit(rng)) / n);
    // the quad's four pixels, each with its own first code (the path's init_idepth[0..3])
    for (const int j : {0, 1, 2, 3}) {
      const float zj = j == 0 ? z0 : j == 1 ? z0 + dzdx : j == 2 ? z0 + dzdy : z0 + dzdx + dzdy;
      const uint16_t first = to_ushort(zj * 65535.0f);
      const uint16_t step = to_ushort(dzdx * 65535.0f);
      for (int dx = 0; dx <= kSteps; dx += 2) {
        const double z = static_cast<double>(zj) + dx * static_cast<double>(dzdx);
        if (!(z >= 0 && z < 1) || !(zj >= 0 && zj < 1)) continue;  // outside the buffer's range
        const auto code = static_cast<uint16_t>(first + dx * step);
        const double off = static_cast<double>(code) - z * n;  // truncation: in (-width, 0]
        const double allowed = width + stepped_code_drift(dzdx * 65535.0, dx);
        if (!(std::fabs(off) <= allowed) && beyond++ == 0)
          first_beyond = fmt::format("z0 {} dzdx {} dx {}: code {}, {} codes off, allowed {}", z0,
                                     dzdx, dx, code, off, allowed);
        worst = std::max(worst, std::fabs(off) / allowed);
        ++checked;
      }
    }
  }
  INFO(first_beyond);
  CHECK(beyond == 0);
  CHECK(checked > 40000000);
  // the term is reached, not just respected: some run drifts most of a code per pixel
  CHECK(worst > 0.9);
}

TEST_CASE("the drift decides a unorm16 row near the near plane under softpipe's model only",
          "[bound]") {
  // At z = 1.005 a plane's depth changes by about a 16-bit code per pixel, so the drift, up to 14
  // codes per plane, outweighs the conversion's own width: the bound under softpipe's model is
  // many times llvmpipe's, whose conversion is per pixel. unorm24 rows take no drift.
  for (const char* format : {"unorm16", "unorm24"}) {
    INFO(format);
    const EvalPair pair{Technique::reversed, format, DepthRange::zero_to_one};
    const auto bound_under = [&](const char* model) {
      return mts_bound(load_scene("", {std::string("bound_model=") + model}), pair, 1.005).s;
    };
    const double softpipe = bound_under("softpipe"), llvmpipe = bound_under("llvmpipe");
    if (std::string(format) == "unorm16")
      CHECK(softpipe > 8 * llvmpipe);
    else
      CHECK(softpipe < 2 * llvmpipe);
  }
}
