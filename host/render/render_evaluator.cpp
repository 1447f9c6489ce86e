#include "host/render/render_evaluator.h"

#include <epoxy/gl.h>
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>

#include "host/base/embedded_sources.h"
#include "host/base/errors.h"
#include "host/model/frame_setup.h"
#include "host/model/shader_log.h"
#include "host/mts/probe.h"
#include "host/render/driver_settings.h"
#include "host/render/gl_program.h"
#include "host/runtime/kernel_variant.h"
#include "interface/relative_to_eye.h"

namespace depthprec {

namespace {

// Frames rendered before one round of read-backs: llvmpipe rasterises a frame when it is read,
// switched away from or flushed, on its own threads, so several frames in flight keep every core
// busy. Bounded by memory: one target is a colour and a depth buffer of the viewport.
constexpr size_t kMaxTargets = 64;
constexpr size_t kTargetBudgetBytes = size_t(256) << 20;

}  // namespace

RenderEvaluator::RenderEvaluator(GlContext& gl, const Scene& scene, const EvalPair& pair,
                                 const Orientations& orientations)
    : gl_(gl),
      scene_(scene),
      pair_(pair),
      orientations_(orientations),
      depth_(gl_depth_format(pair.format)) {
  check_renderable(scene);
  const std::string defines = shader_defines(scene, pair);
  program_ =
      link_program("host/render/shaders/plane.vert", "host/render/shaders/plane.frag", defines);
  const auto loc = [this](const char* name) { return glGetUniformLocation(program_, name); };
  loc_p_ = loc("P");
  loc_mv_ = loc("MV");
  loc_colour_ = loc("colour");
  loc_near_ = loc("near_plane");
  loc_far_ = loc("far_plane");
  loc_range_ = loc("depth_range");
  loc_vlogk_ = loc("log_k");
  loc_vlogl_ = loc("log_L");
  loc_v_ = loc("V");
  loc_eye_high_ = loc("eye_high");
  loc_eye_low_ = loc("eye_low");
  loc_threejs_fc_ = loc("threejs_fc");
  loc_cesium_far1_ = loc("cesium_far1");
  loc_cesium_inv_log2_ = loc("cesium_inv_log2");

  // The plane: a grid of g x g quads over [-0.5, 0.5]^2, each split along the diagonal from its
  // lower-left corner, triangles (a, b, c) and (a, c, d) in this vertex order -- the emulator's
  // (kernels/mts/setup.cl), since a rasterizer anchors its plane equation at a vertex.
  const int g = scene.plane_subdivisions;
  std::vector<float> xy;
  for (int j = 0; j <= g; ++j)
    for (int i = 0; i <= g; ++i) {
      xy.push_back(grid_coordinate(g, i));
      xy.push_back(grid_coordinate(g, j));
    }
  // The bias measurement's overlay (BiasRenderer, render_bias.cpp) splits each quad along the
  // other diagonal, (a, b, d) and (b, c, d), as kernels/mts/setup.cl's triangle_vertices16 does.
  std::vector<GLuint> idx, flipped;
  for (int qj = 0; qj < g; ++qj)
    for (int qi = 0; qi < g; ++qi) {
      const GLuint a = static_cast<GLuint>(qj * (g + 1) + qi), b = a + 1,
                   c = a + static_cast<GLuint>(g) + 2, d = a + static_cast<GLuint>(g) + 1;
      idx.insert(idx.end(), {a, b, c, a, c, d});
      flipped.insert(flipped.end(), {a, b, d, b, c, d});
    }
  index_count_ = static_cast<int>(idx.size());
  glCreateVertexArrays(1, &vao_);
  glCreateBuffers(1, &vbo_);
  glCreateBuffers(1, &ibo_);
  glCreateBuffers(1, &ibo_flipped_);
  glNamedBufferStorage(vbo_, static_cast<GLsizeiptr>(xy.size() * sizeof(float)), xy.data(), 0);
  glNamedBufferStorage(ibo_, static_cast<GLsizeiptr>(idx.size() * sizeof(GLuint)), idx.data(), 0);
  glNamedBufferStorage(ibo_flipped_, static_cast<GLsizeiptr>(flipped.size() * sizeof(GLuint)),
                       flipped.data(), 0);
  glVertexArrayVertexBuffer(vao_, 0, vbo_, 0, 2 * sizeof(float));
  glVertexArrayElementBuffer(vao_, ibo_);
  glEnableVertexArrayAttrib(vao_, 0);
  glVertexArrayAttribFormat(vao_, 0, 2, GL_FLOAT, GL_FALSE, 0);
  glVertexArrayAttribBinding(vao_, 0, 0);
  if (scene.pipeline.transform == Transform::relative_to_eye) {
    // Per vertex its world position's high and low parts, rewritten for every plane drawn.
    glCreateBuffers(1, &world_vbo_);
    glNamedBufferStorage(world_vbo_, static_cast<GLsizeiptr>(6 * sizeof(float) * (xy.size() / 2)),
                         nullptr, GL_DYNAMIC_STORAGE_BIT);
    glVertexArrayVertexBuffer(vao_, 1, world_vbo_, 0, 6 * sizeof(float));
    for (const GLuint a : {1u, 2u}) {
      glEnableVertexArrayAttrib(vao_, a);
      glVertexArrayAttribFormat(vao_, a, 3, GL_FLOAT, GL_FALSE, (a - 1) * 3 * sizeof(float));
      glVertexArrayAttribBinding(vao_, a, 1);
    }
  }
  check_gl("setting up the plane");
}

RenderEvaluator::~RenderEvaluator() {
  for (auto& t : targets_) {
    glDeleteFramebuffers(1, &t.fbo);
    glDeleteRenderbuffers(1, &t.colour);
    glDeleteRenderbuffers(1, &t.depth);
  }
  glDeleteBuffers(1, &vbo_);
  if (world_vbo_) glDeleteBuffers(1, &world_vbo_);
  glDeleteBuffers(1, &ibo_);
  glDeleteBuffers(1, &ibo_flipped_);
  glDeleteVertexArrays(1, &vao_);
  glDeleteProgram(program_);
}

void RenderEvaluator::grow_targets(size_t n) {
  while (targets_.size() < n) {
    Target t;
    glCreateFramebuffers(1, &t.fbo);
    glCreateRenderbuffers(1, &t.colour);
    glCreateRenderbuffers(1, &t.depth);
    glNamedRenderbufferStorage(t.colour, GL_RGBA8, scene_.viewport_w, scene_.viewport_h);
    glNamedRenderbufferStorage(t.depth, depth_.internal, scene_.viewport_w, scene_.viewport_h);
    glNamedFramebufferRenderbuffer(t.fbo, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, t.colour);
    glNamedFramebufferRenderbuffer(t.fbo, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, t.depth);
    if (glCheckNamedFramebufferStatus(t.fbo, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
      throw RuntimeError(fmt::format("a {}x{} framebuffer with {} is not complete on this driver",
                                     scene_.viewport_w, scene_.viewport_h, depth_.gl_name));
    targets_.push_back(t);
  }
  check_gl("creating framebuffers");
}

void RenderEvaluator::begin_frame(const ProbeConstants& pc, const Target& t) {
  const bool greater = info(depth_path(scene_, pair_.technique)).greater;
  const int ox = (scene_.viewport_w - scene_.kernel_w) / 2;
  const int oy = (scene_.viewport_h - scene_.kernel_h) / 2;

  glBindFramebuffer(GL_FRAMEBUFFER, t.fbo);
  glViewport(0, 0, scene_.viewport_w, scene_.viewport_h);
  glDepthRange(0.0, 1.0);
  glClipControl(GL_LOWER_LEFT,
                pair_.depth_range == DepthRange::gl ? GL_NEGATIVE_ONE_TO_ONE : GL_ZERO_TO_ONE);
  // Only the kernel is compared, so only the kernel is rasterised: the scissor changes which
  // pixels are shaded, not the clipping, set-up or interpolation of the planes.
  glEnable(GL_SCISSOR_TEST);
  glScissor(ox, oy, scene_.kernel_w, scene_.kernel_h);
  glDisable(GL_CULL_FACE);
  glDisable(GL_BLEND);
  glDisable(GL_DEPTH_CLAMP);
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  glDepthMask(GL_TRUE);
  glClearColor(0, 0, 0, 0);
  glClearDepth(greater ? 0.0 : 1.0);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);

  glUseProgram(program_);
  glBindVertexArray(vao_);
  glUniformMatrix4fv(loc_p_, 1, GL_TRUE, pc.P.data());
  glUniform4f(loc_colour_, 1, 1, 1, 1);
  glUniform1f(loc_near_, pc.near);
  glUniform1f(loc_far_, pc.far);
  glUniform1f(loc_range_, pc.range);
  glUniform1f(loc_vlogk_, pc.log_k);
  glUniform1f(loc_vlogl_, pc.log_L);
  if (pc.forms & MTS_F_VIEW_TRANSLATE) {
    const Mat4f V = {1, 0, 0, pc.view[0], 0, 1, 0, pc.view[1], 0, 0, 1, pc.view[2], 0, 0, 0, 1};
    glUniformMatrix4fv(loc_v_, 1, GL_TRUE, V.data());
  }
  glUniform3fv(loc_eye_high_, 1, pc.eye_high.data());
  glUniform3fv(loc_eye_low_, 1, pc.eye_low.data());
  glUniform1f(loc_threejs_fc_, pc.threejs_fc);
  glUniform1f(loc_cesium_far1_, pc.cesium_far1);
  glUniform1f(loc_cesium_inv_log2_, pc.cesium_inv_log2);
  glVertexArrayElementBuffer(vao_, ibo_);
  glDisable(GL_POLYGON_OFFSET_FILL);
}

void RenderEvaluator::set_plane(const ProbeConstants& pc, double D, int frame, double tilt) {
  const VertexStage st = plane_vertex_stage(scene_, pc, D, frame, tilt);
  if (st.path != VertexPath::relative_to_eye) {
    glUniformMatrix4fv(loc_mv_, 1, GL_TRUE, st.matrix.data());
    return;
  }
  // The application's binary64 world positions of the grid's vertices, split for the GPU.
  const int g = scene_.plane_subdivisions;
  std::vector<float> parts;
  for (int j = 0; j <= g; ++j)
    for (int i = 0; i <= g; ++i) {
      float high[3], low[3];
      for (int r = 0; r < 3; ++r)
        dp_rte_encode(
            dp_rte_world_row(st.world.data(), r, grid_coordinate(g, i), grid_coordinate(g, j)),
            high + r, low + r);
      parts.insert(parts.end(), high, high + 3);
      parts.insert(parts.end(), low, low + 3);
    }
  glNamedBufferSubData(world_vbo_, 0, static_cast<GLsizeiptr>(parts.size() * sizeof(float)),
                       parts.data());
}

void RenderEvaluator::draw(const Probe& probe, int frame, const Target& t) {
  const ProbeConstants pc = probe_constants(scene_, pair_, probe.z, orientations_);
  const bool greater = info(depth_path(scene_, pair_.technique)).greater;
  begin_frame(pc, t);

  // Plane A, with the depth test against the cleared buffer, writing depth.
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(greater ? GL_GEQUAL : GL_LEQUAL);
  glColorMask(GL_TRUE, GL_FALSE, GL_FALSE, GL_FALSE);
  set_plane(pc, probe.z, frame);
  glDrawElements(GL_TRIANGLES, index_count_, GL_UNSIGNED_INT, nullptr);
  // Plane B against A's depth: where it passes, it shows.
  glDepthMask(GL_FALSE);
  glColorMask(GL_FALSE, GL_FALSE, GL_TRUE, GL_FALSE);
  set_plane(pc, probe.z + probe.s, frame);
  glDrawElements(GL_TRIANGLES, index_count_, GL_UNSIGNED_INT, nullptr);
  // Plane B's coverage, whatever the depth test would say.
  glDisable(GL_DEPTH_TEST);
  glColorMask(GL_FALSE, GL_TRUE, GL_FALSE, GL_FALSE);
  glDrawElements(GL_TRIANGLES, index_count_, GL_UNSIGNED_INT, nullptr);
  glFlush();
}

std::vector<uint8_t> RenderEvaluator::read(const Target& t) {
  const int ox = (scene_.viewport_w - scene_.kernel_w) / 2;
  const int oy = (scene_.viewport_h - scene_.kernel_h) / 2;
  const size_t n = static_cast<size_t>(scene_.kernel_w) * static_cast<size_t>(scene_.kernel_h);
  std::vector<uint8_t> rgba(4 * n);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, t.fbo);
  glReadBuffer(GL_COLOR_ATTACHMENT0);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(ox, oy, scene_.kernel_w, scene_.kernel_h, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
  check_gl("reading the kernel back");
  std::vector<uint8_t> bits(n);
  for (size_t i = 0; i < n; ++i)
    bits[i] = static_cast<uint8_t>((rgba[4 * i] ? a_covers : 0) | (rgba[4 * i + 1] ? b_covers : 0) |
                                   (rgba[4 * i + 2] ? b_shows : 0));
  return bits;
}

bool RenderEvaluator::leaves_depth_range(double z, double D, int frame, double tilt) const {
  const ProbeConstants pc = probe_constants(scene_, pair_, z, orientations_);
  const VertexStage stage = plane_vertex_stage(scene_, pc, D, frame, tilt);
  const bool gl = pair_.depth_range == DepthRange::gl;
  const bool vertex_log = info(depth_path(scene_, pair_.technique)).from == DepthFrom::vertex_log;
  const int g = scene_.plane_subdivisions;
  for (int j = 0; j <= g; ++j)
    for (int i = 0; i <= g; ++i) {
      const float obj[4] = {grid_coordinate(g, i), grid_coordinate(g, j), 0.0f, 1.0f};
      float clip[4];
      vertex_clip(stage, pc.P, obj, VertexForm::separate, clip);
      if (vertex_log) clip[2] = vertex_log_clip_z(pc, LogForm::library, gl, clip[3]);
      if (!(clip[3] > 0) || clip[2] > clip[3] || clip[2] < (gl ? -clip[3] : 0.0f)) return true;
    }
  return false;
}

std::vector<ProbeResult> RenderEvaluator::run(const std::vector<Probe>& probes) {
  std::vector<double> z;
  for (const Probe& p : probes) z.push_back(p.z);
  return run_rounds(
      z, [&](size_t i, int frame, const Target& t) { draw(probes[i], frame, t); },
      [](uint8_t b) { return (b & a_covers) && (b & b_shows); },
      [&](size_t i, int frame) {
        return leaves_depth_range(probes[i].z, probes[i].z, frame) ||
               leaves_depth_range(probes[i].z, probes[i].z + probes[i].s, frame);
      });
}

std::vector<ProbeResult> RenderEvaluator::run_rounds(
    const std::vector<double>& z, const std::function<void(size_t, int, const Target&)>& draw_frame,
    const std::function<bool(uint8_t)>& pixel_fights,
    const std::function<bool(size_t, int)>& leaves_range) {
  const int frames = scene_.frames;
  const uint64_t kernel_pixels =
      static_cast<uint64_t>(scene_.kernel_w) * static_cast<uint64_t>(scene_.kernel_h);
  std::vector<ProbeResult> results(z.size());
  std::vector<bool> decided(z.size(), false);
  std::vector<int> done(z.size(), 0), first(z.size(), 0);
  for (size_t i = 0; i < z.size(); ++i) {
    const auto it = last_fight_frame_.find(z[i]);
    if (it != last_fight_frame_.end()) first[i] = it->second;
  }
  const size_t target_bytes =
      static_cast<size_t>(scene_.viewport_w) * static_cast<size_t>(scene_.viewport_h) * 8;
  const size_t max_targets =
      std::max<size_t>(1, std::min(kMaxTargets, kTargetBudgetBytes / target_bytes));

  while (true) {
    // This round: the next frames of every undecided probe, in growing batches as the emulator
    // takes them, so a fighting probe costs few frames.
    struct Job {
      size_t probe;
      int visit;
    };
    std::vector<Job> jobs;
    for (size_t i : undecided(decided)) {
      const int step = batch_frames(done[i], frames);
      for (int v = done[i]; v < done[i] + step; ++v) jobs.push_back({i, v});
    }
    if (jobs.empty()) break;
    std::vector<std::vector<uint8_t>> seen(jobs.size());
    for (size_t c = 0; c < jobs.size(); c += max_targets) {
      const size_t n = std::min(max_targets, jobs.size() - c);
      grow_targets(n);
      const auto t0 = std::chrono::steady_clock::now();
      for (size_t k = 0; k < n; ++k) {
        const Job& j = jobs[c + k];
        draw_frame(j.probe, (first[j.probe] + j.visit) % frames, targets_[k]);
      }
      for (size_t k = 0; k < n; ++k) seen[c + k] = read(targets_[k]);
      const double secs =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      seconds_ += secs;
      frames_ += n;
      ++read_backs_;
      for (size_t k = 0; k < n; ++k) {
        ProbeResult& r = results[jobs[c + k].probe];
        r.seconds += secs / static_cast<double>(n);
        r.kernel_seconds = r.seconds;
      }
      std::vector<bool> counted(z.size(), false);
      for (size_t k = 0; k < n; ++k)
        if (!counted[jobs[c + k].probe]) {
          counted[jobs[c + k].probe] = true;
          ++results[jobs[c + k].probe].launches;
        }
    }
    // Fold frame by frame in visiting order: a probe is decided at its first fighting frame.
    for (size_t k = 0; k < jobs.size(); ++k) {
      const size_t i = jobs[k].probe;
      if (decided[i]) continue;
      const int frame = (first[i] + jobs[k].visit) % frames;
      ProbeResult& r = results[i];
      ++r.frames;
      r.fragment_pairs += kernel_pixels;
      bool fight = false, uncovered = false;
      for (uint8_t b : seen[k]) {
        if (pixel_fights(b)) fight = true;
        if ((b & (a_covers | b_covers)) != (a_covers | b_covers)) uncovered = true;
      }
      if (uncovered) {
        if (leaves_range(i, frame))
          r.any_clipped = true;
        else
          r.any_uncovered = true;
      }
      if (fight) {
        r.outcome = Outcome::fight;
        decided[i] = true;
        r.deciding_frame = frame;
        last_fight_frame_[z[i]] = frame;
      }
    }
    for (size_t i = 0; i < z.size(); ++i) {
      if (decided[i]) continue;
      done[i] += batch_frames(done[i], frames);
      if (done[i] >= frames) decided[i] = true;  // every frame clean
    }
  }
  for (auto& r : results)
    if (r.outcome != Outcome::fight && r.any_clipped) r.outcome = Outcome::clipped;
  return results;
}

std::vector<uint8_t> RenderEvaluator::pixels(const Probe& probe, int frame) {
  grow_targets(1);
  draw(probe, frame, targets_[0]);
  return read(targets_[0]);
}

std::vector<float> RenderEvaluator::depths_a(const Probe& probe, int frame) {
  grow_targets(1);
  draw(probe, frame, targets_[0]);
  std::vector<float> d(static_cast<size_t>(scene_.kernel_w) * static_cast<size_t>(scene_.kernel_h));
  glBindFramebuffer(GL_READ_FRAMEBUFFER, targets_[0].fbo);
  glPixelStorei(GL_PACK_ALIGNMENT, 4);
  glReadPixels((scene_.viewport_w - scene_.kernel_w) / 2, (scene_.viewport_h - scene_.kernel_h) / 2,
               scene_.kernel_w, scene_.kernel_h, GL_DEPTH_COMPONENT, GL_FLOAT, d.data());
  check_gl("reading plane A's depth back");
  return d;
}

}  // namespace depthprec
