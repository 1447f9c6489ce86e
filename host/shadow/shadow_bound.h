// The smallest shadow biases that leave no acne on any receiver up to the slope limit, proven
// (docs/shadow.md "The bound"): the gap a filter's reach opens between a receiver and the texels
// it reads, plus every rounding a bound model allows between the light matrix and the comparison,
// each term written beside the arithmetic it bounds (host/shadow/shadow_bound.cpp).
#pragma once

#include "host/model/bound_model.h"
#include "host/shadow/shadow_setup.h"

namespace depthprec {

// Error terms of one cascade. Depths are window depths (the cascade's range is 1).
struct ShadowTerms {
  double reach = 0;          // the filter's, texels
  double caster_xy = 0;      // texels: the caster's vertex transform, viewport and snapping
  double receiver_xy = 0;    // texels: the receiver's position, normal offset and transform
  double caster_vertex = 0;  // the caster's vertex depth transform
  double interpolation = 0;  // the caster's depth at a texel centre from its vertices
  double storage = 0;        // the conversion to the format and back, downward
  double receiver = 0;       // the receiver's reference depth
  double depth_errors() const { return caster_vertex + interpolation + storage + receiver; }
  double lateral_reach() const { return reach + caster_xy + receiver_xy; }
};

// The raster bias's r in a cascade: fixed for unorm; for float32 2^(e - 23), e the exponent of
// the largest depth of the caster's vertices, which is at least the receivers': a directional
// light's taken at depths in [1/2, 1) (the largest r, so the fewest units: nearer the light's near
// side a float buffer needs more), a spot light's at its row's depth.
double shadow_r(const ShadowSetup& s, size_t cascade);

struct ShadowBound {
  ShadowTerms terms;
  double texel = 0, range = 0;  // metres
  // A constant alone: window depth, and the same in r units and in metres along the light.
  double constant = 0, constant_units = 0, constant_metres = 0;
  // The slope factor with the constant the errors alone need (error_units r, error_metres).
  double slope_factor = 0;
  double error_constant = 0, error_units = 0, error_metres = 0;
  // The receiver normal offset with the same error constant: metres and texels.
  double normal_metres = 0, normal_texels = 0;
  // The shadow gap each costs, metres along the ground, for a wall standing on level ground under
  // the light's elevation (docs/shadow.md "The gap").
  double gap_constant = 0, gap_slope = 0, gap_normal = 0;
};

// The relative error the bound allows the rasteriser's depth slope (max(|dz/dx|, |dz/dy|)) against
// the plane's: triangles more than a few texels across and not sliver-thin (docs/shadow.md).
constexpr double kSlopeRelativeError = 0x1.0p-12;
// The relative error of the bias's own binary32 arithmetic (m factor + r units, two roundings).
constexpr double kBiasArithmetic = 0x1.0p-22;

ShadowBound shadow_bound(const ShadowSetup& s, size_t cascade, const BoundModel& model);

// A gap for a depth offset of `metres` along the light: the ground distance from a wall's foot
// over which the wall's shadow is lost, metres * cos(elevation).
double gap_of(const ShadowSetup& s, double metres);

}  // namespace depthprec
