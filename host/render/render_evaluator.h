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

#include "host/model/frame_setup.h"
#include "host/model/scene.h"
#include "host/mts/probe.h"
#include "host/render/gl_context.h"
#include "host/render/gl_depth_format.h"

namespace depthprec {

class RenderEvaluator : public ProbeEvaluator {
 public:
  // Throws InputError when the driver cannot store the pair's format (listing what it can).
  // orientations: the frames' sampled ones where a distance has them (worst-case sampling).
  RenderEvaluator(GlContext& gl, const Scene& scene, const EvalPair& pair,
                  const Orientations& orientations = {});
  ~RenderEvaluator() override;
  RenderEvaluator(const RenderEvaluator&) = delete;
  RenderEvaluator& operator=(const RenderEvaluator&) = delete;

  std::vector<ProbeResult> run(const std::vector<Probe>& probes) override;
  RowSource source() const override { return RowSource::rendered; }
  // What a kernel pixel read back tells: a colour channel per question (see the top of this file).
  enum PixelBits : uint8_t { a_covers = 1, b_covers = 2, b_shows = 4 };
  // Kernel pixels of both planes of one frame, for tests and diagnosis: per pixel (row-major from
  // the kernel's bottom-left) its PixelBits.
  std::vector<uint8_t> pixels(const Probe& probe, int frame);
  // The depth the driver stored for plane A at every kernel pixel (same order), read back as
  // binary32: exact for a float32 buffer, the stored code's value for the unorm ones.
  std::vector<float> depths_a(const Probe& probe, int frame);

  const GlDepthFormat& depth_format() const { return depth_; }
  uint64_t frames_rendered() const { return frames_; }
  uint64_t read_backs() const { return read_backs_; }  // rounds of frames drawn and read back
  double seconds() const { return seconds_; }

 private:
  struct Target {
    unsigned fbo = 0, colour = 0, depth = 0;
  };
  // The state every frame starts from: target t bound and cleared, the program and the probe's
  // constants set, plane A's index buffer, no polygon offset.
  void begin_frame(const ProbeConstants& pc, const Target& t);
  // The plane at distance D in this frame for the next draw: its model-view (or P * MV) as the
  // MV uniform, or relative to eye its vertices' split world positions.
  void set_plane(const ProbeConstants& pc, double D, int frame, double tilt = 0);
  // Draws frame `frame` of the probe into target t (nothing read back yet).
  void draw(const Probe& probe, int frame, const Target& t);
  // The rounds both kinds of probe (these and BiasRenderer's) share: frames drawn in growing
  // batches into the targets and read back, a probe decided at its first frame with a pixel for
  // which pixel_fights holds; leaves_range(probe, frame) tells a clipped frame from an uncovered
  // one.
  std::vector<ProbeResult> run_rounds(const std::vector<double>& z,
                                      const std::function<void(size_t, int, const Target&)>& draw,
                                      const std::function<bool(uint8_t)>& pixel_fights,
                                      const std::function<bool(size_t, int)>& leaves_range);
  // Reads the kernel back from target t: PixelBits as in pixels().
  std::vector<uint8_t> read(const Target& t);
  // Whether a vertex of the plane at D leaves the clip volume's depth range in this frame (the
  // reason a kernel pixel can be uncovered other than the planes' extent).
  bool leaves_depth_range(double z, double D, int frame, double tilt = 0) const;
  void grow_targets(size_t n);

  // Depth-bias probes (host/render/render_bias.h) are drawn with this evaluator's program, plane
  // buffers (ibo_flipped_ is theirs) and targets and decided in its rounds.
  friend class BiasRenderer;

  GlContext& gl_;
  const Scene& scene_;
  EvalPair pair_;
  Orientations orientations_;
  GlDepthFormat depth_;
  unsigned program_ = 0, vao_ = 0, vbo_ = 0, ibo_ = 0, ibo_flipped_ = 0;
  unsigned world_vbo_ = 0;  // relative to eye: the vertices' high and low parts (set_plane)
  int index_count_ = 0;
  int loc_p_ = -1, loc_mv_ = -1, loc_colour_ = -1, loc_vlogk_ = -1, loc_vlogl_ = -1, loc_near_ = -1,
      loc_far_ = -1, loc_range_ = -1, loc_flogk_ = -1, loc_flogl_ = -1, loc_threejs_fc_ = -1,
      loc_cesium_far1_ = -1, loc_cesium_inv_log2_ = -1, loc_v_ = -1, loc_eye_high_ = -1,
      loc_eye_low_ = -1;
  std::vector<Target> targets_;
  std::map<double, int> last_fight_frame_;  // frame order as in the emulator (MtsEvaluator)
  uint64_t frames_ = 0, read_backs_ = 0;
  double seconds_ = 0;
};

}  // namespace depthprec
