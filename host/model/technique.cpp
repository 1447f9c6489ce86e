#include "host/model/technique.h"

#include <fmt/format.h>

#include <cmath>

#include "host/base/did_you_mean.h"
#include "host/base/errors.h"

namespace depthprec {

const char* to_string(DepthRange r) {
  return r == DepthRange::gl ? "gl" : "zero_to_one";
}

const char* to_string(DepthFrom f) {
  switch (f) {
    case DepthFrom::projection:
      return "projection";
    case DepthFrom::vertex_log:
      return "vertex_log";
    case DepthFrom::fragment:
      return "fragment";
  }
  return "?";
}

const char* to_string(FragmentDepth f) {
  switch (f) {
    case FragmentDepth::none:
      return "";
    case FragmentDepth::linear:
      return "linear";
    case FragmentDepth::w_buffer:
      return "w_buffer";
    case FragmentDepth::log:
      return "log";
    case FragmentDepth::threejs_log:
      return "threejs_log";
    case FragmentDepth::cesium_log:
      return "cesium_log";
  }
  return "?";
}

DepthRange parse_depth_range(const std::string& s) {
  if (s == "gl") return DepthRange::gl;
  if (s == "zero_to_one") return DepthRange::zero_to_one;
  throw InputError(fmt::format("unknown depth range '{}': expected gl or zero_to_one", s));
}

const std::vector<TechniqueInfo>& technique_table() {
  using D = DepthFrom;
  using F = FragmentDepth;
  using M = DepthMap;
  const DepthRange gl = DepthRange::gl, zo = DepthRange::zero_to_one;
  const char* projection_only = "projection matrix only";
  const char* fragment_write =
      "writes depth in the fragment stage: no early depth test, weaker depth compression";
  const char* vertex_log = "a log per vertex; depth not interpolated perspective-correctly";
  // id, name, depth from, fragment depth, GEQUAL, range, clips at near, exact map, LJ buffer, GPU
  // cost
  static const std::vector<TechniqueInfo> table = {
      {Technique::standard, "standard", D::projection, F::none, false, gl, true, M::standard, "z",
       projection_only},
      {Technique::infinite, "infinite", D::projection, F::none, false, gl, true, M::infinite,
       nullptr, projection_only},
      {Technique::reversed, "reversed", D::projection, F::none, true, zo, true, M::reversed,
       "complementary_z", projection_only},
      {Technique::reversed_infinite, "reversed_infinite", D::projection, F::none, true, zo, true,
       M::n_over_w, nullptr, projection_only},
      {Technique::log_vertex, "log_vertex", D::vertex_log, F::none, false, gl, false, M::log,
       nullptr, vertex_log},
      {Technique::log_fragment, "log_fragment", D::fragment, F::log, false, gl, true, M::log,
       nullptr, fragment_write},
      {Technique::log_threejs, "log_threejs", D::fragment, F::threejs_log, false, gl, true,
       M::log2_one_plus_w, nullptr, fragment_write},
      {Technique::log_threejs_vertex, "log_threejs_vertex", D::vertex_log, F::none, false, gl,
       false, M::log2_one_plus_w, nullptr, vertex_log},
      {Technique::log_cesium, "log_cesium", D::fragment, F::cesium_log, false, gl, true,
       M::log2_from_near, nullptr, fragment_write},
      {Technique::linear, "linear", D::fragment, F::linear, false, gl, true, M::linear, nullptr,
       fragment_write},
      {Technique::w_buffer, "w_buffer", D::fragment, F::w_buffer, false, gl, true, M::w_over_f, "w",
       fragment_write},
      {Technique::inverse_w, "inverse_w", D::projection, F::none, true, zo, true, M::n_over_w,
       "inverse_w", projection_only},
      {Technique::layered, "layered", D::projection, F::none, false, gl, true, M::standard, nullptr,
       "one pass per layer, depth cleared per layer"},
      // An orthographic camera (CAD viewers, shadow maps of directional lights): depth linear in
      // the eye z; for the MTS its view at the planes' distance is the perspective one's.
      {Technique::orthographic, "orthographic", D::projection, F::none, false, gl, true, M::linear,
       nullptr, projection_only},
  };
  return table;
}

const TechniqueInfo& info(Technique t) {
  for (const auto& i : technique_table())
    if (i.id == t) return i;
  throw Error(ExitCode::internal, "technique missing from the table");
}

bool takes_shader_log(const TechniqueInfo& ti) {
  return ti.map == DepthMap::log || ti.map == DepthMap::log2_one_plus_w ||
         ti.map == DepthMap::log2_from_near;
}

VertexLog vertex_log(const TechniqueInfo& ti) {
  return ti.map == DepthMap::log2_one_plus_w ? VertexLog::threejs : VertexLog::gilg;
}

bool has_far_plane(Technique t) {
  return t != Technique::infinite && t != Technique::reversed_infinite && t != Technique::inverse_w;
}

std::string finite_far_technique_names() {
  std::string s;
  for (const auto& i : technique_table())
    if (has_far_plane(i.id)) s += (s.empty() ? "" : ", ") + std::string(i.name);
  return s;
}

std::string technique_names() {
  std::string s;
  for (const auto& i : technique_table()) s += (s.empty() ? "" : ", ") + std::string(i.name);
  return s;
}

Technique parse_technique(const std::string& s) {
  for (const auto& i : technique_table())
    if (s == i.name) return i.id;
  std::vector<std::string> names;
  for (const auto& i : technique_table()) names.push_back(i.name);
  throw InputError(fmt::format("unknown technique '{}'{}: expected one of {}", s,
                               technique_suggestion(s, names), technique_names()));
}

double depth_of_distance(Technique t, double n, double f, const TechniqueParams& p, double w) {
  // The gl and zero_to_one window depths are the same function of w (only their binary32
  // evaluation differs), so one closed form per mapping, each without cancellation.
  if (t == Technique::layered) {
    const Layer l = layer_bounds(layer_of(w, n, f, p), n, f, p);
    return depth_of_distance(p.layer_mapping, l.near, l.far, p, w);
  }
  switch (info(t).map) {
    case DepthMap::standard:
      return f * (w - n) / ((f - n) * w);
    case DepthMap::infinite:
      return (w - n) / w;
    case DepthMap::reversed:
      return n * (f - w) / ((f - n) * w);
    case DepthMap::n_over_w:
      return n / w;
    case DepthMap::log:
      return std::log1p(p.log_k * w) / std::log1p(p.log_k * f);
    case DepthMap::log2_one_plus_w:
      return std::log1p(w) / std::log1p(f);
    case DepthMap::log2_from_near:
      return std::log1p(w - n) / std::log1p(f - n);
    case DepthMap::linear:
      return (w - n) / (f - n);
    case DepthMap::w_over_f:
      return w / f;
  }
  return NAN;
}

void throw_layered_has_no_single_mapping() {
  throw InputError(
      "layered has one mapping per layer: ask for its layer_mapping with the layer's near and far");
}

Layer layer_bounds(int i, double n, double f, const TechniqueParams& p) {
  const double ratio = f / n;
  const double lo = n * std::pow(ratio, static_cast<double>(i) / p.layers);
  const double hi =
      i + 1 == p.layers ? f : n * std::pow(ratio, static_cast<double>(i + 1) / p.layers);
  return {i == 0 ? n : lo, i + 1 == p.layers ? f : hi * (1.0 + p.layer_overlap)};
}

int layer_of(double z, double n, double f, const TechniqueParams& p) {
  for (int i = p.layers - 1; i > 0; --i) {
    const double lo = n * std::pow(f / n, static_cast<double>(i) / p.layers);
    if (z >= lo) return i;
  }
  return 0;
}

}  // namespace depthprec
