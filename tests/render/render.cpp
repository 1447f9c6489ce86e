// `depthprec render` on the system's OpenGL (Mesa llvmpipe here and in CI): rendered rows checked
// against the emulation where both are storage-limited, against the verdicts standard must give
// beyond 2^23, against an independent rendering written from the paper's description, and the
// refusals a user meets. Frames and distances are cut down so the suite stays fast.
#include <epoxy/gl.h>
#include <fmt/format.h>

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstring>
#include <nlohmann/json.hpp>

#include "host/base/errors.h"
#include "host/bias/bias_evaluator.h"
#include "host/bias/bias_search.h"
#include "host/model/frame_setup.h"
#include "host/model/profile.h"
#include "host/mts/mts_search.h"
#include "host/mts/reference_pipeline.h"
#include "host/mts/worst_case.h"
#include "host/render/gl_context.h"
#include "host/render/gl_program.h"
#include "host/render/render_bias.h"
#include "host/render/render_evaluator.h"
#include "host/runtime/kernel_variant.h"
#include "tests/support/mts_fixture.h"
#include "tests/support/run_cli.h"

using namespace depthprec;
using namespace depthprec::test;
using Catch::Matchers::Contains;
using Catch::Matchers::WithinRel;

namespace {

GlContext& gl() {
  static GlContext context;
  return context;
}

std::vector<MtsRow> rendered_rows(const Scene& scene, const EvalPair& pair,
                                  const std::vector<double>& zs) {
  RenderEvaluator ev(gl(), scene, pair);
  return search_pair(ev, scene, pair, zs);
}

// An independent rendering of one probe, written from Gilg et al.'s description and nothing of
// RenderEvaluator: per frame, clear, draw plane A white, plane B black with the technique's depth
// test, read the kernel's colour back; any black pixel fights. One frame at a time, immediate
// uniforms, no scissor, no channel tricks.
class PaperRendering {
 public:
  PaperRendering(const Scene& scene, const EvalPair& pair) : scene_(scene), pair_(pair) {
    gl();  // the context current on this thread
    const TechniqueInfo& ti = info(depth_path(scene, pair.technique));
    const std::string head = fmt::format(
        "#version 450 core\n#define DEPTH_FROM {}\n#define FRAG_DEPTH {}\n#define VERTEX_LOG {}\n"
        "#define DEPTH_RANGE_GL {}\n#define COMPOSE_PREMULTIPLIED 0\n",
        static_cast<int>(ti.from), static_cast<int>(ti.fragment), static_cast<int>(vertex_log(ti)),
        pair.depth_range == DepthRange::gl ? 1 : 0);
    program_ = glCreateProgram();
    for (auto [stage, path] : {std::pair{GL_VERTEX_SHADER, "host/render/shaders/plane.vert"},
                               std::pair{GL_FRAGMENT_SHADER, "host/render/shaders/plane.frag"}}) {
      const std::string text = head + glsl_source(path);
      const char* src = text.c_str();
      const GLuint sh = glCreateShader(stage);
      glShaderSource(sh, 1, &src, nullptr);
      glCompileShader(sh);
      glAttachShader(program_, sh);
    }
    glLinkProgram(program_);
    const int g = scene.plane_subdivisions;
    for (int t = 0; t < 2 * g * g; ++t) {  // quad by quad, lower-left diagonal
      const int q = t / 2, a = (q / g) * (g + 1) + q % g;
      const int tri[3] = {a, (t & 1) ? a + g + 2 : a + 1, (t & 1) ? a + g + 1 : a + g + 2};
      for (int v : tri) {
        vertices_.push_back(static_cast<float>(v % (g + 1)) / static_cast<float>(g) - 0.5f);
        vertices_.push_back(static_cast<float>(v / (g + 1)) / static_cast<float>(g) - 0.5f);
      }
    }
    glCreateVertexArrays(1, &vao_);
    glCreateBuffers(1, &vbo_);
    glNamedBufferData(vbo_, static_cast<GLsizeiptr>(vertices_.size() * sizeof(float)),
                      vertices_.data(), GL_STATIC_DRAW);
    glVertexArrayVertexBuffer(vao_, 0, vbo_, 0, 2 * sizeof(float));
    glEnableVertexArrayAttrib(vao_, 0);
    glVertexArrayAttribFormat(vao_, 0, 2, GL_FLOAT, GL_FALSE, 0);
    glVertexArrayAttribBinding(vao_, 0, 0);
    glCreateFramebuffers(1, &fbo_);
    glCreateRenderbuffers(1, &colour_);
    glCreateRenderbuffers(1, &depth_);
    glNamedRenderbufferStorage(colour_, GL_RGBA8, scene.viewport_w, scene.viewport_h);
    glNamedRenderbufferStorage(depth_, gl_depth_format(pair.format).internal, scene.viewport_w,
                               scene.viewport_h);
    glNamedFramebufferRenderbuffer(fbo_, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, colour_);
    glNamedFramebufferRenderbuffer(fbo_, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth_);
  }
  ~PaperRendering() {
    glDeleteFramebuffers(1, &fbo_);
    glDeleteRenderbuffers(1, &colour_);
    glDeleteRenderbuffers(1, &depth_);
    glDeleteBuffers(1, &vbo_);
    glDeleteVertexArrays(1, &vao_);
    glDeleteProgram(program_);
  }

