// How an API turns a depth bias (units, factor, clamp) into an offset of window depth for a
// storage format (docs/bias.md): the minimum resolvable difference r per format and API, the
// slope form, the clamp and the sign the compare function asks for. The arithmetic itself is
// interface/bias_formula.h, shared with the kernel.
#pragma once

#include <optional>
#include <string>

#include "host/model/scene.h"
#include "host/model/storage_format.h"

namespace depthprec {

enum class BiasApi { gl, d3d, vulkan };
// r of a unorm<n> buffer where the API leaves it open (GL: implementation-dependent; Vulkan
// without depthBiasExact: up to 2 x 2^-n):
//   pow2         2^-n             Vulkan with depthBiasExact, D3D as translation layers read it
//   step         1/(2^n - 1)      one code step: D3D's "minimum representable value > 0", Mesa's
//   mrd double_step  2/(2^n - 1)      Mesa's Gallium drivers (llvmpipe: units * mrd * 2)
//   double_pow2  2 x 2^-n         NVIDIA without depthBiasExact
enum class UnormR { pow2, step, double_step, double_pow2 };
// VK_EXT_depth_bias_control's depthBiasRepresentation.
enum class VulkanRepresentation { format, force_unorm, float_value };
enum class SlopeForm { max, sqrt };  // m = max(|dz/dx|, |dz/dy|) or sqrt(dz/dx^2 + dz/dy^2)

const char* to_string(BiasApi a);
const char* to_string(UnormR r);
const char* to_string(VulkanRepresentation r);
const char* to_string(SlopeForm s);
BiasApi parse_bias_api(const std::string& s);  // each throws InputError listing the names
UnormR parse_unorm_r(const std::string& s);
VulkanRepresentation parse_vulkan_representation(const std::string& s);
SlopeForm parse_slope_form(const std::string& s);

struct BiasOptions {
  BiasApi api = BiasApi::gl;
  std::optional<UnormR> unorm_r;  // unset: the API's own (unorm_r_default)
  VulkanRepresentation representation = VulkanRepresentation::format;
  SlopeForm slope = SlopeForm::max;
  // The APIs' signed clamp (D3D DepthBiasClamp, Vulkan depthBiasClamp, GL
  // glPolygonOffsetClamp): > 0 limits the offset from above, < 0 from below, 0 none (clamped).
  double clamp = 0;
  bool or_equal = false;  // LEQUAL / GEQUAL instead of the APIs' default LESS / GREATER
  double tilt_deg = 0;    // planes tilted about the view's x axis, on top of the scene's rotation
  double set_factor = 1;  // the slope factor of the pair a user would set
};

UnormR unorm_r_default(BiasApi api);
// The r of unorm buffers under the scene's implementation profile (pipeline.profile: llvmpipe's
// double step), none where the scene names no profile or its profile models none.
std::optional<UnormR> scene_unorm_r(const Scene& scene);

// The offset o after the API's clamp c: min(o, c) for c > 0, max(o, c) for c < 0, o for c = 0.
// A clamp of the other sign than the offset never binds: under LESS the bias is negative, and
// only a negative clamp limits it. The kernels apply the same rule in binary32
// (interface/bias_formula.h depth_bias); this is the host's, in binary64, for the offset reported.
double clamped(double o, double clamp);

// Whether the clamp can bind the offsets of a pair whose bias carries sign (bias_sign): 0 or the
// same sign.
bool clamp_binds(double clamp, int sign);

// Throws InputError for options that contradict each other or the API (a clamp that is not
// finite, a tilt outside [0, 90) degrees, sqrt slopes under D3D, a representation outside
// Vulkan). The scene's own limit on the tilt is check_tilt's (host/model/tilt_limit.h).
void validate(const BiasOptions& o);

// The r of one storage format under the options.
struct BiasRule {
  bool float_rule = false;  // r = 2^(e - 23), e the exponent of the primitive's largest |z|
  double r_fixed = 0;       // otherwise r, exact
  std::string r_text;       // "1/(2^24 - 1)", "2^(e - 23)", ...
  // What the kernel's depth_bias takes as units_term: the units (float rule) or fl32(r * units).
  float units_term(double units) const;
  // r for a primitive whose largest |z| is the binary32 z.
  double r_at(float z) const;
};

// Throws InputError when the API defines no depth bias for the format (naming the formats it
// does: gl unorm16/24/32 and float32; d3d and vulkan unorm16, unorm24 and float32).
BiasRule bias_rule(const BiasOptions& o, const StorageFormat& f);

// Whether the API's bias reaches the pair's stored depth: not when the fragment stage writes the
// depth (log_fragment, linear, w_buffer, a layered mapping among them), which replaces the
// rasterised depth the offset was added to. The reason, or "" when it applies.
std::string bias_not_applicable(const Scene& scene, const EvalPair& pair);

// The sign an application gives units and factor so plane B moves toward the camera: -1 where
// nearer is smaller (LESS), +1 for the reversed mappings (GREATER).
int bias_sign(const Scene& scene, const EvalPair& pair);

}  // namespace depthprec
