// A plain C++ implementation of the emulated pipeline (docs/spec.md 2), written apart from the
// kernel to check it: same documented arithmetic forms, same formats/ source for storage, scalar
// and slow. Tests compare its stored codes with the kernel's (mts_codes) bit for bit.
#pragma once

#include "host/model/scene.h"
#include "host/mts/probe.h"

namespace depthprec {

FrameCodes reference_frame(const Scene& scene, const EvalPair& pair, const Probe& probe, int frame);

// What the overlay of the depth-bias measurement adds to its fragments' depth, as kernels/bias.cl
// takes it (interface/bias_formula.h depth_bias's arguments; host/bias/bias_reference.h computes
// them from an API's rule), and how it is drawn.
struct ReferenceBias {
  float units_term = 0, factor = 0, clamp = 0;
  int float_rule = 0, slope_form = 0;  // slope_form: BIAS_SLOPE_MAX or BIAS_SLOPE_SQRT
  double tilt = 0;                     // radians about the view's x axis (bias --tilt)
  bool or_equal = false;               // the overlay's test: LEQUAL/GEQUAL rather than LESS/GREATER
};

// One frame of the depth-bias measurement (kernels/bias.cl): fight when plane A shows through
// the biased overlay at some kernel pixel; the other flags as the kernel's row words say them.
struct BiasFrame {
  bool fight = false, clipped = false, non_finite = false, uncovered = false;
};
BiasFrame reference_biased_frame(const Scene& scene, const EvalPair& pair,
                                 const ReferenceBias& bias, double z, int frame);

}  // namespace depthprec
