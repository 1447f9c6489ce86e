// The one description of the vertex stage (host/model/vertex_stage.h): the decision per transform
// and compose, and the claims that made the MTS's planes and the audit's draws one path bit for
// bit (vertex_stage.cpp): a product from the identity is the product from P, a plane's eye w is 1
// exactly, relative to eye the world row with the planes' z = 0 is the kernels' row, and the
// kernels' words read back are the description they were packed from.
#include "host/model/vertex_stage.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <cstring>
#include <glm/glm.hpp>
#include <string>
#include <vector>

#include "host/model/frame_setup.h"
#include "interface/binary16.h"
#include "interface/relative_to_eye.h"

using namespace depthprec;

namespace {

bool vs_same_bits(float a, float b) {
  return std::memcmp(&a, &b, sizeof a) == 0;
}

// A technique of each projection_row3 case (and two more), in both depth ranges.
std::vector<EvalPair> vs_pairs() {
  std::vector<EvalPair> out;
  for (const Technique t :
       {Technique::standard, Technique::infinite, Technique::reversed, Technique::reversed_infinite,
        Technique::inverse_w, Technique::linear, Technique::log_vertex})
    for (const DepthRange r : {DepthRange::gl, DepthRange::zero_to_one})
      out.push_back({t, "float32", r});
  return out;
}

}  // namespace

TEST_CASE("the vertex path follows transform and compose", "[vertex_stage]") {
  Pipeline p;
  p.transform = Transform::absolute;
  CHECK(vertex_path(p) == VertexPath::model_then_view);
  p.transform = Transform::camera_relative;
  CHECK(vertex_path(p) == VertexPath::model_view);
  p.compose = Compose::premultiplied;
  CHECK(vertex_path(p) == VertexPath::premultiplied);
  p.transform = Transform::absolute;
  CHECK(vertex_path(p) == VertexPath::premultiplied);
  p.transform = Transform::relative_to_eye;  // compose does not apply
  CHECK(vertex_path(p) == VertexPath::relative_to_eye);
}

TEST_CASE("a product from the identity is the product from P", "[vertex_stage]") {
  // I P = P entry for entry in both precisions, for every projection the MTS builds
  for (const std::string precision : {"float", "double"})
    for (const EvalPair& pair : vs_pairs()) {
      const Scene scene = load_scene("", {"pipeline.matrix_precision=" + precision});
      const ProbeConstants pc = probe_constants(scene, pair, 100.0);
      glm::dmat4 P(0.0);
      glm::mat4 Pf(0.0f);
      for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c) {
          P[c][r] = pc.P_full[r * 4 + c];
          Pf[c][r] = pc.P[r * 4 + c];
        }
      const glm::dmat4 IP = glm::dmat4(1.0) * P;
      const glm::mat4 IPf = glm::mat4(1.0f) * Pf;
      for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) {
          CHECK(std::memcmp(&IP[c][r], &P[c][r], sizeof(double)) == 0);
          CHECK(vs_same_bits(IPf[c][r], Pf[c][r]));
        }
    }
  // and premultiplied binary32 planes are glm's P * V * M of the separate path's matrices
  const std::string far = "world_position=[1e5,-3e4,2e5]";
  for (const EvalPair& pair : vs_pairs()) {
    const Scene sep = load_scene("", {far});
    const Scene pre = load_scene("", {far, "pipeline.compose=premultiplied"});
    const ProbeConstants pc = probe_constants(sep, pair, 30.0);
    glm::mat4 P(0.0f), V(1.0f);
    for (int r = 0; r < 4; ++r)
      for (int c = 0; c < 4; ++c) P[c][r] = pc.P[r * 4 + c];
    for (int i = 0; i < 3; ++i) V[3][i] = pc.view[i];
    for (int f = 0; f < 5; ++f) {
      const Mat4f m = plane_matrix(sep, pc, 30.5, f);
      glm::mat4 M(0.0f);
      for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c) M[c][r] = m[r * 4 + c];
      const glm::mat4 PVM = P * V * M;
      const Mat4f got = plane_matrix(pre, probe_constants(pre, pair, 30.0), 30.5, f);
      for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c) CHECK(vs_same_bits(got[r * 4 + c], PVM[c][r]));
    }
  }
}

