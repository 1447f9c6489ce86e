#include "host/render/render_shadow.h"

#include <epoxy/gl.h>
#include <fmt/format.h>

#include <algorithm>
#include <array>

#include "host/base/errors.h"
#include "host/render/gl_context.h"
#include "host/render/gl_depth_format.h"
#include "host/render/gl_program.h"
#include "interface/shadow_layout.h"

namespace depthprec {

namespace {

// The part of the map drawn per plane: a window of this many texels around the receiver grid's
// texel, the viewport shifted so that window coordinates stay those of the whole map.
constexpr int kWindow = 128;

// One bias setting as the rendered passes apply it: glPolygonOffset's factor and units on the
// caster, a window-depth offset and a normal offset on the receiver.
struct RenderedProbe {
  const char* recipe;
  double level;  // 1: the bound's value, 0.9: 10 % below
  float factor = 0, units = 0, receiver_offset = 0, normal = 0;
};

std::vector<RenderedProbe> probes_of(const nlohmann::json& bound, bool reversed) {
  const float sign = reversed ? -1.0f : 1.0f;
  std::vector<RenderedProbe> out;
  for (const double level : {1.0, 0.9}) {
    // The constant as a receiver offset: exact in window depth, free of the driver's r.
    RenderedProbe c{"constant", level};
    c.receiver_offset = static_cast<float>(level * bound["constant"].get<double>());
    RenderedProbe s{"slope", level};
    s.factor = sign * static_cast<float>(level * bound["slope_factor"].get<double>());
    s.units = sign * static_cast<float>(bound["error_units"].get<double>());
    RenderedProbe n{"normal", level};
    n.receiver_offset = static_cast<float>(bound["error_constant"].get<double>());
    n.normal = static_cast<float>(level * bound["normal_metres"].get<double>());
    out.insert(out.end(), {c, s, n});
  }
  return out;
}

struct GlObjects {
  GLuint caster = 0, receiver = 0, vao = 0, vbo = 0, depth = 0, depth_fbo = 0, colour = 0,
         colour_fbo = 0;
  ~GlObjects() {
    glDeleteProgram(caster);
    glDeleteProgram(receiver);
    glDeleteVertexArrays(1, &vao);
    glDeleteBuffers(1, &vbo);
    glDeleteTextures(1, &depth);
    glDeleteFramebuffers(1, &depth_fbo);
    glDeleteRenderbuffers(1, &colour);
    glDeleteFramebuffers(1, &colour_fbo);
  }
};

void set_light(GLuint program, const LightMatrix& L) {
  const char* names[3] = {"light_x", "light_y", "light_z"};
  for (int r = 0; r < 3; ++r)
    glProgramUniform4f(program, glGetUniformLocation(program, names[r]), L.m[r][0], L.m[r][1],
                       L.m[r][2], L.m[r][3]);
}

}  // namespace

nlohmann::json rendered_shadow_check(const ShadowRequest& r, size_t cascade,
                                     const nlohmann::json& record) {
  const ShadowSetup& s = r.setup;
  GLint dims[2] = {0, 0};
  glGetIntegerv(GL_MAX_VIEWPORT_DIMS, dims);
  if (s.resolution > dims[0])
    throw InputError(
        fmt::format("--source rendered: a {0}x{0} map exceeds this driver's largest viewport, {1}",
                    s.resolution, dims[0]));
  ShadowSampling sampling = r.sampling;
  sampling.planes = std::min(sampling.planes, kRenderedShadowPlanes);
  const ShadowPlanes planes = shadow_planes(s, cascade, sampling);
  const LightMatrix L = light_matrix(s, cascade);
  const GlDepthFormat format = gl_depth_format(s.format.name());
  const int grid = static_cast<int>(sampling.grid);

  GlObjects gl;
  gl.caster = link_program("host/render/shaders/shadow_caster.vert",
                           "host/render/shaders/shadow_caster.frag", "");
  gl.receiver = link_program("host/render/shaders/shadow_receiver.vert",
                             "host/render/shaders/shadow_receiver.frag", "");
  set_light(gl.caster, L);
  set_light(gl.receiver, L);
  glCreateVertexArrays(1, &gl.vao);
  glCreateBuffers(1, &gl.vbo);
  glNamedBufferStorage(gl.vbo, 9 * sizeof(float), nullptr, GL_DYNAMIC_STORAGE_BIT);
  glVertexArrayVertexBuffer(gl.vao, 0, gl.vbo, 0, 3 * sizeof(float));
  glEnableVertexArrayAttrib(gl.vao, 0);
  glVertexArrayAttribFormat(gl.vao, 0, 3, GL_FLOAT, GL_FALSE, 0);
  glVertexArrayAttribBinding(gl.vao, 0, 0);
  glCreateTextures(GL_TEXTURE_2D, 1, &gl.depth);
  glTextureStorage2D(gl.depth, 1, format.internal, kWindow, kWindow);
  glTextureParameteri(gl.depth, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTextureParameteri(gl.depth, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glTextureParameteri(gl.depth, GL_TEXTURE_COMPARE_MODE, GL_NONE);
  glCreateFramebuffers(1, &gl.depth_fbo);
  glNamedFramebufferTexture(gl.depth_fbo, GL_DEPTH_ATTACHMENT, gl.depth, 0);
  glNamedFramebufferDrawBuffer(gl.depth_fbo, GL_NONE);
  glCreateRenderbuffers(1, &gl.colour);
  glNamedRenderbufferStorage(gl.colour, GL_R32F, grid, grid);
  glCreateFramebuffers(1, &gl.colour_fbo);
  glNamedFramebufferRenderbuffer(gl.colour_fbo, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, gl.colour);
  for (GLuint fbo : {gl.depth_fbo, gl.colour_fbo})
    if (glCheckNamedFramebufferStatus(fbo, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
      throw RuntimeError("shadow --source rendered: a framebuffer is not complete on this driver");
  check_gl("setting up the shadow pass");

  const GLuint rp = gl.receiver;
  glProgramUniform1i(rp, glGetUniformLocation(rp, "grid"), grid);
  glProgramUniform1f(rp, glGetUniformLocation(rp, "reach"), static_cast<float>(s.filter.reach));
  glProgramUniform1f(rp, glGetUniformLocation(rp, "half_res"),
                     static_cast<float>(s.resolution / 2.0));
  glProgramUniform1i(rp, glGetUniformLocation(rp, "reversed"), s.reversed ? 1 : 0);
  glProgramUniform1i(rp, glGetUniformLocation(rp, "depth_map"), 0);

  const std::vector<RenderedProbe> probes = probes_of(record["bound"], s.reversed);
  std::vector<uint64_t> acne(probes.size(), 0);
  std::vector<float> flags(static_cast<size_t>(grid * grid));
  glDisable(GL_CULL_FACE);
  glDisable(GL_SCISSOR_TEST);
  glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
  glDepthRange(0.0, 1.0);
  for (uint32_t k = 0; k < planes.count; ++k) {
    const float* f = &planes.f[k * SHADOW_F_STRIDE];
    const double* d = &planes.d[k * SHADOW_D_STRIDE];
    glNamedBufferSubData(gl.vbo, 0, 9 * sizeof(float), f);
    // The window's first texel, so that texel (i, j) of the map is (i - x0, j - y0) of it.
    const int x0 = static_cast<int>(f[SHADOW_F_BASE_U]) - kWindow / 2;
    const int y0 = static_cast<int>(f[SHADOW_F_BASE_V]) - kWindow / 2;
    glProgramUniform3d(rp, glGetUniformLocation(rp, "origin"), d[0], d[1], d[2]);
    glProgramUniform3d(rp, glGetUniformLocation(rp, "du"), d[3], d[4], d[5]);
    glProgramUniform3d(rp, glGetUniformLocation(rp, "dv"), d[6], d[7], d[8]);
    glProgramUniform2f(rp, glGetUniformLocation(rp, "base"), f[SHADOW_F_BASE_U],
                       f[SHADOW_F_BASE_V]);
    glProgramUniform3f(rp, glGetUniformLocation(rp, "normal"), f[SHADOW_F_NORMAL],
                       f[SHADOW_F_NORMAL + 1], f[SHADOW_F_NORMAL + 2]);
    // The receiver's coordinates are the map's; the texture holds the window from (x0, y0).
    glProgramUniform2i(rp, glGetUniformLocation(rp, "window_origin"), x0, y0);
    for (size_t p = 0; p < probes.size(); ++p) {
      const RenderedProbe& pr = probes[p];
      glBindFramebuffer(GL_FRAMEBUFFER, gl.depth_fbo);
      glViewport(-x0, -y0, s.resolution, s.resolution);
      glEnable(GL_DEPTH_TEST);
      glDepthMask(GL_TRUE);
      glDepthFunc(s.reversed ? GL_GREATER : GL_LESS);
      glClearDepth(s.reversed ? 0.0 : 1.0);
      glClear(GL_DEPTH_BUFFER_BIT);
      glEnable(GL_POLYGON_OFFSET_FILL);
      glPolygonOffset(pr.factor, pr.units);
      glUseProgram(gl.caster);
      glBindVertexArray(gl.vao);
      glDrawArrays(GL_TRIANGLES, 0, 3);
      glDisable(GL_POLYGON_OFFSET_FILL);
      glDisable(GL_DEPTH_TEST);
      glBindFramebuffer(GL_FRAMEBUFFER, gl.colour_fbo);
      glViewport(0, 0, grid, grid);
      glUseProgram(rp);
      glProgramUniform1f(rp, glGetUniformLocation(rp, "receiver_offset"), pr.receiver_offset);
      glProgramUniform1f(rp, glGetUniformLocation(rp, "normal_offset"), pr.normal);
      glBindTextureUnit(0, gl.depth);
      glDrawArrays(GL_POINTS, 0, grid * grid);
      glReadPixels(0, 0, grid, grid, GL_RED, GL_FLOAT, flags.data());
      for (float v : flags) acne[p] += v != 0.0f ? 1 : 0;
    }
    check_gl("drawing a shadow pass");
  }
  nlohmann::json out;
  out["planes"] = planes.count;
  out["points"] = static_cast<uint64_t>(planes.count) * grid * grid;
  bool clean = true;
  for (size_t p = 0; p < probes.size(); ++p) {
    const std::string key = probes[p].level == 1.0 ? "acne_at_bound" : "acne_at_90_percent";
    out[probes[p].recipe][key] = acne[p];
    if (probes[p].level == 1.0 && acne[p] != 0) clean = false;
  }
  out["clean_at_bound"] = clean;
  return out;
}

}  // namespace depthprec
