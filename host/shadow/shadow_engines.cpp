#include "host/shadow/shadow_engines.h"

#include <fmt/format.h>

#include <cmath>

#include "host/base/errors.h"

namespace depthprec {

namespace {

// The metres one unit of an engine's setting stands for in a cascade.
struct Scales {
  double depth;   // metres along the light per unit of depth bias (negative: its sign is flipped)
  double normal;  // metres per unit of normal bias
};

Scales scales_of(const EngineInfo& e, const ShadowSetup& s, size_t cascade) {
  const double texel = s.texel(cascade), range = s.cascades[cascade].depth_range();
  const double soft = e.soft_scaled && s.filter.name != "nearest" ? 2.5 : 1.0;
  auto metres = [&](const SettingScale& k) {
    return (k.per_texel * texel * soft + k.per_range * range + k.per_metre) / k.divisor;
  };
  return {metres(e.depth_scale), metres(e.normal_scale)};
}

double clearance(NormalForm f, double k, double theta) {
  const double c = std::cos(theta), sn = std::sin(theta);
  switch (f) {
    case NormalForm::full:
      return k / c;
    case NormalForm::sine:
      return k * sn / c;
    case NormalForm::lateral:
      return k * sn * sn / c;
    case NormalForm::one_minus_cos:
      return k * (1 - c) / c;
  }
  return 0;
}

}  // namespace

const std::vector<EngineInfo>& engine_table() {
  static const std::vector<EngineInfo> table = {
      {"unity",
       "Unity URP ShadowUtils.cs GetShadowBias; ShaderLibrary/Shadows.hlsl ApplyShadowBias",
       "texels (x 2.5 with soft shadows), caster moved away along the light",
       "texels (x 2.5 with soft shadows), caster inset along its normal x (1 - N.L)",
       {1, 0, 0},
       {1, 0, 0},
       true,
       NormalForm::one_minus_cos,
       2.5,
       1.0,
       1.0,
       1.0,
       true},
      {"godot",
       "Godot 4 renderer_scene_cull.cpp (bias_scale, shadow_texel_size); light_storage.cpp "
       "update_light_buffers; scene_forward_clustered light_dir_shadow BIAS_FUNC",
       "1/100 of the cascade's depth range (Hard quality), receiver toward the light",
       "texels, receiver moved along the normal's part across the light",
       {0, 0.01, 0},
       {1, 0, 0},
       false,
       NormalForm::lateral,
       0,
       0,
       0.1,
       2.0,
       true},
      {"bevy",
       "Bevy shadows.wesl sample_directional_cascade; render/light.rs (normal bias x sqrt 2)",
       "metres, receiver toward the light",
       "texels x sqrt(2), receiver along its normal",
       {0, 0, 1},
       {std::sqrt(2.0), 0, 0},
       false,
       NormalForm::full,
       0,
       0,
       0.02,
       1.8,
       true},
      {"threejs",
       "three.js shadowmap_vertex.glsl.js; shadowmap_pars_fragment.glsl.js getShadow",
       "window depth of the shadow camera, added to the receiver (negative lifts it)",
       "metres, receiver along its normal",
       {0, -1, 0},
       {0, 0, 1},
       false,
       NormalForm::full,
       0,
       0,
       0,
       0,
       true},
      {"filament",
       "Filament LightManager.h ShadowOptions; ShadowMap.cpp updateDirectional; "
       "ShadowMapManager.cpp; common_shadowing.glsl computeLightSpacePosition",
       "metres, caster moved away along the light",
       "texels x 1/2, receiver along its normal x sin(theta)",
       {0, 0, 1},
       {0.5, 0, 0},
       false,
       NormalForm::sine,
       2.0,
       0.5,
       0.001,
       1.0,
       true},
      {"babylon",
       "Babylon.js shadowGenerator.ts; shadowMapVertexMetric, shadowMapVertexNormalBias",
       "window depth of the light's range, added to the caster",
       "metres, caster inset along its normal x sin(theta)",
       {0, 1, 0},
       {0, 0, 1},
       false,
       NormalForm::sine,
       0,
       0,
       0.00005,
       0,
       true},
      {"unreal",
       "not public: ShadowBias and r.Shadow.CSMDepthBias are applied in ShadowRendering.cpp, "
       "outside the public sources",
       "",
       "",
       {},
       {},
       false,
       NormalForm::full,
       0,
       0,
       0.5,
       0,
       false},
  };
  return table;
}

const EngineInfo& engine_info(const std::string& name) {
  for (const EngineInfo& e : engine_table())
    if (name == e.name) return e;
  throw InputError(fmt::format("unknown engine '{}': expected {}", name, engine_names()));
}

std::string engine_names() {
  std::string out;
  for (const EngineInfo& e : engine_table()) out += (out.empty() ? "" : ", ") + std::string(e.name);
  return out;
}

namespace {

// One engine's conversion in a cascade: its scales, the reach its raster slope leaves uncovered,
// and the depth offset (metres along the light) a normal offset of k metres still needs.
struct EngineConversion {
  Scales sc;
  double a = 0;              // metres of uncovered reach per unit of tan(theta)
  double raster_metres = 0;  // what its raster constant covers
  double error_metres = 0;
  double theta_max = 0;
  NormalForm form = NormalForm::full;

