#include "host/render/shadow_pass.h"

#include <epoxy/gl.h>
#include <fmt/format.h>

#include "host/base/errors.h"
#include "host/render/gl_context.h"
#include "host/render/gl_depth_format.h"
#include "host/render/gl_program.h"

namespace depthprec {

namespace {

void set_light_rows(GLuint program, const LightMatrix& L) {
  const char* names[4] = {"light_x", "light_y", "light_z", "light_w"};
  for (int r = 0; r < 4; ++r)
    glProgramUniform4f(program, glGetUniformLocation(program, names[r]), L.m[r][0], L.m[r][1],
                       L.m[r][2], L.m[r][3]);
}

}  // namespace

ShadowPass::ShadowPass(const ShadowSetup& s, size_t cascade, int grid) : setup_(s), grid_(grid) {
  GLint dims[2] = {0, 0};
  glGetIntegerv(GL_MAX_VIEWPORT_DIMS, dims);
  if (s.resolution > dims[0])
    throw InputError(
        fmt::format("--source rendered: a {0}x{0} map exceeds this driver's largest viewport, {1}",
                    s.resolution, dims[0]));
  const GlDepthFormat format = gl_depth_format(s.format.name());
  const LightMatrix L = light_matrix(s, cascade);
  caster_ = link_program("host/render/shaders/shadow_caster.vert",
                         "host/render/shaders/shadow_caster.frag", "");
  receiver_ = link_program("host/render/shaders/shadow_receiver.vert",
                           "host/render/shaders/shadow_receiver.frag", "");
  set_light_rows(caster_, L);
  set_light_rows(receiver_, L);
  glCreateVertexArrays(1, &vao_);
  glCreateVertexArrays(1, &points_vao_);  // the receivers' points read no attribute
  glCreateTextures(GL_TEXTURE_2D, 1, &depth_);
  glTextureStorage2D(depth_, 1, format.internal, kWindow, kWindow);
  glTextureParameteri(depth_, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTextureParameteri(depth_, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glTextureParameteri(depth_, GL_TEXTURE_COMPARE_MODE, GL_NONE);
  glCreateFramebuffers(1, &depth_fbo_);
  glNamedFramebufferTexture(depth_fbo_, GL_DEPTH_ATTACHMENT, depth_, 0);
  glNamedFramebufferDrawBuffer(depth_fbo_, GL_NONE);
  glCreateRenderbuffers(1, &colour_);
  glNamedRenderbufferStorage(colour_, GL_R32F, grid, grid);
  glCreateFramebuffers(1, &colour_fbo_);
  glNamedFramebufferRenderbuffer(colour_fbo_, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, colour_);
  for (GLuint fbo : {depth_fbo_, colour_fbo_})
    if (glCheckNamedFramebufferStatus(fbo, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
      throw RuntimeError("shadow --source rendered: a framebuffer is not complete on this driver");
  const GLuint rp = receiver_;
  glProgramUniform1i(rp, glGetUniformLocation(rp, "grid"), grid);
  glProgramUniform1f(rp, glGetUniformLocation(rp, "half_res"),
                     static_cast<float>(s.resolution / 2.0));
  glProgramUniform1i(rp, glGetUniformLocation(rp, "reversed"), s.reversed ? 1 : 0);
  glProgramUniform1i(rp, glGetUniformLocation(rp, "depth_map"), 0);
  check_gl("setting up the shadow pass");
}

ShadowPass::~ShadowPass() {
  glDeleteProgram(caster_);
  glDeleteProgram(receiver_);
  glDeleteVertexArrays(1, &vao_);
  glDeleteVertexArrays(1, &points_vao_);
  glDeleteBuffers(1, &vbo_);
  glDeleteTextures(1, &depth_);
  glDeleteFramebuffers(1, &depth_fbo_);
  glDeleteRenderbuffers(1, &colour_);
  glDeleteFramebuffers(1, &colour_fbo_);
}

void ShadowPass::draw_casters(const std::vector<float>& triangles, int x0, int y0, float factor,
                              float units) {
  if (triangles.size() != vbo_floats_) {
    glDeleteBuffers(1, &vbo_);
    glCreateBuffers(1, &vbo_);
    glNamedBufferStorage(vbo_, static_cast<GLsizeiptr>(triangles.size() * sizeof(float)), nullptr,
                         GL_DYNAMIC_STORAGE_BIT);
    glVertexArrayVertexBuffer(vao_, 0, vbo_, 0, 3 * sizeof(float));
    glEnableVertexArrayAttrib(vao_, 0);
    glVertexArrayAttribFormat(vao_, 0, 3, GL_FLOAT, GL_FALSE, 0);
    glVertexArrayAttribBinding(vao_, 0, 0);
    vbo_floats_ = triangles.size();
  }
  glNamedBufferSubData(vbo_, 0, static_cast<GLsizeiptr>(triangles.size() * sizeof(float)),
                       triangles.data());
  x0_ = x0;
  y0_ = y0;
  glBindFramebuffer(GL_FRAMEBUFFER, depth_fbo_);
  // The viewport is the whole map's, shifted so that the window's first texel is (x0, y0).
  glViewport(-x0, -y0, setup_.resolution, setup_.resolution);
  glDisable(GL_CULL_FACE);
  glDisable(GL_SCISSOR_TEST);
  glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
  glDepthRange(0.0, 1.0);
  glEnable(GL_DEPTH_TEST);
  glDepthMask(GL_TRUE);
  glDepthFunc(setup_.reversed ? GL_GREATER : GL_LESS);
  glClearDepth(setup_.reversed ? 0.0 : 1.0);
  glClear(GL_DEPTH_BUFFER_BIT);
  glEnable(GL_POLYGON_OFFSET_FILL);
  glPolygonOffset(factor, units);
  glUseProgram(caster_);
  glBindVertexArray(vao_);
  glDrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(triangles.size() / 3));
  glDisable(GL_POLYGON_OFFSET_FILL);
  glDisable(GL_DEPTH_TEST);
}

std::vector<float> ShadowPass::receivers(const ShadowReceivers& r) {
  const GLuint rp = receiver_;
  glProgramUniform3d(rp, glGetUniformLocation(rp, "origin"), r.origin[0], r.origin[1], r.origin[2]);
  glProgramUniform3d(rp, glGetUniformLocation(rp, "du"), r.du[0], r.du[1], r.du[2]);
  glProgramUniform3d(rp, glGetUniformLocation(rp, "dv"), r.dv[0], r.dv[1], r.dv[2]);
  glProgramUniform3d(rp, glGetUniformLocation(rp, "denom"), r.denom[0], r.denom[1], r.denom[2]);
  glProgramUniform2f(rp, glGetUniformLocation(rp, "base"), r.base[0], r.base[1]);
  glProgramUniform3f(rp, glGetUniformLocation(rp, "normal"), r.normal[0], r.normal[1], r.normal[2]);
  glProgramUniform1f(rp, glGetUniformLocation(rp, "normal_offset"), r.normal_offset);
  glProgramUniform1f(rp, glGetUniformLocation(rp, "receiver_offset"), r.receiver_offset);
  glProgramUniform1f(rp, glGetUniformLocation(rp, "reach"), static_cast<float>(r.reach));
  glProgramUniform2i(rp, glGetUniformLocation(rp, "window_origin"), x0_, y0_);
  glBindFramebuffer(GL_FRAMEBUFFER, colour_fbo_);
  glViewport(0, 0, grid_, grid_);
  glUseProgram(rp);
  glBindTextureUnit(0, depth_);
  glBindVertexArray(points_vao_);
  glDrawArrays(GL_POINTS, 0, grid_ * grid_);
  std::vector<float> flags(static_cast<size_t>(grid_) * grid_);
  glReadPixels(0, 0, grid_, grid_, GL_RED, GL_FLOAT, flags.data());
  check_gl("drawing a shadow pass");
  return flags;
}

}  // namespace depthprec