  bool fights(double z, double s) {
    const ProbeConstants pc = probe_constants(scene_, pair_, z);
    const bool greater = info(depth_path(scene_, pair_.technique)).greater;
    const int kw = scene_.kernel_w, kh = scene_.kernel_h;
    std::vector<uint8_t> rgba(4 * static_cast<size_t>(kw * kh));
    glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
    glDisable(GL_SCISSOR_TEST);
    glViewport(0, 0, scene_.viewport_w, scene_.viewport_h);
    glClipControl(GL_LOWER_LEFT,
                  pair_.depth_range == DepthRange::gl ? GL_NEGATIVE_ONE_TO_ONE : GL_ZERO_TO_ONE);
    glUseProgram(program_);
    glBindVertexArray(vao_);
    const auto set = [this](const char* name, float v) {
      glUniform1f(glGetUniformLocation(program_, name), v);
    };
    set("near_plane", pc.near);
    set("far_plane", pc.far);
    set("depth_range", pc.range);
    set("log_k", pc.log_k);
    set("log_L", pc.log_L);
    set("threejs_fc", pc.threejs_fc);
    set("cesium_far1", pc.cesium_far1);
    set("cesium_inv_log2", pc.cesium_inv_log2);
    glUniformMatrix4fv(glGetUniformLocation(program_, "P"), 1, GL_TRUE, pc.P.data());
    const GLint mv = glGetUniformLocation(program_, "MV"),
                colour = glGetUniformLocation(program_, "colour");
    for (int f = 0; f < scene_.frames; ++f) {
      glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
      glDepthMask(GL_TRUE);
      glClearColor(0.5f, 0.5f, 0.5f, 1.0f);
      glClearDepth(greater ? 0.0 : 1.0);
      glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
      glEnable(GL_DEPTH_TEST);
      glDepthFunc(greater ? GL_GEQUAL : GL_LEQUAL);
      glUniformMatrix4fv(mv, 1, GL_TRUE, plane_matrix(scene_, pc, z, f).data());
      glUniform4f(colour, 1, 1, 1, 1);
      glDrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(vertices_.size() / 2));
      glUniformMatrix4fv(mv, 1, GL_TRUE, plane_matrix(scene_, pc, z + s, f).data());
      glUniform4f(colour, 0, 0, 0, 1);
      glDrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(vertices_.size() / 2));
      glReadPixels((scene_.viewport_w - kw) / 2, (scene_.viewport_h - kh) / 2, kw, kh, GL_RGBA,
                   GL_UNSIGNED_BYTE, rgba.data());
      bool black = false, grey = false;
      for (size_t i = 0; i < rgba.size(); i += 4) {
        black |= rgba[i] == 0;
        grey |= rgba[i] == 128;
      }
      REQUIRE_FALSE(grey);  // every kernel pixel covered by a plane
      if (black) return true;
    }
    return false;
  }

  // docs/spec.md 5.2, written out: from s = z double while fighting, then bisect at the midpoint
  // until (hi - lo) / hi <= rel_precision.
  double mts(double z) {
    double lo = 0, hi = z;
    while (fights(z, hi)) {
      lo = hi;
      hi *= 2;
      REQUIRE(hi <= scene_.max_separation_factor * z);
    }
    while ((hi - lo) / hi > scene_.rel_precision) {
      const double mid = 0.5 * (lo + hi);
      (fights(z, mid) ? lo : hi) = mid;
    }
    return hi;
  }

 private:
  const Scene& scene_;
  EvalPair pair_;
  std::vector<float> vertices_;
  GLuint program_ = 0, vao_ = 0, vbo_ = 0, fbo_ = 0, colour_ = 0, depth_ = 0;
};

}  // namespace

