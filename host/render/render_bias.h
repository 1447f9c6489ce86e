// Depth bias on a real rasterizer (`bias --source rendered`): the bias searches' evaluator
// (host/bias/bias_probe.h) deciding probes (z, units, factor) by drawing them with
// glPolygonOffset, so the bias arithmetic, r and slope are the driver's. It draws with a
// RenderEvaluator's program, plane buffers and targets and decides its probes in that evaluator's
// rounds, so frames are visited, batched and folded into outcomes as for the MTS probes.
#pragma once

#include <vector>

#include "host/bias/bias_probe.h"
#include "host/bias/bias_rule.h"
#include "host/mts/probe.h"
#include "host/render/render_evaluator.h"

namespace depthprec {

// A probe per frame: plane A, then the same plane split along the other diagonal with
// glPolygonOffset(factor, units) (glPolygonOffsetClamp with a clamp), the compare LESS/GREATER
// (or-equal when asked). It fights where A shows through the overlay at a pixel both cover.
class BiasRenderer : public BiasEvaluator {
 public:
  BiasRenderer(RenderEvaluator& renderer, const BiasOptions& options)
      : renderer_(renderer), options_(options) {}
  std::vector<ProbeResult> run(const std::vector<BiasProbe>& probes) override;
  RowSource source() const override { return RowSource::rendered; }

 private:
  // Draws frame `frame` of the probe into target t (nothing read back yet).
  void draw(const BiasProbe& probe, int frame, const RenderEvaluator::Target& t);
  double tilt_radians() const;

  RenderEvaluator& renderer_;
  BiasOptions options_;
};

}  // namespace depthprec