  EngineConversion(const EngineInfo& e, const ShadowSetup& s, size_t cascade, const ShadowBound& b)
      : sc(scales_of(e, s, cascade)), form(e.normal_form) {
    // The raster slope the engine always sets covers part of the reach: at the worst azimuth
    // the texels' drop sqrt(2) reach' g against the slope bias's factor g / sqrt(2)
    // (shadow_bound.cpp).
    a = std::max(0.0, std::sqrt(2.0) * b.terms.lateral_reach() - e.raster_slope / std::sqrt(2.0)) *
        b.texel;
    raster_metres = e.raster_units * shadow_r(s, cascade) * b.range;
    error_metres = b.error_metres;
    theta_max = radians(s.slope_max);
  }
  // The largest uncovered reach over slopes up to the limit, on a grid fine enough for these
  // smooth functions, plus the errors' constant.
  double need(double k) const {
    double worst = 0;
    const int steps = 4096;
    for (int i = 0; i <= steps; ++i) {
      const double th = theta_max * i / steps;
      worst = std::max(worst, a * std::tan(th) - clearance(form, k, th));
    }
    return error_metres + worst;
  }
  double setting(double metres) const { return std::max(0.0, metres - raster_metres) / sc.depth; }
};

}  // namespace

std::optional<double> engine_depth_for_normal(const EngineInfo& e, const ShadowSetup& s,
                                              size_t cascade, const ShadowBound& b, double normal) {
  if (!e.public_formula) return std::nullopt;
  const EngineConversion c(e, s, cascade, b);
  return c.setting(c.need(normal * c.sc.normal));
}

std::vector<EngineBias> engine_biases(const ShadowSetup& s, size_t cascade, const ShadowBound& b,
                                      const std::vector<std::string>& engines) {
  std::vector<const EngineInfo*> chosen;
  if (engines.empty())
    for (const EngineInfo& e : engine_table()) chosen.push_back(&e);
  else
    for (const std::string& n : engines) chosen.push_back(&engine_info(n));
  std::vector<EngineBias> out;
  for (const EngineInfo* e : chosen) {
    EngineBias eb;
    eb.engine = e->name;
    if (!e->public_formula) {
      out.push_back(eb);
      continue;
    }
    const EngineConversion c(*e, s, cascade, b);
    eb.depth_alone = c.setting(c.need(0));
    if (e->normal_form == NormalForm::full)
      eb.normal_min = c.a * std::sin(c.theta_max) * (1 + kBiasArithmetic) / c.sc.normal;
    else if (e->normal_form == NormalForm::sine)
      eb.normal_min = c.a * (1 + kBiasArithmetic) / c.sc.normal;
    if (eb.normal_min) eb.depth_for_normal_min = c.setting(b.error_metres);
    const double needed = c.need(e->default_normal * c.sc.normal);
    eb.depth_with_normal_default = c.setting(needed);
    eb.default_suffices = e->default_depth * c.sc.depth + c.raster_metres >= needed;
    out.push_back(eb);
  }
  return out;
}

}  // namespace depthprec
