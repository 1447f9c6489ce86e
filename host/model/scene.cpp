#include "host/model/scene.h"

#include <fmt/format.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <sstream>

#include "host/base/embedded_sources.h"
#include "host/base/errors.h"
#include "host/base/named_choice.h"
#include "host/base/read_file.h"
#include "host/model/profile.h"
#include "host/model/scene_json.h"
#include "host/model/scene_reader.h"
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

int Pipeline::clip_slots() const {
  return clip == ClipForm::llvmpipe ? MTS_CLIP_SLOTS : 1;
}

using nlohmann::json;

namespace {

constexpr const char* kDefaultPath = "data/gilg2021.json";
constexpr int kMaxKernelSide = 16384;

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
                                        "worst_case",
                                        "pipeline",
                                        "log_k",
                                        "layers",
                                        "layer_mapping",
                                        "layer_overlap",
                                        "evaluate"};
const std::set<std::string> kPipelineKeys = {
    "depth_range", "matrix_precision", "compose", "divide",   "rounding",
    "denormals",   "contraction",      "plane",   "viewport", "conversion",
    "vertex",      "profile",          "log",     "clip",     "snap",
    "transform"};
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
  if (j.contains("pipeline"))
    check_known_keys(j["pipeline"], kPipelineKeys, "pipeline", source, text);
  if (j.contains("worst_case"))
    check_known_keys(j["worst_case"], kWorstCaseKeys, "worst_case", source, text);
  if (j.contains("evaluate") && j["evaluate"].is_array())
    for (const auto& p : j["evaluate"])
      check_known_keys(p, kPairKeys, "an evaluate entry", source, text);
}

MatrixPrecision parse_matrix_precision(const std::string& s) {
  return named_choice<MatrixPrecision>(
      "matrix precision", s,
      {{"float", MatrixPrecision::single}, {"double", MatrixPrecision::binary64}});
}
Compose parse_compose(const std::string& s) {
  return named_choice<Compose>(
      "compose", s, {{"separate", Compose::separate}, {"premultiplied", Compose::premultiplied}});
}
Divide parse_divide(const std::string& s) {
  return named_choice<Divide>("divide", s,
                              {{"reciprocal", Divide::reciprocal}, {"exact", Divide::exact}});
}
PlaneForm parse_plane_form(const std::string& s) {
  return named_choice<PlaneForm>("plane", s,
                                 {{"vertex", PlaneForm::vertex},
                                  {"origin_fma", PlaneForm::origin_fma},
                                  {"origin_quads", PlaneForm::origin_quads}});
}
ViewportForm parse_viewport_form(const std::string& s) {
  return named_choice<ViewportForm>(
      "viewport", s, {{"separate", ViewportForm::separate}, {"fma", ViewportForm::fma}});
}
ClipForm parse_clip_form(const std::string& s) {
  return named_choice<ClipForm>("clip", s,
                                {{"none", ClipForm::none}, {"llvmpipe", ClipForm::llvmpipe}});
}
LogForm parse_log_form(const std::string& s) {
  return named_choice<LogForm>("log", s,
                               {{"library", LogForm::library}, {"llvmpipe", LogForm::llvmpipe}});
}
Sampling parse_sampling(const std::string& s) {
  return named_choice<Sampling>("sampling", s,
                                {{"worst_case", Sampling::worst_case}, {"paper", Sampling::paper}});
}
VertexForm parse_vertex_form(const std::string& s) {
  return named_choice<VertexForm>("vertex", s,
                                  {{"separate", VertexForm::separate}, {"fma", VertexForm::fma}});
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

namespace {
Scene parse_scene(const json& merged, const std::string& source, const std::string& where_name,
                  const std::string& text, const std::map<std::string, std::string>& origins);
}  // namespace

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
                                     value, named("pipeline." + key, where),
                                     (*layer)["pipeline"][key].dump()));
    merged["pipeline"][key] = value;
  }
}

// The profile whose every setting the pipeline has, else "custom".
std::string matching_profile(const json& pipeline) {
  for (const Profile& p : profiles()) {
    bool all = true;
    for (const std::string& set : p.sets) {
      const auto [key, value] = pipeline_setting(set);
      all = all && pipeline.contains(key) && pipeline[key] == value;
    }
    if (all) return p.name;
  }
  return "custom";
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
      patch["name"] = merged["name"].get<std::string>() + "+set";
    merged.merge_patch(patch);
    if (patch.contains("evaluate")) merged["evaluate"] = patch["evaluate"];
    if (!overrides.empty()) source += " (with --set overrides)";
  }
  apply_profile(merged, {&user, &patch}, blame, path.empty() ? source : path);

  Scene s = parse_scene(merged, source, path.empty() ? source : path, text, blame);
  if (check) check_pairs(s);
  return s;
}

