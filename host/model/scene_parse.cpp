#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "host/base/errors.h"
#include "host/base/named_choice.h"
#include "host/model/bound_model.h"
#include "host/model/profile.h"
#include "host/model/scene.h"
#include "host/model/scene_reader.h"

namespace depthprec {

using nlohmann::json;

namespace {

constexpr int kMaxKernelSide = 16384;

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

// pipeline.depth_range: a range, or "technique" (nullopt) for each technique's own.
std::optional<DepthRange> parse_scene_depth_range(const std::string& v) {
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

void read_view_fields(const Reader& r, Scene& s) {
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
}

void read_plane_motion_fields(const Reader& r, Scene& s) {
  s.plane_margin = r.positive("plane_margin");
  s.plane_subdivisions = r.integer("plane_subdivisions", 1, 11);
  s.frames = r.integer("frames", 1, 1000000);
  s.delta_a = r.number("delta_a");
  s.rotation_range_deg = r.number("rotation_range_deg");
  if (!(s.rotation_range_deg >= 0 && s.rotation_range_deg < 45))
    r.fail("rotation_range_deg",
           fmt::format("must be 0 up to below 45 degrees (each axis turns within ± it), not {}",
                       s.rotation_range_deg));
  s.rotation_step = r.vec3("rotation_step");
  s.rotation_offset = r.vec3("rotation_offset");
}

void read_distances(const Reader& r, Scene& s) {
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
}

void read_world_position(const Reader& r, Scene& s) {
  s.world_position = r.vec3("world_position");
  for (const double c : s.world_position)
    if (!(std::abs(c) <= kMaxWorldCoordinate))
      r.fail("world_position", fmt::format("coordinates must be within +-{:g} (2^40), not {:g}",
                                           kMaxWorldCoordinate, c));
}

void read_search_fields(const Reader& r, Scene& s) {
  s.rel_precision = r.positive("rel_precision");
  if (s.rel_precision >= 1) r.fail("rel_precision", "must be below 1 (e.g. 0.0009765625 = 2^-10)");
  s.max_separation_factor = r.positive("max_separation_factor");
  if (s.max_separation_factor < 1) r.fail("max_separation_factor", "must be >= 1");
  s.stiffness_probes = r.integer("stiffness_probes", 0, 8);
  s.sampling = r.choice("sampling", parse_sampling);
  s.bound_model = r.choice("bound_model", [](const std::string& v) { return bound_model(v).name; });
  const nlohmann::json& tol = r.at("interpolation_tolerance");
  if (tol != "model") {
    if (!tol.is_number() || !(tol.get<double>() >= 0 && tol.get<double>() <= 0.01))
      r.fail("interpolation_tolerance",
             fmt::format("must be model (the bound model's own) or a relative error 0..0.01 "
                         "(Vulkan's \"1 part in 10^5\" is 1e-5), not {}",
                         tol.dump()));
    s.interpolation_tolerance = tol.get<double>();
  }
}

void read_worst_case(const Reader& r, WorstCaseSettings& w) {
  w.max_rounds = r.integer("worst_case.max_rounds", 1, 16);
  w.min_rounds = r.integer("worst_case.min_rounds", 1, 16);
  if (w.min_rounds > w.max_rounds)
    r.fail("worst_case.max_rounds",
           fmt::format("must be at least worst_case.min_rounds ({}), not {}: set both",
                       w.min_rounds, w.max_rounds));
  w.round_size = r.integer("worst_case.round_size", 1, 1000000);
  // Rounds double: the last one renders round_size * 2^(max_rounds - 1) frames per probe.
  if ((static_cast<long long>(w.round_size) << (w.max_rounds - 1)) > 1000000)
    r.fail("worst_case.max_rounds",
           fmt::format("with round_size {} the last round would sample {} orientations; at most "
                       "1000000 (rounds double)",
                       w.round_size, static_cast<long long>(w.round_size) << (w.max_rounds - 1)));
  w.tolerance = r.number("worst_case.tolerance");
  if (!(w.tolerance >= 0 && w.tolerance < 1))
    r.fail("worst_case.tolerance", "must be 0..1 (a relative rise of the MTS, e.g. 0.01)");
}

void read_pipeline(const Reader& r, Pipeline& p) {
  p.depth_range = r.choice("pipeline.depth_range", parse_scene_depth_range);
  p.matrix_precision = r.choice("pipeline.matrix_precision", parse_matrix_precision);
  p.compose = r.choice("pipeline.compose", parse_compose);
  p.divide = r.choice("pipeline.divide", parse_divide);
  p.rounding = r.choice("pipeline.rounding", parse_rounding);
  p.denormals = r.choice("pipeline.denormals", parse_denormals);
  p.contraction = r.boolean("pipeline.contraction");
  p.plane = r.choice("pipeline.plane", parse_plane_form);
  p.viewport = r.choice("pipeline.viewport", parse_viewport_form);
  p.vertex = r.choice("pipeline.vertex", parse_vertex_form);
  p.log = r.choice("pipeline.log", parse_log_form);
  p.clip = r.choice("pipeline.clip", parse_clip_form);
  p.snap_bits = r.none_or_integer("pipeline.snap", 1, 16);
  p.conversion = r.choice("pipeline.conversion", parse_conversion);
  p.transform = r.choice("pipeline.transform", parse_transform);
  p.shader_precision = r.choice("pipeline.shader_precision", parse_shader_precision);
  p.envelope = r.choice("pipeline.envelope", [](const std::string& v) {
    const BoundModel* m = envelope_model(v);
    return std::string(m ? m->name : "");
  });
  if (p.shader_precision != ShaderPrecision::highp && p.transform == Transform::relative_to_eye)
    r.fail("pipeline.shader_precision",
           "mediump and es2_highp are not modelled with transform relative_to_eye: its binary32 "
           "high and low parts would need a split of their own at the shader's precision (use "
           "absolute or camera_relative)");
}

void read_technique_params(const Reader& r, TechniqueParams& p) {
  p.log_k = r.positive("log_k");
  p.layers = r.integer("layers", 1, 64);
  p.layer_mapping = r.choice("layer_mapping", parse_technique);
  if (p.layer_mapping != Technique::standard && p.layer_mapping != Technique::reversed &&
      p.layer_mapping != Technique::linear)
    r.fail("layer_mapping", "must be standard, reversed or linear");
  p.layer_overlap = r.number("layer_overlap");
  if (p.layer_overlap < 0 || p.layer_overlap > 1)
    r.fail("layer_overlap", "must be 0..1 (a fraction of the layer's far bound)");
}

// After the pipeline: a pair that names no depth range takes the scene's.
void read_evaluate(const Reader& r, Scene& s) {
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
}

}  // namespace

Scene parse_scene(const json& merged, const std::string& source, const std::string& where_name,
                  const std::string& text, const std::map<std::string, std::string>& origins) {
  const Reader r(merged, where_name, text, origins);
  Scene s;
  s.source = source;
  s.name = r.string("name");
  s.description = r.string("description");
  read_view_fields(r, s);
  read_plane_motion_fields(r, s);
  read_distances(r, s);
  read_world_position(r, s);
  read_search_fields(r, s);
  read_worst_case(r, s.worst_case);
  read_pipeline(r, s.pipeline);
  read_technique_params(r, s.params);
  read_evaluate(r, s);
  // The shadow block is `shadow`'s options, read where they are used (`report`: docs/shadow.md).
  if (merged.contains("shadow") && !merged["shadow"].is_object())
    r.fail("shadow", "must be an object of shadow's options (docs/shadow.md)");
  s.json = merged;
  s.json["pipeline"]["profile"] = matching_profile(merged["pipeline"]);
  return s;
}

}  // namespace depthprec
