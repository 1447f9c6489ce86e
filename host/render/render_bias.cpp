#include "host/render/render_bias.h"

#include <epoxy/gl.h>

#include <cmath>

#include "host/model/frame_setup.h"
#include "host/runtime/kernel_variant.h"

namespace depthprec {

double BiasRenderer::tilt_radians() const {
  return options_.tilt_deg * M_PI / 180.0;
}

std::vector<ProbeResult> BiasRenderer::run(const std::vector<BiasProbe>& probes) {
  using Bits = RenderEvaluator::PixelBits;
  std::vector<double> z;
  for (const BiasProbe& p : probes) z.push_back(p.z);
  const double tilt = tilt_radians();
  return renderer_.run_rounds(
      z, [&](size_t i, int frame, const RenderEvaluator::Target& t) { draw(probes[i], frame, t); },
      // the overlay lost the depth test where both planes cover the pixel
      [](uint8_t b) {
        return (b & Bits::a_covers) && (b & Bits::b_covers) && !(b & Bits::b_shows);
      },
      [&](size_t i, int frame) {
        return renderer_.leaves_depth_range(probes[i].z, probes[i].z, frame, tilt);
      });
}

void BiasRenderer::draw(const BiasProbe& probe, int frame, const RenderEvaluator::Target& t) {
  RenderEvaluator& r = renderer_;
  const BiasOptions& o = options_;
  const ProbeConstants pc = probe_constants(r.scene_, r.pair_, probe.z, r.orientations_);
  const bool greater = info(depth_path(r.scene_, r.pair_.technique)).greater;
  const GLenum func =
      greater ? (o.or_equal ? GL_GEQUAL : GL_GREATER) : (o.or_equal ? GL_LEQUAL : GL_LESS);
  r.begin_frame(pc, t);
  r.set_plane(pc, probe.z, frame, tilt_radians());
  // Plane A, writing depth.
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(func);
  glColorMask(GL_TRUE, GL_FALSE, GL_FALSE, GL_FALSE);
  glDrawElements(GL_TRIANGLES, r.index_count_, GL_UNSIGNED_INT, nullptr);
  // The overlay: the same plane tessellated the other way, offset as the application sets it.
  glVertexArrayElementBuffer(r.vao_, r.ibo_flipped_);
  glEnable(GL_POLYGON_OFFSET_FILL);
  // The clamp as given: it is signed as the APIs take it (a negative one limits a negative
  // offset), the emulation applies the same rule (interface/bias_formula.h).
  if (o.clamp != 0)
    glPolygonOffsetClamp(static_cast<float>(probe.factor), static_cast<float>(probe.units),
                         static_cast<float>(o.clamp));
  else
    glPolygonOffset(static_cast<float>(probe.factor), static_cast<float>(probe.units));
  glDepthMask(GL_FALSE);
  glColorMask(GL_FALSE, GL_FALSE, GL_TRUE, GL_FALSE);
  glDrawElements(GL_TRIANGLES, r.index_count_, GL_UNSIGNED_INT, nullptr);
  glDisable(GL_DEPTH_TEST);
  glColorMask(GL_FALSE, GL_TRUE, GL_FALSE, GL_FALSE);
  glDrawElements(GL_TRIANGLES, r.index_count_, GL_UNSIGNED_INT, nullptr);
  glDisable(GL_POLYGON_OFFSET_FILL);
  glVertexArrayElementBuffer(r.vao_, r.ibo_);
  glFlush();
}

}  // namespace depthprec
