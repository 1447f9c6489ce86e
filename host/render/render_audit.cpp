#include "host/render/render_audit.h"

#include <epoxy/gl.h>
#include <fmt/format.h>

#include <cmath>

#include "host/base/errors.h"
#include "host/model/vertex_stage.h"
#include "host/render/gl_depth_format.h"
#include "host/render/gl_program.h"
#include "host/runtime/kernel_variant.h"
#include "interface/audit_layout.h"

namespace depthprec {

std::vector<uint32_t> render_winners(GlContext&, const Scene& scene, const EvalPair& pair,
                                     const SceneGeometry& g, const AuditCamera& cam) {
  if (vertex_path(scene.pipeline) == VertexPath::relative_to_eye)
    throw InputError("audit --source rendered: the relative_to_eye transform is emulated only");
  const Scene s = audit_scene(scene, cam);
  const ProbeConstants pc = probe_constants(s, pair, s.near);
  const TechniqueInfo& ti = info(depth_path(s, pair.technique));
  const GlDepthFormat depth = gl_depth_format(pair.format);
  const bool view_on_gpu = vertex_path(s.pipeline) == VertexPath::model_then_view;
  const unsigned program = link_program(
      "host/render/shaders/audit.vert", "host/render/shaders/audit.frag",
      shader_defines(s, pair) + fmt::format("#define VIEW_ON_GPU {}\n", view_on_gpu ? 1 : 0));
  const int w = cam.width, h = cam.height;
  GLuint fbo = 0, colour = 0, zbuf = 0, vao = 0;
  glCreateFramebuffers(1, &fbo);
  glCreateRenderbuffers(1, &colour);
  glCreateRenderbuffers(1, &zbuf);
  glNamedRenderbufferStorage(colour, GL_R32UI, w, h);
  glNamedRenderbufferStorage(zbuf, depth.internal, w, h);
  glNamedFramebufferRenderbuffer(fbo, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, colour);
  glNamedFramebufferRenderbuffer(fbo, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, zbuf);
  if (glCheckNamedFramebufferStatus(fbo, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
    throw RuntimeError(fmt::format(
        "audit: a {}x{} framebuffer with {} is incomplete on this driver", w, h, depth.gl_name));
  glBindFramebuffer(GL_FRAMEBUFFER, fbo);
  glViewport(0, 0, w, h);
  glDepthRange(0.0, 1.0);
  glClipControl(GL_LOWER_LEFT,
                pair.depth_range == DepthRange::gl ? GL_NEGATIVE_ONE_TO_ONE : GL_ZERO_TO_ONE);
  glDisable(GL_SCISSOR_TEST);
  glDisable(GL_CULL_FACE);
  glDisable(GL_BLEND);
  glDisable(GL_DEPTH_CLAMP);
  glEnable(GL_DEPTH_TEST);
  glDepthMask(GL_TRUE);
  glDepthFunc(ti.greater ? GL_GREATER : GL_LESS);  // the emulation's strict test
  const GLuint clear_id = 0;
  glClearBufferuiv(GL_COLOR, 0, &clear_id);
  const GLfloat clear_depth = ti.greater ? 0.0f : 1.0f;
  glClearBufferfv(GL_DEPTH, 0, &clear_depth);
  glUseProgram(program);
  const auto loc = [program](const char* name) { return glGetUniformLocation(program, name); };
  glUniformMatrix4fv(loc("P"), 1, GL_TRUE, pc.P.data());
  glUniform1f(loc("near_plane"), pc.near);
  glUniform1f(loc("far_plane"), pc.far);
  glUniform1f(loc("depth_range"), pc.range);
  glUniform1f(loc("log_k"), pc.log_k);
  glUniform1f(loc("log_L"), pc.log_L);
  glUniform1f(loc("threejs_fc"), pc.threejs_fc);
  glUniform1f(loc("cesium_far1"), pc.cesium_far1);
  glUniform1f(loc("cesium_inv_log2"), pc.cesium_inv_log2);
  glCreateVertexArrays(1, &vao);
  glBindVertexArray(vao);
  for (const Draw& d : g.draws) {
    const VertexStage m = draw_vertex_stage(s, pc, d, cam);
    glUniformMatrix4fv(loc("FIRST"), 1, GL_TRUE, m.matrix.data());
    glUniformMatrix4fv(loc("SECOND"), 1, GL_TRUE, m.view_matrix.data());
    glUniform1ui(loc("first_triangle"), d.first_triangle);
    GLuint vbo = 0, ibo = 0;
    glCreateBuffers(1, &vbo);
    glCreateBuffers(1, &ibo);
    glNamedBufferStorage(vbo, static_cast<GLsizeiptr>(d.positions.size() * 12), d.positions.data(),
                         0);
    glNamedBufferStorage(ibo, static_cast<GLsizeiptr>(d.triangles.size() * 12), d.triangles.data(),
                         0);
    glVertexArrayVertexBuffer(vao, 0, vbo, 0, 12);
    glVertexArrayAttribFormat(vao, 0, 3, GL_FLOAT, GL_FALSE, 0);
    glVertexArrayAttribBinding(vao, 0, 0);
    glEnableVertexArrayAttrib(vao, 0);
    glVertexArrayElementBuffer(vao, ibo);
    glDrawElements(GL_TRIANGLES, static_cast<GLsizei>(d.triangles.size() * 3), GL_UNSIGNED_INT,
                   nullptr);
    glDeleteBuffers(1, &vbo);
    glDeleteBuffers(1, &ibo);
  }
  std::vector<uint32_t> ids(static_cast<size_t>(w) * h);
  glPixelStorei(GL_PACK_ALIGNMENT, 4);
  glReadPixels(0, 0, w, h, GL_RED_INTEGER, GL_UNSIGNED_INT, ids.data());
  const GLenum err = glGetError();
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glDeleteVertexArrays(1, &vao);
  glDeleteFramebuffers(1, &fbo);
  glDeleteRenderbuffers(1, &colour);
  glDeleteRenderbuffers(1, &zbuf);
  glDeleteProgram(program);
  if (err != GL_NO_ERROR) throw RuntimeError(fmt::format("audit: OpenGL error 0x{:x}", err));
  for (uint32_t& id : ids) id = id == 0 ? AUDIT_NONE : id - 1;
  return ids;
}

nlohmann::json render_audit(GlContext& gl, const Scene& scene, const EvalPair& pair,
                            const SceneGeometry& g, const AuditCamera& cam,
                            const SetupAudit& audit) {
  const std::vector<uint32_t> rendered = render_winners(gl, scene, pair, g, cam);
  const Scene s = audit_scene(scene, cam);
  const std::vector<std::array<double, 4>> planes = exact_planes(g, cam);
  const std::array<double, 4> ray = pixel_ray(s, probe_constants(s, pair, s.near));
  const AuditPixels& e = audit.image;
  // Pixels whose winners (or fight verdicts) differ, by why: on a seam between neighbours of one
  // surface, where two surfaces share a plane (coplanar: the draw order decides), where the
  // emulation marks the pixel at risk (another conformant implementation may store the other
  // order), where the emulation's own codes tie or are one apart (one rounding decides), on the
  // border of the front surface's coverage (edge: the coverage rules decide), or none of these.
  struct Why {
    uint64_t seam = 0, coplanar = 0, tie = 0, at_risk = 0, edge = 0, other = 0;
    nlohmann::json json() const {
      return {{"seam", seam},       {"coplanar", coplanar}, {"tie", tie},
              {"at_risk", at_risk}, {"edge", edge},         {"other", other}};
    }
  } winners_differ, fights_differ, fights_missed;
  uint64_t winner_agree = 0, fight_agree = 0, fights = 0, fights_emulated = 0;
  nlohmann::json examples = nlohmann::json::array();  // the first pixels whose winners differ
  const auto id = [](uint32_t t) {
    return t == AUDIT_NONE ? nlohmann::json(nullptr) : nlohmann::json(t);
  };
  // Whether the pixel lies on the border of its front surface's coverage (a 4-neighbour's front is
  // another draw's, or none): there each rasterizer's coverage rule (llvmpipe's fixed point, the
  // emulation's binary32 edges) decides which surface the pixel sees at all.
  const auto draw_at = [&](int x, int y) -> int {
    if (x < 0 || y < 0 || x >= e.width || y >= e.height) return -1;
    const uint32_t t = e.front[static_cast<size_t>(y) * e.width + x];
    return t == AUDIT_NONE ? -1 : static_cast<int>(&g.draw_of(t) - g.draws.data());
  };
  const auto on_edge = [&](int x, int y) {
    const int d = draw_at(x, y);
    return draw_at(x - 1, y) != d || draw_at(x + 1, y) != d || draw_at(x, y - 1) != d ||
           draw_at(x, y + 1) != d;
  };
  for (int y = 0; y < e.height; ++y)
    for (int x = 0; x < e.width; ++x) {
      const size_t i = static_cast<size_t>(y) * e.width + x;
      const uint32_t rw = rendered[i], ew = e.winner[i], front = e.front[i];
      bool fight = false;
      if (rw != AUDIT_NONE && front != AUDIT_NONE && rw != front && !g.neighbours(rw, front)) {
        const float px = static_cast<float>(x) + 0.5f, py = static_cast<float>(y) + 0.5f;
        const double sw = ray_depth(ray, planes[rw], px, py);
        const double sf = ray_depth(ray, planes[front], px, py);
        fight = !(std::fabs(sw - sf) <= AUDIT_COPLANAR_RELATIVE * std::fmin(sw, sf));
      }
      const bool emulated = (e.flags[i] & AUDIT_FIGHT) != 0;
      const auto classify = [&](Why& why) {
        if (rw != AUDIT_NONE && ew != AUDIT_NONE && g.neighbours(rw, ew))
          ++why.seam;
        else if (e.flags[i] & AUDIT_COPLANAR)
          ++why.coplanar;
        else if (e.flags[i] & AUDIT_AT_RISK)
          ++why.at_risk;
        else if (std::abs(e.margin[i]) <= 1)
          ++why.tie;
        else if (on_edge(x, y))
          ++why.edge;
        else
          ++why.other;
      };
      winner_agree += rw == ew;
      fight_agree += fight == emulated;
      fights += fight;
      fights_emulated += emulated;
      if (rw != ew) classify(winners_differ);
      if (fight != emulated) classify(fights_differ);
      if (fight && !emulated) classify(fights_missed);  // rendered fights the emulation did not
      if (rw != ew && examples.size() < 8)
        examples.push_back({{"x", x},
                            {"y", y},
                            {"rendered", id(rw)},
                            {"emulated", id(ew)},
                            {"front", id(front)},
                            {"emulated_margin_codes", e.margin[i]}});
    }
  return {{"renderer", gl.description()},
          {"pixels", e.flags.size()},
          {"winner_agree", winner_agree},
          {"winners_differ", winners_differ.json()},
          {"fight_agree", fight_agree},
          {"fights_differ", fights_differ.json()},
          {"fights_missed", fights_missed.json()},
          {"fighting_pixels", fights},
          {"fighting_pixels_emulated", fights_emulated},
          {"winners_differ_at", examples}};
}

}  // namespace depthprec
