#include "host/mts/row_json.h"

#include <fmt/format.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <sstream>

#include "host/base/errors.h"
#include "host/base/json_number.h"

namespace depthprec {

using nlohmann::json;

namespace {

json number(double v) {
  return json_number(v);
}

double read_number(const json& j, const char* key) {
  if (!j.contains(key)) throw InputError(fmt::format("row is missing '{}'", key));
  return number_from_json(j.at(key), std::string("row field ") + key);
}

// A count read back from a file: an integer in T's range, else an InputError (a float such as
// 4.8e58 would otherwise be converted with undefined behaviour).
template <class T>
T read_count(const json& j, const char* key) {
  if (!j.contains(key)) throw InputError(fmt::format("row is missing '{}'", key));
  const json& v = j.at(key);
  const bool fits = v.is_number_unsigned()
                        ? v.get<uint64_t>() <= static_cast<uint64_t>(std::numeric_limits<T>::max())
                        : v.is_number_integer() && v.get<int64_t>() >= 0 &&
                              static_cast<uint64_t>(v.get<int64_t>()) <=
                                  static_cast<uint64_t>(std::numeric_limits<T>::max());
  if (!fits)
    throw InputError(fmt::format("row field {} must be a count (a non-negative integer), not {}",
                                 key, v.dump()));
  return static_cast<T>(v.is_number_unsigned() ? v.get<uint64_t>()
                                               : static_cast<uint64_t>(v.get<int64_t>()));
}

}  // namespace

std::string row_key(const EvalPair& pair, double z) {
  return fmt::format("{}@{:.17g}", pair.label(), z);
}

json row_to_json(const MtsRow& r, bool timing) {
  json j = r.pair.fields();
  if (!r.profile.empty()) j["profile"] = r.profile;
  j.update({{"source", to_string(r.source)},
            {"z", r.z},
            {"mts", number(r.mts)},
            {"bound_model", r.bound_model},
            {"bound_by", r.bound_note},
            {"mts_paper", number(r.mts_paper)},
            {"orientations", r.orientations},
            {"convergence", r.convergence},
            {"lo", r.lo},
            {"hi", number(r.hi)},
            {"mts_seen", number(r.mts_seen)},
            {"vertex_bound", r.vertex_bound},
            {"probes", r.probes},
            {"clipped_probes", r.clipped_probes},
            {"frames", r.frames},
            {"fragment_pairs", r.fragment_pairs},
            {"kernel_launches", r.launches},
            {"fight_max", number(r.fight_max)},
            {"clean_min", number(r.clean_min)},
            {"flags", r.flags()},
            {"verdict", to_string(r.verdict())}});
  if (!std::isnan(r.mts_bound)) j["mts_bound"] = number(r.mts_bound);  // left out where none
  if (!std::isnan(r.monotone_fight)) {
    j["monotone_clean"] = number(r.monotone_clean);
    j["monotone_fight"] = number(r.monotone_fight);
  }
  if (r.below_one_code) j["code_width"] = number(r.code_width);
  if (r.below_world_grid) j["world_grid_reach"] = number(r.world_grid_reach);
  if (r.attributed()) {
    j["storage_mts"] = number(r.storage_mts);
    j["arithmetic_mts"] = number(r.arithmetic_mts);
    j["dominant"] = r.dominant;
  }
  if (timing) {
    j["seconds"] = r.seconds;
    j["kernel_seconds"] = r.kernel_seconds;
    if (r.source == RowSource::rendered) j["frames_per_second"] = r.frames_per_second;
  }
  return j;
}

MtsRow row_from_json(const json& j) {
  if (!j.is_object()) throw InputError("a row must be a JSON object");
  MtsRow r;
  try {
    r.source = parse_row_source(j.value("source", "emulated"));
    r.profile = j.value("profile", "");
    r.pair.technique = parse_technique(j.at("technique").get<std::string>());
    r.pair.format = j.at("format").get<std::string>();
    r.pair.depth_range = parse_depth_range(j.at("depth_range").get<std::string>());
    r.probes = read_count<int>(j, "probes");
    r.clipped_probes = read_count<int>(j, "clipped_probes");
    r.frames = read_count<uint64_t>(j, "frames");
    r.fragment_pairs = read_count<uint64_t>(j, "fragment_pairs");
    r.launches = read_count<uint64_t>(j, "kernel_launches");
    const std::string flags = j.at("flags").get<std::string>();
    std::stringstream ss(flags);
    std::string f;
    while (std::getline(ss, f, ',')) {
      if (f == "non_finite")
        r.non_finite = true;
      else if (f == "clipped")
        r.clipped = true;
      else if (f == "unresolvable")
        r.unresolvable = true;
      else if (f == "non_monotone")
        r.non_monotone = true;
      else if (f == "uncovered")
        r.uncovered = true;
      else if (f == "beyond_far_plane")
        r.beyond_far = true;
      else if (f == "nearer_than_near_plane")
        r.before_near = true;
      else if (f == "below_one_code")
        r.below_one_code = true;
      else if (f == "below_world_grid")
        r.below_world_grid = true;
      else
        throw InputError(fmt::format("unknown row flag '{}'", f));
    }
  } catch (const json::exception& e) {
    throw InputError(fmt::format("malformed row {}: {}", j.dump(), e.what()));
  }
  r.z = read_number(j, "z");
  r.mts = read_number(j, "mts");
  if (j.contains("mts_bound")) r.mts_bound = read_number(j, "mts_bound");
  r.bound_note = j.value("bound_by", "");
  r.bound_model = j.value("bound_model", "");
  r.mts_paper = j.contains("mts_paper") ? read_number(j, "mts_paper") : r.mts;
  r.orientations = j.contains("orientations") ? read_count<uint64_t>(j, "orientations") : 0;
  r.convergence = j.contains("convergence") ? read_number(j, "convergence") : 0;
  r.lo = read_number(j, "lo");
  r.hi = read_number(j, "hi");
  r.mts_seen = read_number(j, "mts_seen");
  r.vertex_bound = read_number(j, "vertex_bound");
  r.fight_max = read_number(j, "fight_max");
  if (j.contains("storage_mts")) {
    r.storage_mts = read_number(j, "storage_mts");
    r.arithmetic_mts = read_number(j, "arithmetic_mts");
    r.dominant = j.value("dominant", "");
  }
  r.clean_min = read_number(j, "clean_min");
  if (j.contains("monotone_fight")) {
    r.monotone_clean = read_number(j, "monotone_clean");
    r.monotone_fight = read_number(j, "monotone_fight");
  }
  if (r.below_one_code) r.code_width = read_number(j, "code_width");
  if (r.below_world_grid) r.world_grid_reach = read_number(j, "world_grid_reach");
  if (j.contains("seconds")) r.seconds = read_number(j, "seconds");
  if (j.contains("kernel_seconds")) r.kernel_seconds = read_number(j, "kernel_seconds");
  if (j.contains("frames_per_second")) r.frames_per_second = read_number(j, "frames_per_second");
  return r;
}

}  // namespace depthprec
