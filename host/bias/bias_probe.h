// Decides depth-bias probes: does a coplanar overlay (plane B in plane A, tessellated along the
// other diagonal, drawn after A with the bias) pass the depth test at every kernel pixel of every
// frame? The interface the bias searches drive, without OpenCL: emulated by kernels/bias.cl
// (BiasEmulator, host/bias/bias_evaluator.h) or rendered through OpenGL with glPolygonOffset
// (BiasRenderer, host/render/render_bias.h), so one search drives both.
#pragma once

#include <vector>

#include "host/mts/probe.h"

namespace depthprec {

// units and factor as the application sets them (signed: negative toward the camera under
// LESS); clamp from the options.
struct BiasProbe {
  double z = 0;
  double units = 0, factor = 0;
};

// Outcome::fight: plane A showed through the overlay at some kernel pixel of some frame (the
// bias was too small); clean: the overlay won everywhere.
class BiasEvaluator {
 public:
  virtual ~BiasEvaluator() = default;
  virtual std::vector<ProbeResult> run(const std::vector<BiasProbe>& probes) = 0;
  virtual RowSource source() const = 0;
};

}  // namespace depthprec