TEST_CASE("a plane's eye w is 1 exactly", "[vertex_stage]") {
  // vertex_clip sets it; the kernels compute row 3 of M (mat_vec16): the same 1
  const EvalPair pair{Technique::standard, "float32", DepthRange::gl};
  for (const std::string precision : {"float", "double"})
    for (const std::string transform : {"absolute", "camera_relative"}) {
      const Scene scene =
          load_scene("", {"pipeline.matrix_precision=" + precision,
                          "pipeline.transform=" + transform, "world_position=[7e4,0,-1e3]"});
      const ProbeConstants pc = probe_constants(scene, pair, 3.0);
      const int g = scene.plane_subdivisions;
      for (int f = 0; f < scene.frames; f += 7) {
        const Mat4f m = plane_matrix(scene, pc, 3.25, f);
        for (int i = 0; i <= g; i += 3) {
          const float obj[4] = {grid_coordinate(g, i), grid_coordinate(g, g - i), 0.0f, 1.0f};
          CHECK(object_row_dot(m, 3, obj, VertexForm::separate) == 1.0f);
          CHECK(object_row_dot(m, 3, obj, VertexForm::fma) == 1.0f);
        }
      }
    }
}

TEST_CASE("relative to eye the world row with z = 0 is the kernels' row", "[vertex_stage]") {
  // world_row keeps W2 z, dp_rte_world_row (the kernels) leaves z = 0 out: the same eye coordinate
  // bit for bit, zero world coordinates of either sign included.
  const std::vector<double> values = {0.0, -0.0, 1.0, -1.0, 0.5, -3.0, 65536.0, 1e5 + 0.3};
  const std::vector<float> coords = {0.0f, -0.0f, 0.5f, -0.5f, 0.25f};
  const std::vector<double> eyes = {0.0, -0.0, 1.0, -1.0, 65536.0, -1e5 - 0.3};
  for (const double w0 : values)
    for (const double w2 : {0.0, -0.0, 2.0, -2.0})
      for (const double w3 : values)
        for (const float x : coords)
          for (const float y : coords)
            for (const double e : eyes) {
              Mat4d W = mat_identity();
              W[0] = w0;
              W[1] = -w0;
              W[2] = w2;
              W[3] = w3;
              float eh = 0, el = 0;
              dp_rte_encode(e, &eh, &el);
              const float obj[4] = {x, y, 0.0f, 1.0f};
              const float host = dp_rte_eye(world_row(W, 0, obj), eh, el);
              const float kernel = dp_rte_eye(dp_rte_world_row(W.data(), 0, x, y), eh, el);
              CHECK(vs_same_bits(host, kernel));
            }
}

TEST_CASE("the kernels' words read back are the vertex stage they were packed from",
          "[vertex_stage]") {
  const EvalPair pair{Technique::reversed, "float32", DepthRange::zero_to_one};
  for (const std::vector<std::string>& sets : std::vector<std::vector<std::string>>{
           {},
           {"world_position=[2e5,1,-3]"},
           {"world_position=[2e5,1,-3]", "pipeline.compose=premultiplied"},
           {"world_position=[2e5,1,-3]", "pipeline.transform=camera_relative"},
           {"world_position=[2e5,1,-3]", "pipeline.transform=relative_to_eye"},
           {"world_position=[2e5,1,-3]", "pipeline.matrix_precision=double"}}) {
    const Scene scene = load_scene("", sets);
    const ProbeConstants pc = probe_constants(scene, pair, 10.0);
    const int g = scene.plane_subdivisions;
    for (int f = 0; f < 3; ++f) {
      std::vector<float> words;
      append_plane_words(words, scene, pc, 10.125, f);
      REQUIRE(words.size() == plane_words(scene));
      const VertexStage packed = plane_vertex_stage(scene, pc, 10.125, f);
      const VertexStage read = read_plane_words(scene, pc, words.data());
      CHECK(read.path == packed.path);
      CHECK(read.view == packed.view);
      for (const VertexForm form : {VertexForm::separate, VertexForm::fma})
        for (int i = 0; i <= g; i += 2) {
          const float obj[4] = {grid_coordinate(g, i), grid_coordinate(g, i / 2), 0.0f, 1.0f};
          float a[4], b[4];
          vertex_clip(packed, pc.P, obj, form, a);
          vertex_clip(read, pc.P, obj, form, b);
          for (int k = 0; k < 4; ++k) CHECK(vs_same_bits(a[k], b[k]));
        }
    }
  }
}