TEST_CASE("a storage-limited pair renders the MTS the emulation gives", "[render]") {
  const Scene scene = load_scene("", {"frames=10"});
  const EvalPair pair{Technique::standard, "unorm16", DepthRange::gl};
  const MtsRow rendered = rendered_rows(scene, pair, {16.0}).front();
  const MtsRow emulated =
      mts_rows(scene, pair.technique, pair.format, pair.depth_range, {16.0}).front();
  CHECK(rendered.source == RowSource::rendered);
  REQUIRE(rendered.verdict() == Verdict::resolved);
  // unorm16 at z = 16 with near 1: a code spans 3.9e-3 of eye distance, far more than binary32
  // arithmetic moves a depth, so storage decides and the two agree within a few bisection steps.
  CHECK_THAT(rendered.mts, WithinRel(emulated.mts, 0.01));
  CHECK(rendered.frames > 0);
  CHECK(rendered.fragment_pairs == rendered.frames * 200u * 200u);
}

TEST_CASE("standard float32 renders unresolvable beyond 2^23 and resolved at 2^23", "[render]") {
  const Scene scene = load_scene("", {"frames=10"});
  const EvalPair pair{Technique::standard, "float32", DepthRange::gl};
  const auto rows = rendered_rows(scene, pair, {8388608.0, 16777216.0, 33554432.0});
  CHECK(rows[0].verdict() == Verdict::resolved);
  CHECK(rows[0].mts > 8388608.0);  // above z itself: more than a doubling
  CHECK(rows[1].verdict() == Verdict::unresolvable);
  CHECK(rows[2].verdict() == Verdict::unresolvable);
}

TEST_CASE("render agrees with an independent rendering of the measurement", "[render]") {
  const Scene scene = load_scene("", {"frames=6", "kernel=[64,64]", "viewport=[64,64]"});
  for (const EvalPair& pair : {EvalPair{Technique::standard, "float32", DepthRange::gl},
                               EvalPair{Technique::reversed, "unorm24", DepthRange::zero_to_one},
                               EvalPair{Technique::log_fragment, "float32", DepthRange::gl}}) {
    for (double z : {2.0, 1024.0}) {
      CAPTURE(pair.label(), z);
      PaperRendering paper(scene, pair);
      const MtsRow row = rendered_rows(scene, pair, {z}).front();
      REQUIRE(row.verdict() == Verdict::resolved);
      CHECK(row.mts == paper.mts(z));
    }
  }
}

