// Reads a scene's typed values from its merged JSON, with errors that name the key, blame the
// option or file that set it, and say what is allowed (host/model/scene_parse.cpp's parse_scene).
#pragma once

#include <fmt/format.h>

#include <array>
#include <cmath>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <string>

#include "host/base/errors.h"
#include "host/model/scene_json.h"

namespace depthprec {

// The value of a JSON number that is a whole number, however it is written (4, 4.0, 1e12, and an
// integer beyond 64 bits, which nlohmann reads as a double); nullopt for anything else.
inline std::optional<double> whole_value(const nlohmann::json& v) {
  if (!v.is_number()) return std::nullopt;
  const double d = v.get<double>();
  if (!std::isfinite(d) || d != std::floor(d)) return std::nullopt;
  return d;
}

// Reads typed values with errors that name the key and say what is allowed.
class Reader {
 public:
  // origins: the command-line option that set a key (e.g. "--near 5", "--set near=5"); a key
  // found there is blamed on it rather than on the scene file.
  Reader(const nlohmann::json& j, std::string source, std::string text,
         const std::map<std::string, std::string>& origins)
      : j_(j), source_(std::move(source)), text_(std::move(text)), origins_(origins) {}

  [[noreturn]] void fail(const std::string& key, const std::string& msg) const {
    for (std::string k = key;;
         k = k.substr(0, k.rfind('.'))) {  // "pipeline.divide", then "pipeline"
      const auto o = origins_.find(k);
      if (o != origins_.end()) throw InputError(fmt::format("{}: '{}' {}", o->second, key, msg));
      if (k.find('.') == std::string::npos) break;
    }
    const std::string leaf =
        key.substr(key.rfind('.') == std::string::npos ? 0 : key.rfind('.') + 1);
    throw InputError(fmt::format("{}: '{}' {}", scene_key_where(source_, text_, leaf), key, msg));
  }

  const nlohmann::json& at(const std::string& key) const {
    const nlohmann::json* p = &j_;
    std::stringstream ss(key);
    std::string part;
    while (std::getline(ss, part, '.')) {
      if (!p->is_object() || !p->contains(part)) fail(key, "is missing");
      p = &(*p)[part];
    }
    return *p;
  }

  // Text a number's syntax would take: digits, with a sign, a point or an exponent.
  static bool looks_numeric(const std::string& t) {
    return !t.empty() && t.find_first_not_of("+-.0123456789eE") == std::string::npos &&
           t.find_first_of("0123456789") != std::string::npos;
  }

  // A number; "inf" is accepted where allow_inf (JSON has no infinity).
  double number(const std::string& key, bool allow_inf = false) const {
    const nlohmann::json& v = at(key);
    if (allow_inf && v.is_string() && (v == "inf" || v == "infinity")) return INFINITY;
    if (!v.is_number()) {
      // A number too large for binary64 ("1e400") reaches here as the text typed.
      if (v.is_string() && looks_numeric(v.get<std::string>()))
        fail(key, fmt::format("must be a number{}; {} is beyond binary64's range (about 1.8e308)",
                              allow_inf ? " or \"inf\"" : "", v.get<std::string>()));
      fail(key,
           fmt::format("must be a number{}, not {}", allow_inf ? " or \"inf\"" : "", v.dump()));
    }
    const double d = v.get<double>();
    if (!std::isfinite(d)) fail(key, "must be finite");
    return d;
  }

  double positive(const std::string& key, bool allow_inf = false) const {
    const double d = number(key, allow_inf);
    if (!(d > 0)) fail(key, fmt::format("must be > 0, not {}", d));
    return d;
  }

  int integer(const std::string& key, int lo, int hi) const {
    const nlohmann::json& v = at(key);
    // A whole number too large for an integer (1e12, 1e30 reads as a double) is out of range
    // before it is no integer: the range is what the user needs to hear.
    const auto whole = whole_value(v);
    if (whole && (*whole < lo || *whole > hi))
      fail(key, fmt::format("must be {}..{}, not {} (too {})", lo, hi, v.dump(),
                            *whole > hi ? "large" : "small"));
    if (!v.is_number_integer()) fail(key, fmt::format("must be a whole number, not {}", v.dump()));
    return v.get<int>();
  }

  std::string string(const std::string& key) const {
    const nlohmann::json& v = at(key);
    if (!v.is_string()) fail(key, fmt::format("must be a string, not {}", v.dump()));
    return v.get<std::string>();
  }

  // "none" (0) or a whole number lo..hi.
  int none_or_integer(const std::string& key, int lo, int hi) const {
    const nlohmann::json& v = at(key);
    if (v == "none") return 0;
    const auto whole = whole_value(v);
    if (!v.is_number_integer() || *whole < lo || *whole > hi)
      fail(key, fmt::format("must be none or a whole number {}..{}, not {}", lo, hi, v.dump()));
    return v.get<int>();
  }

  bool boolean(const std::string& key) const {
    const nlohmann::json& v = at(key);
    if (!v.is_boolean()) fail(key, fmt::format("must be true or false, not {}", v.dump()));
    return v.get<bool>();
  }

  std::array<int, 2> size2(const std::string& key, int hi) const {
    const nlohmann::json& v = at(key);
    if (!v.is_array() || v.size() != 2 || !whole_value(v[0]) || !whole_value(v[1]))
      fail(key, fmt::format("must be [width, height] in pixels, not {}", v.dump()));
    const double w = *whole_value(v[0]), h = *whole_value(v[1]);
    if (w < 1 || h < 1 || w > hi || h > hi)
      fail(key, fmt::format("sides must be 1..{} pixels, not {}", hi, v.dump()));
    if (!v[0].is_number_integer() || !v[1].is_number_integer())
      fail(key, fmt::format("must be [width, height] in whole pixels, not {}", v.dump()));
    return {v[0].get<int>(), v[1].get<int>()};
  }

  std::array<double, 3> vec3(const std::string& key) const {
    const nlohmann::json& v = at(key);
    if (!v.is_array() || v.size() != 3)
      fail(key, fmt::format("must be three numbers [x, y, z], not {}", v.dump()));
    std::array<double, 3> out{};
    for (int i = 0; i < 3; ++i) {
      if (!v[i].is_number() || !std::isfinite(v[i].get<double>()))
        fail(key, fmt::format("must be three finite numbers, not {}", v.dump()));
      out[i] = v[i].get<double>();
    }
    return out;
  }

  // Converts an enum-like string with the given parser, reporting the key on failure.
  template <class F>
  auto choice(const std::string& key, F parse) const {
    const std::string s = string(key);
    try {
      return parse(s);
    } catch (const InputError& e) {
      fail(key, e.what());
    }
  }

 private:
  const nlohmann::json& j_;
  std::string source_;
  std::string text_;
  const std::map<std::string, std::string>& origins_;
};

}  // namespace depthprec