Scene scene_from_json(const json& j, const std::string& source) {
  json merged = parse_scene_json(default_scene_text(), std::string("embedded:") + kDefaultPath);
  check_user_keys(j, source, "");
  merged.merge_patch(j);
  if (j.contains("evaluate")) merged["evaluate"] = j["evaluate"];
  apply_profile(merged, {&j}, {}, source);
  Scene s = parse_scene(merged, source, source, "", {});
  check_pairs(s);
  return s;
}

const char* to_string(Sampling s) {
  return s == Sampling::paper ? "paper" : "worst_case";
}

namespace {

Scene parse_scene(const json& merged, const std::string& source, const std::string& where_name,
                  const std::string& text, const std::map<std::string, std::string>& origins) {
  const Reader r(merged, where_name, text, origins);
  Scene s;
  s.source = source;
  s.name = r.string("name");
  s.description = r.string("description");
  s.near = r.positive("near");
  s.far = r.positive("far", true);
  if (!(s.far > s.near)) r.fail("far", fmt::format("must be > near ({}), not {}", s.near, s.far));
  const auto k = r.size2("kernel", kMaxKernelSide);
  const auto vp = r.size2("viewport", kMaxKernelSide);
  s.kernel_w = k[0];
  s.kernel_h = k[1];
  s.viewport_w = vp[0];
  s.viewport_h = vp[1];
  if (s.kernel_w > s.viewport_w || s.kernel_h > s.viewport_h)
    r.fail("kernel", fmt::format("must fit in the viewport {}x{}", s.viewport_w, s.viewport_h));
  s.fov_y_deg = r.positive("fov_y_deg");
  if (s.fov_y_deg >= 180) r.fail("fov_y_deg", "must be below 180 degrees");
  s.plane_margin = r.positive("plane_margin");
  s.plane_subdivisions = r.integer("plane_subdivisions", 1, 11);
  s.frames = r.integer("frames", 1, 1000000);
  s.delta_a = r.number("delta_a");
  s.rotation_range_deg = r.number("rotation_range_deg");
  if (std::abs(s.rotation_range_deg) >= 45)
    r.fail("rotation_range_deg", "must be below 45 degrees");
  s.rotation_step = r.vec3("rotation_step");
  s.rotation_offset = r.vec3("rotation_offset");
  const json& dist = r.at("distances");
  if (!dist.is_array() || dist.empty())
    r.fail("distances", "must be a non-empty list of eye distances > 0");
  for (const auto& d : dist) {
    if (!d.is_number() || !(d.get<double>() > 0) || !std::isfinite(d.get<double>()))
      r.fail("distances", fmt::format("must hold finite eye distances > 0, not {}", d.dump()));
    const double z = d.get<double>();
    // The planes are placed in binary32: at its largest value fl32(z) has no binary32 above it
    // (the vertex bound is infinite), past it fl32(z) is infinite.
    if (!(static_cast<float>(z) < std::numeric_limits<float>::max()))
      r.fail(
          "distances",
          fmt::format("{:g} is not below binary32's largest value {:g}: the pipeline cannot place "
                      "a plane there",
                      z, static_cast<double>(std::numeric_limits<float>::max())));
    // A row is keyed by its distance (journals, shards, shared computations): each distance once.
    const auto same = std::find(s.distances.begin(), s.distances.end(), z);
    if (same != s.distances.end())
      r.fail("distances",
             fmt::format("lists {:g} twice (entries {} and {}); list each distance once", z,
                         same - s.distances.begin() + 1, s.distances.size() + 1));
    s.distances.push_back(z);
  }
  s.world_position = r.vec3("world_position");
  for (const double c : s.world_position)
    if (!(std::abs(c) <= kMaxWorldCoordinate))
      r.fail("world_position", fmt::format("coordinates must be within +-{:g} (2^40), not {:g}",
                                           kMaxWorldCoordinate, c));
  s.rel_precision = r.positive("rel_precision");
  if (s.rel_precision >= 1) r.fail("rel_precision", "must be below 1 (e.g. 0.0009765625 = 2^-10)");
  s.max_separation_factor = r.positive("max_separation_factor");
  if (s.max_separation_factor < 1) r.fail("max_separation_factor", "must be >= 1");
  s.stiffness_probes = r.integer("stiffness_probes", 0, 8);
  s.sampling = r.choice("sampling", parse_sampling);
  s.worst_case.max_rounds = r.integer("worst_case.max_rounds", 1, 16);
  s.worst_case.min_rounds = r.integer("worst_case.min_rounds", 1, s.worst_case.max_rounds);
  s.worst_case.round_size = r.integer("worst_case.round_size", 1, 1000000);
  // Rounds double: the last one renders round_size * 2^(max_rounds - 1) frames per probe.
  if ((static_cast<long long>(s.worst_case.round_size) << (s.worst_case.max_rounds - 1)) > 1000000)
    r.fail("worst_case.max_rounds",
           fmt::format("with round_size {} the last round would sample {} orientations; at most "
                       "1000000 (rounds double)",
                       s.worst_case.round_size,
                       static_cast<long long>(s.worst_case.round_size)
                           << (s.worst_case.max_rounds - 1)));
  s.worst_case.tolerance = r.number("worst_case.tolerance");
  if (!(s.worst_case.tolerance >= 0 && s.worst_case.tolerance < 1))
    r.fail("worst_case.tolerance", "must be 0..1 (a relative rise of the MTS, e.g. 0.01)");

  s.pipeline.depth_range =
      r.choice("pipeline.depth_range", [](const std::string& v) -> std::optional<DepthRange> {
        if (v == "technique") return std::nullopt;
        try {
          return parse_depth_range(v);
        } catch (const InputError&) {
          throw InputError(
              fmt::format("unknown depth range '{}': expected gl, zero_to_one or technique "
                          "(each technique's own: zero_to_one for reversed, reversed_infinite and "
                          "inverse_w, gl otherwise)",
                          v));
        }
      });
  s.pipeline.matrix_precision = r.choice("pipeline.matrix_precision", parse_matrix_precision);
  s.pipeline.compose = r.choice("pipeline.compose", parse_compose);
  s.pipeline.divide = r.choice("pipeline.divide", parse_divide);
  s.pipeline.rounding = r.choice("pipeline.rounding", parse_rounding);
  s.pipeline.denormals = r.choice("pipeline.denormals", parse_denormals);
  s.pipeline.contraction = r.boolean("pipeline.contraction");
  s.pipeline.plane = r.choice("pipeline.plane", parse_plane_form);
  s.pipeline.viewport = r.choice("pipeline.viewport", parse_viewport_form);
  s.pipeline.vertex = r.choice("pipeline.vertex", parse_vertex_form);
  s.pipeline.log = r.choice("pipeline.log", parse_log_form);
  s.pipeline.clip = r.choice("pipeline.clip", parse_clip_form);
  s.pipeline.snap_bits = r.none_or_integer("pipeline.snap", 1, 16);
  s.pipeline.conversion = r.choice("pipeline.conversion", parse_conversion);
  s.pipeline.transform = r.choice("pipeline.transform", parse_transform);

  s.params.log_k = r.positive("log_k");
  s.params.layers = r.integer("layers", 1, 64);
  s.params.layer_mapping = r.choice("layer_mapping", parse_technique);
  if (s.params.layer_mapping != Technique::standard &&
      s.params.layer_mapping != Technique::reversed && s.params.layer_mapping != Technique::linear)
    r.fail("layer_mapping", "must be standard, reversed or linear");
  s.params.layer_overlap = r.number("layer_overlap");
  if (s.params.layer_overlap < 0 || s.params.layer_overlap > 1)
    r.fail("layer_overlap", "must be 0..1 (a fraction of the layer's far bound)");

  const json& ev = r.at("evaluate");
  if (!ev.is_array() || ev.empty())
    r.fail("evaluate",
           "must be a non-empty list of {\"technique\", \"format\"[, \"depth_range\"]}");
  for (size_t i = 0; i < ev.size(); ++i) {
    const std::string base = fmt::format("evaluate.{}", i);
    if (!ev[i].is_object() || !ev[i].contains("technique") || !ev[i].contains("format"))
      r.fail("evaluate", fmt::format("entry {} must be an object with technique and format", i));
    EvalPair p;
    try {
      p.technique = parse_technique(ev[i]["technique"].get<std::string>());
      p.format = ev[i]["format"].get<std::string>();
      StorageFormat::parse(p.format);
      p.depth_range = ev[i].contains("depth_range")
                          ? parse_depth_range(ev[i]["depth_range"].get<std::string>())
                          : s.range_for(p.technique);
    } catch (const InputError& e) {
      r.fail(base, e.what());
    } catch (const json::exception&) {
      r.fail(base, "must hold strings for technique, format and depth_range");
    }
    s.evaluate.push_back(p);
  }
  s.json = merged;
  s.json["pipeline"]["profile"] = matching_profile(merged["pipeline"]);
  return s;
}

}  // namespace

}  // namespace depthprec