TEST_CASE("an uncovered kernel pixel or a clipped plane is never a clean probe", "[render]") {
  SECTION("planes smaller than the view leave kernel pixels uncovered") {
    const Scene scene = load_scene("", {"frames=4", "plane_margin=0.5"});
    const EvalPair pair{Technique::standard, "float32", DepthRange::gl};
    RenderEvaluator ev(gl(), scene, pair);
    const ProbeResult r = ev.run({{16.0, 16.0}}).front();
    CHECK(r.any_uncovered);
    CHECK_FALSE(r.any_clipped);
    CHECK(search_pair(ev, scene, pair, {16.0}).front().verdict() == Verdict::uncovered);
  }
  SECTION("plane B beyond the far plane is clipped") {
    const Scene scene = load_scene("", {"frames=4", "near=1", "far=100"});
    const EvalPair pair{Technique::standard, "unorm24", DepthRange::gl};
    RenderEvaluator ev(gl(), scene, pair);
    CHECK(ev.run({{99.0, 5.0}}).front().outcome == Outcome::clipped);
    CHECK(ev.run({{50.0, 5.0}}).front().outcome == Outcome::clean);
  }
}

TEST_CASE("the pixels of a probe: both planes cover the kernel, B shows only when it fights",
          "[render]") {
  const Scene scene = load_scene("", {"frames=1", "kernel=[32,32]", "viewport=[32,32]"});
  const EvalPair pair{Technique::standard, "unorm24", DepthRange::gl};
  RenderEvaluator ev(gl(), scene, pair);
  const auto far_apart = ev.pixels({100.0, 50.0}, 0);
  const auto coincident = ev.pixels({100.0, 0.0}, 0);
  REQUIRE(far_apart.size() == 32u * 32u);
  CHECK(std::count(far_apart.begin(), far_apart.end(), 3) == 32 * 32);  // both cover, B hidden
  // Equal depths pass LEQUAL: B shows everywhere.
  CHECK(std::count(coincident.begin(), coincident.end(), 7) == 32 * 32);
}

TEST_CASE("render: output header and rows say what rendered them", "[render][cli]") {
  const std::string out = fresh("render_rows.json");
  const CliResult r = run_cli(
      "render -t reversed -f float32 --distances 4,64 --frames 4 --format-out json -o " + out);
  REQUIRE(r.exit_code == 0);
  const auto j = nlohmann::json::parse(slurp(out));
  CHECK_THAT(j.at("gl_renderer").get<std::string>(), Contains("llvmpipe"));
  CHECK_THAT(j.at("gl_version").get<std::string>(), Contains("4.5"));
  CHECK(j.at("depth_buffers").at("float32") == "32-bit float (GL_DEPTH_COMPONENT32F)");
  REQUIRE(j.at("rows").size() == 2);
  uint64_t row_launches = 0, most = 0;
  for (const auto& row : j.at("rows")) {
    CHECK(row.at("source") == "rendered");
    CHECK(row.at("frames_per_second").get<double>() > 0);
    CHECK(row.at("depth_range") == "zero_to_one");
    row_launches += row.at("kernel_launches").get<uint64_t>();
    most = std::max(most, row.at("kernel_launches").get<uint64_t>());
  }
  // The header counts the run's read-back rounds, which rows share: at least the busiest row's,
  // at most all of theirs; and the driver's time.
  const uint64_t launches = j.at("kernel_launches").get<uint64_t>();
  CHECK(launches >= most);
  CHECK(launches <= row_launches);
  CHECK(j.at("kernel_seconds").get<double>() > 0);
}

