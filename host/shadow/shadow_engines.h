// The bound's biases in the units of the engines' own settings (docs/shadow.md "Engines"), from
// each engine's published formula: where its depth bias moves the caster or the receiver and by
// how much per unit, the form of its normal offset, the raster slope it always applies, and its
// shipped defaults. Every per-engine fact is in this file's table.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "host/shadow/shadow_bound.h"

namespace depthprec {

// How far (metres along the light) a normal offset of k metres separates a receiver from a plane
// at slope theta: k / cos(theta) for a full-normal offset, k tan(theta) for one scaled by
// sin(theta), k sin(theta) tan(theta) for the lateral part alone, k (1 - cos(theta)) / cos(theta)
// for one scaled by 1 - N.L.
enum class NormalForm { full, sine, lateral, one_minus_cos };

// Metres (along the light, or along the normal) one unit of a setting stands for in a cascade:
// per_texel texels plus per_range depth ranges plus per_metre metres, over divisor (Godot's 1/100
// of the range), the texels times 2.5 under soft shadows where the engine scales by its filter
// (Unity: every filter but nearest).
struct SettingScale {
  double per_texel = 0, per_range = 0, per_metre = 0, divisor = 1;
};

struct EngineInfo {
  const char* name;
  const char* source;       // the file and function the conversion reads
  const char* depth_unit;   // what one unit of its depth bias setting is
  const char* normal_unit;  // what one unit of its normal bias setting is
  SettingScale depth_scale, normal_scale;
  bool soft_scaled;  // both scales times 2.5 unless the filter is nearest
  NormalForm normal_form;
  double raster_slope;  // the slope factor its shadow pass always sets (0: none)
  double raster_units;  // the constant units (r) it always sets
  double default_depth, default_normal;
  bool public_formula;  // false: the formula is not public (Unreal)
};

const std::vector<EngineInfo>& engine_table();
const EngineInfo& engine_info(const std::string& name);  // throws InputError naming them
std::string engine_names();

// One engine's settings for one cascade. Unset: no value of the setting suffices.
struct EngineBias {
  std::string engine;
  std::optional<double> depth_alone;                // the depth bias with no normal bias
  std::optional<double> normal_min;                 // the normal bias with the errors' depth bias
  std::optional<double> depth_with_normal_default;  // the depth bias with its default normal
  std::optional<double> depth_for_normal_min;       // the depth bias that goes with normal_min
  bool default_suffices = false;                    // its defaults leave no acne under the bound
};

// The depth bias setting engine e needs beside a normal bias setting of `normal` (0 when its
// raster bias alone covers the rest); unset when its formula is not public.
std::optional<double> engine_depth_for_normal(const EngineInfo& e, const ShadowSetup& s,
                                              size_t cascade, const ShadowBound& b, double normal);

// Every engine's settings for the cascade (the engines' names, or all when empty).
std::vector<EngineBias> engine_biases(const ShadowSetup& s, size_t cascade, const ShadowBound& b,
                                      const std::vector<std::string>& engines);

}  // namespace depthprec
