// Shadow acne emulated on the OpenCL device (kernels/shadow.cl): receiver planes sampled up to
// the slope limit, each the caster of its own shadow, and per bias setting the number of receiver
// points that shadow themselves. The host searches each recipe's smallest clean value, the
// witnessed counterpart of shadow_bound's proven one (docs/shadow.md "The emulation").
#pragma once

#include <cstdint>
#include <vector>

#include "host/shadow/shadow_bound.h"

namespace depthprec {

class OpenClRuntime;

struct ShadowSampling {
  uint32_t planes = 2048;  // receiver planes: half at the slope limit, a quarter at 45 degrees
  uint32_t grid = 8;       // receiver points per texel side
  uint64_t seed = 1;
};

// One bias setting: the raster constant in r (interface/bias_formula.h, signed by the compare
// function here), the raster slope factor, the receiver's normal offset in metres.
struct ShadowProbe {
  double units = 0, factor = 0, normal = 0;
};

// The receiver planes of one cascade: per plane its binary32 and binary64 records
// (interface/shadow_layout.h), made on the host from the sampling's seed alone.
struct ShadowPlanes {
  std::vector<float> f;
  std::vector<double> d;
  uint32_t count = 0;
};
ShadowPlanes shadow_planes(const ShadowSetup& s, size_t cascade, const ShadowSampling& sampling);

class ShadowEmulator {
 public:
  ShadowEmulator(OpenClRuntime& rt, const ShadowSetup& s, size_t cascade,
                 const ShadowSampling& sampling);
  ~ShadowEmulator();
  ShadowEmulator(const ShadowEmulator&) = delete;
  ShadowEmulator& operator=(const ShadowEmulator&) = delete;
  // Receiver points that shadow themselves under the setting, over every plane.
  uint64_t acne(const ShadowProbe& p);
  uint64_t points() const;
  uint64_t launches() const { return launches_; }

 private:
  struct Impl;
  Impl* impl_;
  uint64_t launches_ = 0;
};

// The smallest clean value of each recipe the emulation finds, by bisection below the bound's
// (which must be clean: `bound_clean` says whether it was).
struct ShadowWitness {
  double constant_units = 0, slope_factor = 0, normal_metres = 0;
  bool bound_clean = true;
  uint64_t acne_below = 0;  // acne points at 90 % of the bound's constant
};
ShadowWitness shadow_witness(ShadowEmulator& e, const ShadowBound& b, bool reversed);

}  // namespace depthprec
