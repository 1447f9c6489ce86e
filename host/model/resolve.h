// Code <-> eye distance for a technique and storage format: which distances a stored code stands
// for, which code a distance gets and how far apart its neighbours are, and the resolution
// across the range. Exact mappings in binary64 (host/model/technique.cpp), differences of nearly
// equal distances in binary128.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "host/model/storage_format.h"
#include "host/model/technique.h"

namespace depthprec {

struct ResolveSetup {
  Technique technique = Technique::standard;
  double near = 1, far = 100;
  TechniqueParams params;
};

struct CodeInterval {
  uint32_t code = 0;
  double depth = 0;                         // the code's stored value
  double distance = 0;                      // eye distance of that value
  double depth_lo = 0, depth_hi = 0;        // depths that store this code (rounding mode's)
  double distance_lo = 0, distance_hi = 0;  // their eye distances, ordered lo <= hi
};

struct DistanceResolution {
  double distance = 0, depth = 0;
  uint32_t code = 0;
  double gap_below = 0;   // eye distance to the next code down (NaN: the first code has none)
  double gap_above = 0;   // ... and to the next code up (NaN: the last code has none)
  double resolution = 0;  // max of the two: the smallest step the buffer can resolve here
};

void validate(const ResolveSetup& s);  // throws InputError
// Throws InputError, naming `option`, when w is no eye distance or the mapping stores no depth for
// it: not finite and > 0, nearer than the near plane of a technique that clips there, or beyond
// the far plane.
void check_stored_distance(const ResolveSetup& s, double w, const std::string& option);

// The mapping that stores distance z: the technique's own, or for layered the layer_mapping
// with the near and far of the layer z is drawn in.
ResolveSetup mapping_at(Technique t, double near, double far, const TechniqueParams& p, double z);
CodeInterval resolve_code(const ResolveSetup& s, const StorageFormat& f, uint32_t code);
DistanceResolution resolve_distance(const ResolveSetup& s, const StorageFormat& f, double w);
// The eye-space width of the interval of distances whose exact depth stores the same code as w's:
// two planes closer than this can share a code wherever they sit, and with LEQUAL/GEQUAL a
// shared code is a fight, so a measurement that samples the whole interval cannot find a
// smaller MTS.
double code_interval_width(const ResolveSetup& s, const StorageFormat& f, double w);

// `points` eye distances spaced geometrically from near to far (both included).
std::vector<DistanceResolution> resolution_curve(const ResolveSetup& s, const StorageFormat& f,
                                                 int points);

// |Ze(a) - Ze(b)| for two depths, in binary128 so the difference keeps its digits.
double distance_gap(const ResolveSetup& s, double depth_a, double depth_b);

}  // namespace depthprec
