#include "host/base/did_you_mean.h"

#include <algorithm>
#include <cctype>
#include <map>

#include "host/base/text.h"

namespace depthprec {

namespace {

// Edits (insert, delete, substitute, swap two neighbours) from a to b: "mst" is one from "mts".
size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::vector<size_t>> d(a.size() + 1, std::vector<size_t>(b.size() + 1));
  for (size_t i = 0; i <= a.size(); ++i) d[i][0] = i;
  for (size_t j = 0; j <= b.size(); ++j) d[0][j] = j;
  for (size_t i = 1; i <= a.size(); ++i)
    for (size_t j = 1; j <= b.size(); ++j) {
      d[i][j] = std::min(
          {d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1)});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1])
        d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
    }
  return d[a.size()][b.size()];
}

std::string suggest(const std::string& typed, const std::map<std::string, std::string>& aliases,
                    const std::vector<std::string>& names) {
  const std::string key = to_lower(typed);
  const auto a = aliases.find(key);
  if (a != aliases.end()) return " (did you mean " + a->second + "?)";
  const std::string near = closest_name(typed, names);
  return near.empty() ? "" : " (did you mean " + near + "?)";
}

}  // namespace

std::string closest_name(const std::string& typed, const std::vector<std::string>& candidates) {
  const std::string t = to_lower(typed);
  std::string best;
  size_t best_d = std::max<size_t>(1, t.size() / 3) + 1;
  for (const auto& c : candidates) {
    const size_t d = edit_distance(t, to_lower(c));
    if (d < best_d) {
      best_d = d;
      best = c;
    }
  }
  return best;
}

std::string format_suggestion(const std::string& typed) {
  // What GL, D3D, Vulkan and WebGPU call the formats depthprec emulates.
  static const std::map<std::string, std::string> aliases = {
      {"d16", "unorm16"},
      {"d16_unorm", "unorm16"},
      {"depth16unorm", "unorm16"},
      {"depth_component16", "unorm16"},
      {"d24", "unorm24"},
      {"d24s8", "unorm24"},
      {"d24x8", "unorm24"},
      {"d24_unorm", "unorm24"},
      {"d24_unorm_s8_uint", "unorm24"},
      {"x8_d24_unorm_pack32", "unorm24"},
      {"depth24plus", "unorm24"},
      {"depth_component24", "unorm24"},
      {"d32", "unorm32 (GL_DEPTH_COMPONENT32) or float32 (D32_FLOAT)"},
      {"depth_component32", "unorm32"},
      {"d32f", "float32"},
      {"d32_float", "float32"},
      {"d32_sfloat", "float32"},
      {"d32_float_s8x24_uint", "float32"},
      {"depth32float", "float32"},
      {"depth_component32f", "float32"},
      {"f32", "float32"},
      {"fp32", "float32"},
      {"float", "float32"},
      {"f16", "float16"},
      {"fp16", "float16"},
      {"half", "float16"},
  };
  static const std::vector<std::string> names = {"unorm16", "unorm24", "unorm32",
                                                 "float16", "float24", "float32"};
  return suggest(typed, aliases, names);
}

std::string technique_suggestion(const std::string& typed, const std::vector<std::string>& names) {
  static const std::map<std::string, std::string> aliases = {
      {"z", "standard"},
      {"zbuffer", "standard"},
      {"z_buffer", "standard"},
      {"perspective", "standard"},
      {"infinite_far", "infinite"},
      {"reverse_z", "reversed"},
      {"reversed_z", "reversed"},
      {"reverse", "reversed"},
      {"complementary_z", "reversed"},
      {"log", "log_vertex or log_fragment"},
      {"logarithmic", "log_vertex or log_fragment"},
      {"threejs", "log_threejs"},
      {"three.js", "log_threejs"},
      {"logarithmic_depth_buffer", "log_threejs"},
      {"cesium", "log_cesium"},
      {"outerra", "log_threejs or log_threejs_vertex"},
      {"w", "w_buffer"},
      {"wbuffer", "w_buffer"},
      {"1/w", "inverse_w"},
  };
  return suggest(typed, aliases, names);
}

std::string buffer_suggestion(const std::string& typed) {
  static const std::map<std::string, std::string> aliases = {
      {"reversed", "complementary_z"},
      {"reversed_z", "complementary_z"},
      {"reverse_z", "complementary_z"},
      {"reversed_infinite", "inverse_w"},
      {"standard", "z"},
      {"zbuffer", "z"},
      {"z_buffer", "z"},
      {"z-buffer", "z"},
      {"linear", "w"},
      {"wbuffer", "w"},
      {"w_buffer", "w"},
      {"w-buffer", "w"},
      {"1/w", "inverse_w"},
  };
  static const std::vector<std::string> names = {"z", "w", "inverse_w", "complementary_z"};
  return suggest(typed, aliases, names);
}

}  // namespace depthprec
