// A directional light's cascaded shadow map as `depthprec shadow` measures it (docs/shadow.md):
// per cascade an orthographic box (a square extent seen from the light, a light-space depth
// range), one resolution, depth format and filter for all, the largest receiver slope to the
// light, and the world position the cascades sit at. Everything the bound, the emulation and the
// rendered check derive from it (texel size, the filter's reach, the light matrix) is here.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "host/bias/bias_rule.h"
#include "host/model/storage_format.h"
#include "host/model/technique.h"

namespace depthprec {

// What a lookup reads: the texels whose centres lie closer than `reach` texels to the receiver's
// shadow-map position along each axis (docs/shadow.md "Filters"). nearest 1/2; pcf2x2, the
// hardware's bilinear comparison, 1; pcfN, N x N hardware comparisons one texel apart, (N + 1)/2;
// tentN, Unity's N x N tent (built from bilinear comparisons), N/2.
struct ShadowFilter {
  std::string name;
  double reach = 0.5;
};
ShadowFilter parse_shadow_filter(const std::string& s);  // throws InputError naming the forms

inline double radians(double degrees) {
  return degrees * 3.14159265358979323846 / 180;
}

// A directional light (an orthographic map per cascade) or a spot light (one perspective map,
// measured at receiver distances along its axis).
enum class LightType { directional, spot };
const char* to_string(LightType t);

// A directional light's cascade, or a spot light's row: the map at one receiver distance.
struct ShadowCascade {
  double extent = 0;  // metres, the square's side seen from the light (spot: at `distance`)
  // Light-space near and far, metres along the light from the box's centre plane (the near side
  // is negative): the depth range is far - near.
  double near = 0, far = 0;
  double split_near = 0, split_far = 0;  // the camera distances it covers (0, 0: given directly)
  // Spot: the receivers' distance along the light's axis; near and far are the light's planes,
  // metres from it.
  double distance = 0;
  double depth_range() const { return far - near; }
};

struct ShadowSetup {
  LightType light = LightType::directional;
  double spot_angle = 60;  // degrees, the spot light's full cone (its map's field of view)
  std::vector<ShadowCascade> cascades;
  int resolution = 2048;
  StorageFormat format = StorageFormat::parse("float32");
  bool reversed = false;  // nearer the light is larger, compare GEQUAL
  ShadowFilter filter = parse_shadow_filter("pcf3");
  BiasOptions raster;     // how the raster bias's r is read (bias --api, --r-unorm)
  double slope_max = 80;  // degrees, the largest angle between a receiver's normal and the light
  std::array<double, 3> world_position{0, 0, 0};    // the cascades' centre, metres
  double light_elevation = 52, light_azimuth = 30;  // degrees: the light's direction
  double texel(size_t i) const { return cascades[i].extent / resolution; }
};

// A spot light's rows: one per receiver distance, each the map's extent there.
std::vector<ShadowCascade> spot_rows(const std::vector<double>& distances, double near, double far,
                                     double angle_deg);

// A spot light's window depth D(w) = A + C / w along its axis: the standard mapping, or the
// reversed one.
Technique spot_mapping(const ShadowSetup& s);

// Window depth per metre along the light at a row's receivers: 1 / range for a directional
// light; the perspective map's slope at the receivers' distance for a spot light.
double depth_per_metre(const ShadowSetup& s, size_t cascade);
// The distance along the light a receiver at the row's distance moves for a window-depth
// offset `depth` toward the light: depth times the range for a directional light, exact for a
// spot light (its map is not linear).
double metres_of_depth(const ShadowSetup& s, size_t cascade, double depth);

// Cascades fitted as engines fit stable cascades: each camera slice [split_i-1, split_i] of a
// perspective frustum (vertical field of view fov_deg, aspect) enclosed in its smallest sphere;
// the extent is the sphere's diameter, the depth range the diameter plus caster_padding toward
// the light. Throws InputError for splits that are not increasing and positive.
std::vector<ShadowCascade> cascades_from_splits(const std::vector<double>& splits,
                                                double camera_near, double fov_deg, double aspect,
                                                double caster_padding);

// Throws InputError naming the cascade and what is allowed: an extent or a depth range that is
// not positive and finite, a resolution outside [16, 65536], a slope outside [0, 90), a format
// other than unorm16, unorm24 and float32, a light below the horizon.
void validate(const ShadowSetup& s);

// The light's world-to-clip map of one cascade as an application hands it to the GPU, rounded to
// binary32: x / w and y / w are normalized device coordinates in [-1, 1] across the map, z / w the
// window depth in [0, 1] (zero-to-one range; reversed: 1 at the near side). A directional light's
// w row is (0, 0, 0, 1); a spot light's the distance along its axis. `basis` is the light's right,
// up and forward (direction of travel) axes in binary64.
struct LightMatrix {
  std::array<std::array<float, 4>, 4> m;
  std::array<std::array<double, 3>, 3> basis;  // right, up, forward
  std::array<double, 3> centre;                // the receivers' centre, world metres
  std::array<double, 3> position;              // spot: the light's position
  double tan_half = 0;                         // spot: tan of half the cone
};
LightMatrix light_matrix(const ShadowSetup& s, size_t cascade);

}  // namespace depthprec