TEST_CASE("render refuses what the driver or the rendering cannot do", "[render][cli]") {
  SECTION("a format the driver does not store, with the list of those it does") {
    const CliResult r = run_cli("render -f float16 -t standard --distances 4 --frames 2");
    CHECK(r.exit_code == 3);
    CHECK_THAT(r.output, Contains("format float16") && Contains("unorm16, unorm24"));
  }
  SECTION("arithmetic only the emulator has") {
    const CliResult r = run_cli("render --set pipeline.divide=exact --distances 4 --frames 2");
    CHECK(r.exit_code == 3);
    CHECK_THAT(r.output, Contains("pipeline.divide=exact") && Contains("driver"));
  }
  SECTION("no GL driver: one line naming the packages, and the emulator still runs") {
    const std::string env = "LIBGL_DRIVERS_PATH=/nonexistent";
    const CliResult r =
        run_cli("render -t standard -f unorm24 --distances 4 --frames 2 2>/dev/null", env);
    CHECK(r.exit_code == 4);
    const CliResult line = run_cli("render -t standard -f unorm24 --distances 4 --frames 2", env);
    CHECK_THAT(line.output, Contains("libgl1-mesa-dri") && Contains("emulator is unaffected"));
    const CliResult emulated = run_cli("mts -t standard -f unorm24 --distances 4 --frames 2", env);
    CHECK(emulated.exit_code == 0);
  }
  SECTION("an EGL device that is not there: out of range, the displays listed, no packages") {
    // Before, it read as a missing installation: "install libegl1 libgl1 ...".
    const CliResult r =
        run_cli("render --gl-device device:7 -t standard -f unorm24 --distances 4 --frames 2");
    CHECK(r.exit_code == 4);
    CHECK_THAT(r.output, Contains("--gl-device device:7: out of range") &&
                             Contains("the displays to choose from: surfaceless (llvmpipe") &&
                             !Contains("install"));
  }
}

TEST_CASE("depth bias rendered with glPolygonOffset on llvmpipe", "[render][bias]") {
  // llvmpipe's r for unorm buffers is two code steps (Mesa's mrd times 2), so the emulation with
  // --r-unorm double_step must need the same whole units where storage decides (unorm16), and
  // one unit less must fight on the real rasterizer too.
  const Scene scene = load_scene("", {"kernel=[32,32]", "frames=6",
                                      R"(evaluate=[{"technique": "standard", "format": "unorm16"},
                        {"technique": "reversed", "format": "unorm16"}])"});
  BiasOptions llvmpipe;
  llvmpipe.unorm_r = UnormR::double_step;
  for (const EvalPair& pair : scene.evaluate) {
    INFO(pair.label());
    RenderEvaluator renderer(gl(), scene, pair);
    BiasRenderer rendered(renderer, llvmpipe);
    BiasEmulator emulated(runtime(), scene, pair, llvmpipe);
    const std::vector<double> zs = {100, 1000};
    const std::vector<double> no_mts(zs.size(), NAN);
    const auto r = bias_pair_rows(rendered, scene, pair, llvmpipe, zs, no_mts);
    const auto e = bias_pair_rows(emulated, scene, pair, llvmpipe, zs, no_mts);
    const double sign = bias_sign(scene, pair);
    for (size_t k = 0; k < zs.size(); ++k) {
      INFO("z = " << zs[k]);
      REQUIRE(r[k]["verdict"] == "resolved");
      CHECK(r[k]["units"] == e[k]["units"]);
      const double units = r[k]["units"];
      CHECK(units * sign >= 1);
      const auto less = rendered.run({{zs[k], units - sign, 0}});
      CHECK_FALSE(bias_passes(less.front()));
    }
  }
}

TEST_CASE("a rendered clamp reaches glPolygonOffsetClamp signed, as the emulation applies it",
          "[render][bias]") {
  // standard: LESS, a negative bias. A negative clamp far below it limits it on both sides (no
  // bias passes); a positive one limits only positive offsets, so it changes nothing.
  const Scene scene =
      load_scene("", {"kernel=[32,32]", "frames=6",
                      R"(evaluate=[{"technique": "standard", "format": "unorm16"}])"});
  const EvalPair pair = scene.evaluate[0];
  BiasOptions o;
  o.unorm_r = UnormR::double_step;
  const std::vector<double> zs = {100};
  const std::vector<double> no_mts(zs.size(), NAN);
  RenderEvaluator renderer(gl(), scene, pair);
  const auto rows_with = [&](double clamp, bool rendered) {
    BiasOptions c = o;
    c.clamp = clamp;
    if (rendered) {
      BiasRenderer ev(renderer, c);
      return bias_pair_rows(ev, scene, pair, c, zs, no_mts).front();
    }
    BiasEmulator ev(runtime(), scene, pair, c);
    return bias_pair_rows(ev, scene, pair, c, zs, no_mts).front();
  };
  const auto plain = rows_with(0, true);
  REQUIRE(plain["verdict"] == "resolved");
  for (const bool rendered : {true, false}) {
    INFO((rendered ? "rendered" : "emulated"));
    CHECK(rows_with(-1e-9, rendered)["verdict"] == "unresolvable");
    const auto positive = rows_with(1e-9, rendered);
    REQUIRE(positive["verdict"] == "resolved");
    CHECK(positive["units"] == plain["units"]);
  }
}

