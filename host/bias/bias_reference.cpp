#include "host/bias/bias_reference.h"

#include <cmath>

#include "interface/bias_formula.h"

namespace depthprec {

BiasFrame reference_bias_frame(const Scene& scene, const EvalPair& pair, const BiasOptions& options,
                               const BiasProbe& probe, int frame) {
  const BiasRule rule = bias_rule(options, scene.storage_format(pair));
  ReferenceBias bias;
  bias.units_term = rule.units_term(probe.units);
  bias.float_rule = rule.float_rule ? 1 : 0;
  bias.factor = static_cast<float>(probe.factor);
  bias.clamp = static_cast<float>(options.clamp);
  bias.slope_form = options.slope == SlopeForm::sqrt ? BIAS_SLOPE_SQRT : BIAS_SLOPE_MAX;
  bias.tilt = options.tilt_deg * M_PI / 180.0;
  bias.or_equal = options.or_equal;
  return reference_biased_frame(scene, pair, bias, probe.z, frame);
}

}  // namespace depthprec
