#include "host/model/scene.h"

#include <fmt/format.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "host/base/embedded_sources.h"
#include "host/base/errors.h"
#include "host/base/named_choice.h"
#include "host/base/read_file.h"
#include "host/model/profile.h"
#include "host/model/scene_json.h"
#include "interface/mts_layout.h"

namespace depthprec {

const char* to_string(Transform t) {
  switch (t) {
    case Transform::absolute:
      return "absolute";
    case Transform::camera_relative:
      return "camera_relative";
    case Transform::relative_to_eye:
      return "relative_to_eye";
  }
  return "?";
}

Transform parse_transform(const std::string& s) {
  return named_choice<Transform>("transform", s,
                                 {{"absolute", Transform::absolute},
                                  {"camera_relative", Transform::camera_relative},
                                  {"relative_to_eye", Transform::relative_to_eye}});
}

const char* to_string(ShaderPrecision p) {
  switch (p) {
    case ShaderPrecision::highp:
      return "highp";
    case ShaderPrecision::mediump:
      return "mediump";
    case ShaderPrecision::es2_highp:
      return "es2_highp";
  }
  return "?";
}

ShaderPrecision parse_shader_precision(const std::string& s) {
  return named_choice<ShaderPrecision>("shader_precision", s,
                                       {{"highp", ShaderPrecision::highp},
                                        {"mediump", ShaderPrecision::mediump},
                                        {"es2_highp", ShaderPrecision::es2_highp}});
}

int Pipeline::clip_slots() const {
  return clip == ClipForm::llvmpipe ? MTS_CLIP_SLOTS : 1;
}

using nlohmann::json;

namespace {

constexpr const char* kDefaultPath = "data/gilg2021.json";

const std::set<std::string> kTopKeys = {"name",
                                        "description",
                                        "near",
                                        "far",
                                        "kernel",
                                        "viewport",
                                        "fov_y_deg",
                                        "plane_margin",
                                        "plane_subdivisions",
                                        "frames",
                                        "delta_a",
                                        "rotation_range_deg",
                                        "rotation_step",
                                        "rotation_offset",
                                        "distances",
                                        "world_position",
                                        "rel_precision",
                                        "max_separation_factor",
                                        "stiffness_probes",
                                        "sampling",
                                        "bound_model",
                                        "interpolation_tolerance",
                                        "worst_case",
                                        "pipeline",
                                        "shadow",
                                        "log_k",
                                        "layers",
                                        "layer_mapping",
                                        "layer_overlap",
                                        "evaluate"};
const std::set<std::string> kPipelineKeys = {
    "depth_range", "matrix_precision", "compose", "divide",   "rounding",
    "denormals",   "contraction",      "plane",   "viewport", "conversion",
    "vertex",      "profile",          "log",     "clip",     "snap",
    "transform",   "shader_precision", "envelope"};
const std::set<std::string> kPairKeys = {"technique", "format", "depth_range"};
const std::set<std::string> kWorstCaseKeys = {"min_rounds", "max_rounds", "round_size",
                                              "tolerance"};

void check_known_keys(const json& j, const std::set<std::string>& known, const std::string& what,
                      const std::string& source, const std::string& text) {
  if (!j.is_object()) return;
  for (const auto& item : j.items()) {
    if (known.count(item.key())) continue;
    std::string list;
    for (const auto& k : known) list += (list.empty() ? "" : ", ") + k;
    throw InputError(fmt::format("{}: unknown key '{}' in {}; known keys: {}",
                                 scene_key_where(source, text, item.key()), item.key(), what,
                                 list));
  }
}

void check_user_keys(const json& j, const std::string& source, const std::string& text) {
  if (!j.is_object()) throw InputError(fmt::format("{}: a scene is a JSON object", source));
  check_known_keys(j, kTopKeys, "the scene", source, text);
  // Blocks of settings are objects, null included: merged into the default's, anything else
  // would replace (or, null, delete) the whole block.
  for (const auto& [key, what] :
       {std::pair<const char*, const char*>{"pipeline", "the pipeline's settings (docs/spec.md 2)"},
        {"worst_case", "the worst case's settings (docs/mts.md)"}})
    if (j.contains(key) && !j[key].is_object())
      throw InputError(fmt::format("{}: '{}' must be an object of {}, not {}",
                                   scene_key_where(source, text, key), key, what, j[key].dump()));
  if (j.contains("pipeline"))
    check_known_keys(j["pipeline"], kPipelineKeys, "pipeline", source, text);
  if (j.contains("worst_case"))
    check_known_keys(j["worst_case"], kWorstCaseKeys, "worst_case", source, text);
  if (j.contains("evaluate") && j["evaluate"].is_array())
    for (const auto& p : j["evaluate"])
      check_known_keys(p, kPairKeys, "an evaluate entry", source, text);
}

// "a.b=value": value parsed as JSON, or taken as a string when it is not JSON.
void apply_override(json& j, const std::string& assignment) {
  const auto eq = assignment.find('=');
  if (eq == std::string::npos || eq == 0)
    throw InputError(
        fmt::format("override '{}' must be key=value, e.g. near=0.5 or "
                    "pipeline.depth_range=zero_to_one",
                    assignment));
  const std::string key = assignment.substr(0, eq);
  const std::string raw = assignment.substr(eq + 1);
  json value = json::parse(raw, nullptr, false);
  if (value.is_discarded()) value = raw;
  json* p = &j;
  std::stringstream ss(key);
  std::string part;
  std::vector<std::string> parts;
  while (std::getline(ss, part, '.')) parts.push_back(part);
  for (size_t i = 0; i + 1 < parts.size(); ++i) p = &(*p)[parts[i]];
  (*p)[parts.back()] = value;
}

}  // namespace

void check_pairs(const Scene& s) {
  if (std::isfinite(s.far)) return;
  for (const auto& p : s.evaluate)
    if (has_far_plane(p.technique))
      throw InputError(
          fmt::format("far = inf: {} needs a finite far plane (as do all of {}); only "
                      "infinite, reversed_infinite and inverse_w have none",
                      p.label(), finite_far_technique_names()));
}

void check_planes_cover_kernel(const Scene& s) {
  // The square planes span plane_margin times the viewport's height in both directions (their
  // side is plane_margin * 2 D tan(fov/2)), centred: a kernel wider than that has pixels no plane
  // covers in any frame, and no probe could be accepted.
  const double plane_px = s.plane_margin * s.viewport_h;
  if (s.kernel_w > plane_px || s.kernel_h > plane_px)
    throw InputError(fmt::format(
        "kernel {}x{} is wider than the planes, which span plane_margin x viewport height = {} x "
        "{} = {:g} "
        "pixels: no probe could be accepted; raise plane_margin to at least {:g} or narrow the "
        "kernel",
        s.kernel_w, s.kernel_h, s.plane_margin, s.viewport_h, plane_px,
        std::ceil(100.0 * std::max(s.kernel_w, s.kernel_h) / s.viewport_h * 1.05) / 100));
}

std::string EvalPair::label() const {
  return fmt::format("{}/{}/{}", info(technique).name, format, to_string(depth_range));
}

nlohmann::json EvalPair::fields() const {
  return {{"technique", info(technique).name},
          {"format", format},
          {"depth_range", to_string(depth_range)}};
}

std::string pair_label(const nlohmann::json& record) {
  return fmt::format("{}/{}/{}", record.at("technique").get<std::string>(),
                     record.at("format").get<std::string>(),
                     record.at("depth_range").get<std::string>());
}

const std::string& default_scene_text() {
  static const std::string text = embedded_sources().at(kDefaultPath);
  return text;
}

Scene load_scene(const std::string& path, const std::vector<std::string>& overrides, bool check,
                 const std::map<std::string, std::string>& origins) {
  if (path.empty()) return load_scene_text("", "", overrides, check, origins);
  return load_scene_text(read_input_file(path, "scene file"), path, overrides, check, origins);
}

namespace {

// pipeline.profile (host/model/profile.cpp): the named profile's settings fill the pipeline keys
// the scene file and the overrides leave alone; a key either sets to another value is refused,
// naming both. "custom" (what a header says of a pipeline no profile matches) names none.
void apply_profile(json& merged, const std::vector<const json*>& layers,
                   const std::map<std::string, std::string>& blame, const std::string& where) {
  std::string name;
  for (const json* layer : layers)
    if (layer->contains("pipeline") && (*layer)["pipeline"].contains("profile")) {
      const json& v = (*layer)["pipeline"]["profile"];
      if (!v.is_string())
        throw InputError(fmt::format("pipeline.profile: expected a profile's name ({}), not {}",
                                     profile_names(), v.dump()));
      name = v.get<std::string>();
    }
  if (name.empty() || name == "custom") return;
  const auto named = [&blame](const std::string& key, const std::string& fallback) {
    const auto it = blame.find(key);
    return it != blame.end() ? it->second : fallback;
  };
  for (const std::string& set : profile(name).sets) {
    const auto [key, value] = pipeline_setting(set);
    for (const json* layer : layers)
      if (layer->contains("pipeline") && (*layer)["pipeline"].contains(key) &&
          (*layer)["pipeline"][key] != value)
        throw InputError(fmt::format("{} sets pipeline.{} to {}, and {} sets it to {}: give one",
                                     named("pipeline.profile", "pipeline.profile " + name), key,
                                     value.is_string() ? value.get<std::string>() : value.dump(),
                                     named("pipeline." + key, where),
                                     (*layer)["pipeline"][key].dump()));
    merged["pipeline"][key] = value;
  }
}

// A pipeline with an envelope's adversary is bounded under that envelope's model unless a layer
// names one (a bound under another model is a comparison the user asked for): the default model
// does not hold what the adversary does.
void bound_model_of_envelope(json& merged, const std::vector<const json*>& layers) {
  const json& envelope = merged["pipeline"]["envelope"];
  if (!envelope.is_string() || envelope == "none") return;
  for (const json* layer : layers)
    if (layer->contains("bound_model")) return;
  merged["bound_model"] = envelope;
}

}  // namespace

Scene load_scene_text(const std::string& text, const std::string& path,
                      const std::vector<std::string>& overrides, bool check,
                      const std::map<std::string, std::string>& origins) {
  json merged = parse_scene_json(default_scene_text(), std::string("embedded:") + kDefaultPath);
  std::string source = std::string("embedded:") + kDefaultPath;
  json user = json::object(), patch = json::object();
  if (!path.empty()) {
    source = path;
    user = parse_scene_json(text, path);
    check_user_keys(user, path, text);
    // A scene file that does not name itself is called after its file, never after the default
    // scene it starts from: outputs and plots must not label a user's scene "gilg2021".
    if (!user.contains("name")) merged["name"] = std::filesystem::path(path).stem().string();
    // Nor does it inherit the default's description ("the paper's MTS configuration. The
    // embedded default scene"), which a report would print as the user's scene's.
    if (!user.contains("description")) merged["description"] = "";
    // A scene that lists its own pairs replaces the default list, not merges into it.
    merged.merge_patch(user);
    if (user.contains("evaluate")) merged["evaluate"] = user["evaluate"];
  }
  std::map<std::string, std::string> blame = origins;
  if (!overrides.empty()) {
    for (const auto& o : overrides) {
      apply_override(patch, o);
      blame.emplace(o.substr(0, o.find('=')), "--set " + o);
    }
    check_user_keys(patch, "--set", "");
    // A scene changed on the command line is no longer the one its name stands for.
    if (!patch.contains("name") && merged["name"].is_string())
      patch["name"] = changed_scene_name(merged["name"].get<std::string>());
    merged.merge_patch(patch);
    if (patch.contains("evaluate")) merged["evaluate"] = patch["evaluate"];
    if (!overrides.empty()) source += " (with --set overrides)";
  }
  apply_profile(merged, {&user, &patch}, blame, path.empty() ? source : path);
  bound_model_of_envelope(merged, {&user, &patch});

  Scene s = parse_scene(merged, source, path.empty() ? source : path, text, blame);
  if (check) check_pairs(s);
  return s;
}

std::string changed_scene_name(const std::string& name) {
  const std::string mark = "+set";
  const bool marked =
      name.size() >= mark.size() && name.compare(name.size() - mark.size(), mark.size(), mark) == 0;
  return marked ? name : name + mark;
}

Scene scene_from_json(const json& j, const std::string& source) {
  json merged = parse_scene_json(default_scene_text(), std::string("embedded:") + kDefaultPath);
  check_user_keys(j, source, "");
  merged.merge_patch(j);
  if (j.contains("evaluate")) merged["evaluate"] = j["evaluate"];
  apply_profile(merged, {&j}, {}, source);
  bound_model_of_envelope(merged, {&j});
  Scene s = parse_scene(merged, source, source, "", {});
  check_pairs(s);
  return s;
}

const char* to_string(Sampling s) {
  return s == Sampling::paper ? "paper" : "worst_case";
}

}  // namespace depthprec