TEST_CASE("the llvmpipe profile's depth is llvmpipe's on every pixel", "[render][llvmpipe]") {
  // Plane A's depth as llvmpipe stores it in a float32 buffer (no quantisation hides a
  // difference), against the emulation's stored depth under each profile, pixel by pixel, for a
  // projection technique, fragment-depth ones (gl_FragDepth from 1 / gl_FragCoord.w, through
  // the shader's log for log_fragment, its log2 for the engines') and the vertex-stage logs, at
  // distances from near the near plane to far beyond it, with the outer triangles clipped at the
  // viewport edge (kernel = viewport, whose half-extents are no powers of two, so the viewport
  // transform's and the clip stage's roundings show). The profile reproduces the driver on every
  // pixel; the ideal pipeline differs on a quarter to a half of them.
  const std::vector<std::string>& profile_sets = profile("llvmpipe").sets;
  for (const char* technique : {"standard", "linear", "log_fragment", "log_vertex", "log_threejs",
                                "log_threejs_vertex", "log_cesium"}) {
    const std::vector<std::string> base = {
        "kernel=[120,90]", "frames=4", "log_k=3", "plane_margin=1.5",
        fmt::format(R"(evaluate=[{{"technique": "{}", "format": "float32", "depth_range": "gl"}}])",
                    technique)};
    auto with_llvmpipe = base;
    with_llvmpipe.insert(with_llvmpipe.end(), profile_sets.begin(), profile_sets.end());
    const Scene ideal = load_scene("", base), llvmpipe = load_scene("", with_llvmpipe);
    const EvalPair pair = ideal.evaluate[0];
    RenderEvaluator driver(gl(), ideal, pair);
    size_t pixels = 0, same_ideal = 0, same_llvmpipe = 0;
    for (const double z : {2.0, 64.0, 1024.0, 65536.0})
      for (int f = 0; f < ideal.frames; ++f) {
        const std::vector<float> real = driver.depths_a({z, 0.0}, f);
        const FrameCodes a = reference_frame(ideal, pair, {z, 0.0}, f);
        const FrameCodes b = reference_frame(llvmpipe, pair, {z, 0.0}, f);
        for (size_t k = 0; k < real.size(); ++k) {
          uint32_t bits = 0;
          std::memcpy(&bits, &real[k], 4);
          ++pixels;
          same_ideal += a.code_a[k] == bits;
          same_llvmpipe += b.code_a[k] == bits;
        }
      }
    INFO(technique << ": ideal " << same_ideal << ", llvmpipe " << same_llvmpipe << " of "
                   << pixels);
    // three.js's vertex form: 19 pixels differ by one ulp, one column of rows 71-89 in frame 2 at
    // z = 64: a line along a triangle edge, where the two triangles' planes differ by an ulp, as
    // llvmpipe's fixed-point coverage would give (which triangle owns a pixel within 1/256 pixel of
    // an edge: not modelled, docs/spec.md 2). Fusing t * FC - 1 as llvmpipe fuses the matrix rows
    // makes 32,446 differ instead.
    const size_t unexplained = std::string(technique) == "log_threejs_vertex" ? 19 : 0;
    CHECK(same_llvmpipe + unexplained >= pixels);
    CHECK(same_ideal < pixels * 9 / 10);
  }
}

