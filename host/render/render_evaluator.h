// Decides probes by rendering them through the system's OpenGL (Gilg et al.'s own measurement):
// per frame, plane A drawn with the technique's depth test, then plane B, and the kernel's pixels
// read back from the colour buffer. The same ProbeEvaluator the emulator is, so the MTS search
// (host/mts/mts_search.h) drives both with one probe sequence.
//
// One colour target, one channel per question, so a pixel tells all three at once:
//   red   plane A covers the pixel (drawn with the depth test, writing depth),
//   blue  plane B passes the depth test there: it shows, the pair fights,
//   green plane B covers the pixel (B again, depth test off, nothing written to depth).
// A fight counts where red and blue are set; a pixel without red or green is uncovered, and the
// probe is then never clean (clipped when a plane's vertices leave the depth range of the clip
// volume, uncovered otherwise), as in the emulator.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "host/bias/bias_evaluator.h"
#include "host/model/frame_setup.h"
#include "host/model/scene.h"
#include "host/mts/probe.h"
#include "host/render/gl_context.h"
#include "host/render/gl_depth_format.h"

namespace depthprec {

// A pipeline setting the driver decides for itself: render refuses any value but the default.
// An implementation form (a profile's, reset set) is one a real rasterizer has its own of:
// `compare` and `bias --source rendered` render the scene with it at its default
// (rendered_counterpart). The others (divide, rounding, denormals, contraction) are refused there
// too: an emulation that sets them has no rendered counterpart.
struct DriverSetting {
  const char* setting;  // as named in the refusal, e.g. "viewport=fma"
  const char* why;
  bool (*changed)(const Pipeline&);
  void (*reset)(Pipeline&);  // nullptr: not an implementation form
};
const std::vector<DriverSetting>& driver_settings();

// Throws InputError when the scene sets a driver setting or its kernel is larger than the
// viewport.
void check_renderable(const Scene& scene);

class RenderEvaluator : public ProbeEvaluator {
 public:
  // Throws InputError when the driver cannot store the pair's format (listing what it can).
  RenderEvaluator(GlContext& gl, const Scene& scene, const EvalPair& pair);
  ~RenderEvaluator() override;
  RenderEvaluator(const RenderEvaluator&) = delete;
  RenderEvaluator& operator=(const RenderEvaluator&) = delete;

  std::vector<ProbeResult> run(const std::vector<Probe>& probes) override;
  RowSource source() const override { return RowSource::rendered; }
  // Depth-bias probes (`bias --source rendered`): plane A, then the same plane split along the
  // other diagonal with glPolygonOffset(factor, units) (glPolygonOffsetClamp with a clamp), the
  // compare LESS/GREATER (or-equal when asked). A probe fights where A shows through the overlay
  // at a pixel both cover. The bias arithmetic, r and slope are the driver's.
  std::vector<ProbeResult> run_bias(const std::vector<BiasProbe>& probes, const BiasOptions& o);

  // Kernel pixels of both planes of one frame, for tests and diagnosis: per pixel (row-major from
  // the kernel's bottom-left) bit 0 A covers, bit 1 B covers, bit 2 B passes the depth test.
  std::vector<uint8_t> pixels(const Probe& probe, int frame);
  // The depth the driver stored for plane A at every kernel pixel (same order), read back as
  // binary32: exact for a float32 buffer, the stored code's value for the unorm ones.
  std::vector<float> depths_a(const Probe& probe, int frame);

  const GlDepthFormat& depth_format() const { return depth_; }
  uint64_t frames_rendered() const { return frames_; }
  double seconds() const { return seconds_; }

 private:
  struct Target {
    unsigned fbo = 0, colour = 0, depth = 0;
  };
  // The state every frame starts from: target t bound and cleared, the program and the probe's
  // constants set, plane A's index buffer, no polygon offset.
  void begin_frame(const ProbeConstants& pc, const Target& t);
  // Draws frame `frame` of the probe into target t (nothing read back yet).
  void draw(const Probe& probe, int frame, const Target& t);
  void draw_bias(const BiasProbe& probe, const BiasOptions& o, int frame, const Target& t);
  // The rounds both kinds of probe share: frames drawn in growing batches into the targets and
  // read back, a probe decided at its first frame with a pixel for which pixel_fights holds;
  // leaves_range(probe, frame) tells a clipped frame from an uncovered one.
  std::vector<ProbeResult> run_rounds(const std::vector<double>& z,
                                      const std::function<void(size_t, int, const Target&)>& draw,
                                      const std::function<bool(uint8_t)>& pixel_fights,
                                      const std::function<bool(size_t, int)>& leaves_range);
  // Reads the kernel back from target t: bits as in pixels().
  std::vector<uint8_t> read(const Target& t);
  // Whether a vertex of the plane at D leaves the clip volume's depth range in this frame (the
  // reason a kernel pixel can be uncovered other than the planes' extent).
  bool leaves_depth_range(double z, double D, int frame, double tilt = 0) const;
  void grow_targets(size_t n);

  GlContext& gl_;
  const Scene& scene_;
  EvalPair pair_;
  GlDepthFormat depth_;
  unsigned program_ = 0, vao_ = 0, vbo_ = 0, ibo_ = 0, ibo_flipped_ = 0;
  int index_count_ = 0;
  int loc_p_ = -1, loc_mv_ = -1, loc_colour_ = -1, loc_vlogk_ = -1, loc_vlogl_ = -1, loc_near_ = -1,
      loc_far_ = -1, loc_range_ = -1, loc_flogk_ = -1, loc_flogl_ = -1, loc_threejs_fc_ = -1,
      loc_cesium_far1_ = -1, loc_cesium_inv_log2_ = -1;
  std::vector<Target> targets_;
  std::map<double, int> last_fight_frame_;  // frame order as in the emulator (MtsEvaluator)
  uint64_t frames_ = 0;
  double seconds_ = 0;
};

// The bias searches' evaluator on a real rasterizer: RenderEvaluator::run_bias.
class BiasRenderer : public BiasEvaluator {
 public:
  BiasRenderer(RenderEvaluator& renderer, const BiasOptions& options)
      : renderer_(renderer), options_(options) {}
  std::vector<ProbeResult> run(const std::vector<BiasProbe>& probes) override {
    return renderer_.run_bias(probes, options_);
  }
  RowSource source() const override { return RowSource::rendered; }

 private:
  RenderEvaluator& renderer_;
  BiasOptions options_;
};

}  // namespace depthprec
