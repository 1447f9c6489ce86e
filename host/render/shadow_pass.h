// A shadow pass on the current OpenGL context, drawn the way `shadow --source rendered` checks the
// proven biases: casters into a depth texture of the format through the cascade's light matrix
// (the driver's transform, set-up, interpolation, glPolygonOffset and storage), then receiver
// points on a grid x grid target looked up through the texels a filter reads
// (host/render/shaders/shadow_*.{vert,frag}). The texture holds a window of the map around one
// place; window coordinates stay the whole map's.
#pragma once

#include <array>
#include <vector>

#include "host/shadow/shadow_setup.h"

namespace depthprec {

// Receiver points: point (gx, gy) of the grid lies at (origin + u du + v dv) / (denom . (1, u, v))
// (a spot light's planes are projective in the map) with u = base[0] +
// gx / grid, v = base[1] + gy / grid (binary64, rounded to binary32 as a varying is), moved by
// normal_offset along `normal`, its reference depth moved toward the light by receiver_offset.
struct ShadowReceivers {
  std::array<double, 3> origin{}, du{}, dv{}, denom{1, 0, 0};
  std::array<float, 2> base{};
  std::array<float, 3> normal{};
  float normal_offset = 0, receiver_offset = 0;
  double reach = 0.5;  // texels: the filter's
};

class ShadowPass {
 public:
  // Throws InputError when the map exceeds the driver's largest viewport, RuntimeError when the
  // driver cannot draw the format.
  ShadowPass(const ShadowSetup& s, size_t cascade, int grid);
  ~ShadowPass();
  ShadowPass(const ShadowPass&) = delete;
  ShadowPass& operator=(const ShadowPass&) = delete;

  // Clears the window starting at map texel (x0, y0) and draws the casters' triangles (binary32
  // world positions, three per triangle) with glPolygonOffset(factor, units).
  void draw_casters(const std::vector<float>& triangles, int x0, int y0, float factor, float units);
  // Per receiver point, 1 where a texel it reads shadows it: gy * grid + gx.
  std::vector<float> receivers(const ShadowReceivers& r);
  static constexpr int kWindow = 256;

 private:
  const ShadowSetup& setup_;
  int grid_;
  int x0_ = 0, y0_ = 0;
  unsigned caster_ = 0, receiver_ = 0, vao_ = 0, points_vao_ = 0, vbo_ = 0, depth_ = 0,
           depth_fbo_ = 0, colour_ = 0, colour_fbo_ = 0;
  size_t vbo_floats_ = 0;
};

}  // namespace depthprec