TEST_CASE("mediump's rounding is the compiler's binary32-to-binary16 conversion",
          "[vertex_stage]") {
  // interface/binary16.h against GCC's _Float16 (IEEE binary16, to nearest, ties to even): every
  // 4099th binary32 (both signs, every binade), and the edges: the largest finite, the first
  // value that rounds to infinity, the subnormals' ends, ties either way.
  size_t compared = 0;
  auto check = [&](uint32_t bits) {
    float x;
    std::memcpy(&x, &bits, sizeof x);
    if (std::isnan(x)) return;
    const float expect = static_cast<float>(static_cast<_Float16>(x));
    INFO(std::hex << bits);
    REQUIRE(vs_same_bits(dp_binary16(x), expect));
    ++compared;
  };
  for (uint64_t u = 0; u < 0x100000000ull; u += 4099) check(static_cast<uint32_t>(u));
  for (const float x : {65504.0f, 65519.996f, 65520.0f, 0x1.0p-14f, 0x1.0p-24f, 0x1.8p-25f,
                        0x1.0p-25f, 2049.0f, 2051.0f, 1.00048828125f, 1.00146484375f})
    for (const float v : {x, -x}) {
      uint32_t b;
      std::memcpy(&b, &v, sizeof b);
      check(b);
    }
  CHECK(compared > 1000000);
  CHECK(dp_binary16(3000.5f) == 3000.0f);  // spacing 2 from 2048 on
  CHECK(std::isinf(dp_binary16(65520.0f)));
}

TEST_CASE("the GLSL ES 1.00 highp minimum rounds to 17 bits within 2^-62 .. 2^62",
          "[vertex_stage]") {
  // interface/binary16.h dp_es2_highp against binary64 arithmetic: the significand scaled to 17
  // bits and rounded to nearest, ties to even (nearbyint in the default rounding mode), the range
  // [2^-62, 2^62) kept, zero below, infinity from 2^62 (after rounding) on.
  size_t compared = 0;
  for (uint64_t u = 0; u < 0x100000000ull; u += 4099) {
    const auto bits = static_cast<uint32_t>(u);
    float x;
    std::memcpy(&x, &bits, sizeof x);
    if (std::isnan(x)) continue;
    double expect = x;
    if (std::isfinite(x) && x != 0) {
      int e = 0;
      const double m = std::frexp(static_cast<double>(x), &e);  // |m| in [0.5, 1)
      expect = std::ldexp(std::nearbyint(std::ldexp(m, 17)), e - 17);
      if (std::fabs(expect) >= 0x1.0p62) expect = std::copysign(INFINITY, x);
      if (std::fabs(static_cast<double>(x)) < 0x1.0p-62) expect = std::copysign(0.0, x);
    }
    INFO(std::hex << bits);
    REQUIRE(vs_same_bits(dp_es2_highp(x), static_cast<float>(expect)));
    ++compared;
  }
  CHECK(compared > 1000000);
  CHECK(dp_es2_highp(1.0f + 0x1.0p-17f) == 1.0f);  // a tie, to even
  CHECK(dp_es2_highp(1.0f + 0x1.8p-17f) == 1.0f + 0x1.0p-16f);
  CHECK(dp_shader_round(1.0f + 0x1.0p-20f, DP_SHADER_HIGHP) == 1.0f + 0x1.0p-20f);
}