TEST_CASE(
    "away from the world origin llvmpipe stores the depth the profile emulates, per transform",
    "[render][llvmpipe][world]") {
  // Plane A's stored float32 depth from llvmpipe against the llvmpipe profile's, pixel by pixel,
  // at world position (1e5, -2e5, 3e5) under each transform: the view's translation on the GPU
  // after the model matrix (absolute), the translation formed in binary64 first
  // (camera_relative), and Cesium's high/low split (relative_to_eye). The scene of the test
  // above: kernel 120 x 90 in the 200 x 200 viewport, planes clipped at its edge.
  // (compose premultiplied is left out: P * MV differs from llvmpipe on a few pixels even at the
  // origin, 49 of 129600 here.)
  for (const auto& [transform, compose] :
       {std::pair{"absolute", "separate"}, std::pair{"camera_relative", "separate"},
        std::pair{"relative_to_eye", "separate"}}) {
    std::vector<std::string> sets = {
        "kernel=[120,90]",
        "plane_margin=1.5",
        "frames=4",
        "world_position=[1e5,-2e5,3e5]",
        std::string("pipeline.transform=") + transform,
        std::string("pipeline.compose=") + compose,
        R"(evaluate=[{"technique": "standard", "format": "float32", "depth_range": "gl"}])"};
    const Scene ideal = load_scene("", sets);
    const std::vector<std::string>& profile_sets = profile("llvmpipe").sets;
    sets.insert(sets.end(), profile_sets.begin(), profile_sets.end());
    const Scene llvmpipe = load_scene("", sets);
    const EvalPair pair = ideal.evaluate[0];
    RenderEvaluator driver(gl(), ideal, pair);
    size_t pixels = 0, same = 0;
    for (const double z : {2.0, 100.0, 1024.0})
      for (int f = 0; f < ideal.frames; ++f) {
        const std::vector<float> real = driver.depths_a({z, 0.0}, f);
        const FrameCodes b = reference_frame(llvmpipe, pair, {z, 0.0}, f);
        for (size_t k = 0; k < real.size(); ++k) {
          uint32_t bits = 0;
          std::memcpy(&bits, &real[k], 4);
          ++pixels;
          same += b.code_a[k] == bits;
        }
      }
    INFO(transform << " " << compose << ": " << same << " of " << pixels);
    // camera_relative on every pixel; absolute and relative_to_eye on all but one, whose depth
    // differs by one binary32 ulp (z = 1024; untraced: the vertices sit on a coarse grid there)
    CHECK(same + 1 >= pixels);
    if (std::string(transform) == "camera_relative") CHECK(same == pixels);
  }
}

TEST_CASE("the llvmpipe profile stores unorm32 as llvmpipe does: 31 truncated bits",
          "[render][llvmpipe]") {
  // reversed/unorm32 is storage-limited: the ideal pipeline's correctly rounded 32-bit codes
  // resolve half the separation llvmpipe's 2 * trunc(d * 2^31) can. The profile's conversion
  // gives llvmpipe's own MTS.
  const std::vector<std::string> base = {
      "kernel=[64,64]", "frames=10",
      R"(evaluate=[{"technique": "reversed", "format": "unorm32", "depth_range": "zero_to_one"}])"};
  auto with_llvmpipe = base;
  for (const std::string& s : profile("llvmpipe").sets) with_llvmpipe.push_back(s);
  const Scene ideal = load_scene("", base), llvmpipe = load_scene("", with_llvmpipe);
  const EvalPair pair = ideal.evaluate[0];
  const std::vector<double> zs = {4096, 1048576};
  const auto rendered = rendered_rows(ideal, pair, zs);
  const auto emulated = mts_rows(llvmpipe, pair.technique, pair.format, pair.depth_range, zs);
  const auto exact = mts_rows(ideal, pair.technique, pair.format, pair.depth_range, zs);
  for (size_t k = 0; k < zs.size(); ++k) {
    INFO("z = " << zs[k]);
    CHECK(emulated[k].mts == rendered[k].mts);
    CHECK(exact[k].mts < 0.6 * rendered[k].mts);
  }
}
