#include "host/bias/bias_rule.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>

#include "host/base/errors.h"
#include "host/model/profile.h"
#include "host/runtime/kernel_variant.h"
#include "interface/bias_formula.h"

namespace depthprec {

namespace {

template <class E, size_t N>
E parse_named(const std::string& s, const char* what, const std::array<E, N>& all) {
  std::string names;
  for (E e : all) {
    if (s == to_string(e)) return e;
    names += (names.empty() ? "" : ", ") + std::string(to_string(e));
  }
  throw InputError(fmt::format("unknown {} '{}' (allowed: {})", what, s, names));
}

}  // namespace

const char* to_string(BiasApi a) {
  switch (a) {
    case BiasApi::gl:
      return "gl";
    case BiasApi::d3d:
      return "d3d";
    case BiasApi::vulkan:
      return "vulkan";
  }
  return "?";
}

const char* to_string(UnormR r) {
  switch (r) {
    case UnormR::pow2:
      return "pow2";
    case UnormR::step:
      return "step";
    case UnormR::double_step:
      return "double_step";
    case UnormR::double_pow2:
      return "double_pow2";
  }
  return "?";
}

const char* to_string(VulkanRepresentation r) {
  switch (r) {
    case VulkanRepresentation::format:
      return "format";
    case VulkanRepresentation::force_unorm:
      return "force_unorm";
    case VulkanRepresentation::float_value:
      return "float";
  }
  return "?";
}

const char* to_string(SlopeForm s) {
  return s == SlopeForm::max ? "max" : "sqrt";
}

BiasApi parse_bias_api(const std::string& s) {
  return parse_named<BiasApi, 3>(s, "--api", {BiasApi::gl, BiasApi::d3d, BiasApi::vulkan});
}
UnormR parse_unorm_r(const std::string& s) {
  return parse_named<UnormR, 4>(
      s, "--r-unorm", {UnormR::pow2, UnormR::step, UnormR::double_step, UnormR::double_pow2});
}
VulkanRepresentation parse_vulkan_representation(const std::string& s) {
  return parse_named<VulkanRepresentation, 3>(
      s, "--vulkan-representation",
      {VulkanRepresentation::format, VulkanRepresentation::force_unorm,
       VulkanRepresentation::float_value});
}
SlopeForm parse_slope_form(const std::string& s) {
  return parse_named<SlopeForm, 2>(s, "--slope", {SlopeForm::max, SlopeForm::sqrt});
}

std::optional<UnormR> scene_unorm_r(const Scene& scene) {
  const std::string name =
      scene.json.value("pipeline", nlohmann::json::object()).value("profile", "");
  if (name.empty() || name == "custom") return std::nullopt;
  const char* r = profile(name).bias_unorm_r;
  return r ? std::optional<UnormR>(parse_unorm_r(r)) : std::nullopt;
}

UnormR unorm_r_default(BiasApi api) {
  // GL leaves r to the implementation ("the smallest difference guaranteed to remain distinct"):
  // one code step. D3D: "the minimum representable value > 0 in the depth-buffer format", read
  // literally, is one step too. Vulkan: exactly 2^-n with depthBiasExact, which depthprec assumes.
  return api == BiasApi::vulkan ? UnormR::pow2 : UnormR::step;
}

double clamped(double o, double clamp) {
  if (clamp > 0) return std::min(o, clamp);
  if (clamp < 0) return std::max(o, clamp);
  return o;
}

bool clamp_binds(double clamp, int sign) {
  return clamp != 0 && (clamp > 0) == (sign > 0);
}

void validate(const BiasOptions& o) {
  if (!std::isfinite(o.clamp))
    throw InputError(
        fmt::format("--clamp {}: the clamp must be finite (> 0 limits the offset from above, < 0 "
                    "from below, 0: none)",
                    o.clamp));
  // The scene sets the steepest tilt it can measure (check_tilt, host/model/tilt_limit.h);
  // whatever the scene, a plane at 90 degrees or more is seen edge-on or from behind.
  if (!(o.tilt_deg >= 0 && o.tilt_deg < 90))
    throw InputError(
        fmt::format("--tilt {}: the planes' tilt must lie in [0, 90) degrees (at 90 a plane is "
                    "seen edge-on, beyond it from behind)",
                    o.tilt_deg));
  if (!std::isfinite(o.set_factor) || o.set_factor < 0)
    throw InputError(fmt::format("--set-factor {}: the slope factor must be >= 0", o.set_factor));
  if (o.api == BiasApi::d3d && o.slope == SlopeForm::sqrt)
    throw InputError(
        "--slope sqrt: Direct3D defines the slope as max(|dz/dx|, |dz/dy|) only (use --api gl or "
        "vulkan)");
  if (o.api != BiasApi::vulkan && o.representation != VulkanRepresentation::format)
    throw InputError(
        fmt::format("--vulkan-representation {}: depth bias representations are Vulkan's "
                    "(VK_EXT_depth_bias_control); give --api vulkan",
                    to_string(o.representation)));
}

float BiasRule::units_term(double units) const {
  return float_rule ? static_cast<float>(units) : static_cast<float>(r_fixed * units);
}

double BiasRule::r_at(float z) const {
  return float_rule ? static_cast<double>(depth_bias_float_r(std::fabs(z))) : r_fixed;
}

BiasRule bias_rule(const BiasOptions& o, const StorageFormat& f) {
  const std::string& name = f.name();
  const bool unorm = f.is_unorm() &&
                     (f.bits() == 16 || f.bits() == 24 || (f.bits() == 32 && o.api == BiasApi::gl));
  const bool float32 = name == "float32";
  if (!unorm && !float32)
    throw InputError(fmt::format(
        "{}: {} defines depth bias for {} only (no API has a bias rule for other formats)", name,
        to_string(o.api),
        o.api == BiasApi::gl ? "unorm16, unorm24, unorm32 and float32"
                             : "unorm16, unorm24 and float32"));
  BiasRule r;
  const auto fixed = [&r](double value, std::string text) {
    r.r_fixed = value;
    r.r_text = std::move(text);
  };
  if (float32) {
    if (o.api == BiasApi::vulkan && o.representation == VulkanRepresentation::force_unorm)
      fixed(std::ldexp(1.0, -24), "2^-24");  // FORCE_UNORM: a float buffer takes n = 24
    else if (o.api == BiasApi::vulkan && o.representation == VulkanRepresentation::float_value)
      fixed(1.0, "1");
    else {
      r.float_rule = true;
      r.r_text = "2^(e - 23)";
    }
    return r;
  }
  const int n = static_cast<int>(f.bits());
  if (o.api == BiasApi::vulkan && o.representation == VulkanRepresentation::float_value) {
    fixed(1.0, "1");
    return r;
  }
  const double steps = std::ldexp(1.0, n) - 1;
  switch (o.unorm_r.value_or(unorm_r_default(o.api))) {
    case UnormR::pow2:
      fixed(std::ldexp(1.0, -n), fmt::format("2^-{}", n));
      break;
    case UnormR::step:
      fixed(1.0 / steps, fmt::format("1/(2^{} - 1)", n));
      break;
    case UnormR::double_step:
      fixed(2.0 / steps, fmt::format("2/(2^{} - 1)", n));
      break;
    case UnormR::double_pow2:
      fixed(std::ldexp(1.0, 1 - n), fmt::format("2^-{}", n - 1));
      break;
  }
  return r;
}

std::string bias_not_applicable(const Scene& scene, const EvalPair& pair) {
  if (info(depth_path(scene, pair.technique)).from == DepthFrom::fragment)
    return "the fragment stage writes the depth, which replaces the rasterised depth the offset is "
           "added to";
  return "";
}

int bias_sign(const Scene& scene, const EvalPair& pair) {
  return info(depth_path(scene, pair.technique)).greater ? 1 : -1;
}

}  // namespace depthprec
