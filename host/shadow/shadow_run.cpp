#include "host/shadow/shadow_run.h"

namespace depthprec {

namespace {

nlohmann::json optional_number(const std::optional<double>& v) {
  return v ? nlohmann::json(*v) : nlohmann::json(nullptr);
}

}  // namespace

nlohmann::json shadow_header(const ShadowRequest& r) {
  const ShadowSetup& s = r.setup;
  nlohmann::json h;
  h["light"] = to_string(s.light);
  if (s.light == LightType::spot) h["spot_angle_deg"] = s.spot_angle;
  h["resolution"] = s.resolution;
  h["format"] = s.format.name();
  h["reversed"] = s.reversed;
  h["filter"] = s.filter.name;
  h["reach_texels"] = s.filter.reach;
  h["api"] = to_string(s.raster.api);
  h["slope_max_deg"] = s.slope_max;
  h["world_position"] = s.world_position;
  h["light_elevation_deg"] = s.light_elevation;
  h["light_azimuth_deg"] = s.light_azimuth;
  h["bound_model"] = r.bound_model;
  if (s.light == LightType::directional) h["r"] = shadow_r(s, 0);
  if (r.emulate) {
    h["sampling"] = {
        {"planes", r.sampling.planes}, {"grid", r.sampling.grid}, {"seed", r.sampling.seed}};
  }
  nlohmann::json engines = nlohmann::json::array();
  for (const EngineInfo& e : engine_table()) {
    if (s.light != LightType::directional) break;
    if (!r.engines.empty() &&
        std::find(r.engines.begin(), r.engines.end(), std::string(e.name)) == r.engines.end())
      continue;
    engines.push_back({{"engine", e.name},
                       {"source", e.source},
                       {"depth_unit", e.depth_unit},
                       {"normal_unit", e.normal_unit},
                       {"default_depth", e.default_depth},
                       {"default_normal", e.default_normal},
                       {"public_formula", e.public_formula}});
  }
  h["engines"] = engines;
  return h;
}

nlohmann::json shadow_record(OpenClRuntime* rt, const ShadowRequest& r, size_t cascade) {
  const ShadowSetup& s = r.setup;
  const ShadowCascade& c = s.cascades[cascade];
  const ShadowBound b = shadow_bound(s, cascade, bound_model(r.bound_model));
  nlohmann::json rec;
  rec["cascade"] = cascade + 1;
  if (c.split_far > 0) rec["split"] = {c.split_near, c.split_far};
  if (s.light == LightType::spot) rec["distance"] = c.distance;
  rec["extent"] = c.extent;
  rec["near"] = c.near;
  rec["far"] = c.far;
  rec["texel"] = b.texel;
  rec["r"] = shadow_r(s, cascade);
  rec["depth_range"] = b.range;
  const ShadowTerms& t = b.terms;
  rec["terms"] = {{"reach", t.reach},
                  {"caster_xy", t.caster_xy},
                  {"receiver_xy", t.receiver_xy},
                  {"caster_vertex", t.caster_vertex},
                  {"interpolation", t.interpolation},
                  {"storage", t.storage},
                  {"receiver", t.receiver}};
  rec["bound"] = {{"constant", b.constant},
                  {"constant_units", b.constant_units},
                  {"constant_metres", b.constant_metres},
                  {"slope_factor", b.slope_factor},
                  {"error_constant", b.error_constant},
                  {"error_units", b.error_units},
                  {"error_metres", b.error_metres},
                  {"normal_metres", b.normal_metres},
                  {"normal_texels", b.normal_texels},
                  {"gap_constant", b.gap_constant},
                  {"gap_slope", b.gap_slope},
                  {"gap_normal", b.gap_normal}};
  if (r.emulate) {
    ShadowEmulator e(*rt, s, cascade, r.sampling);
    const ShadowWitness w = shadow_witness(e, b, s.reversed);
    rec["witnessed"] = {{"constant_units", w.constant_units},
                        {"slope_factor", w.slope_factor},
                        {"normal_metres", w.normal_metres},
                        {"bound_clean", w.bound_clean},
                        {"acne_at_90_percent", w.acne_below},
                        {"points", e.points()},
                        {"launches", e.launches()}};
  }
  nlohmann::json engines = nlohmann::json::array();
  // The engines' conversions read their directional lights' formulas.
  const std::vector<EngineBias> converted = s.light == LightType::directional
                                                ? engine_biases(s, cascade, b, r.engines)
                                                : std::vector<EngineBias>{};
  for (const EngineBias& eb : converted)
    engines.push_back({{"engine", eb.engine},
                       {"depth_alone", optional_number(eb.depth_alone)},
                       {"normal_min", optional_number(eb.normal_min)},
                       {"depth_for_normal_min", optional_number(eb.depth_for_normal_min)},
                       {"depth_with_default_normal", optional_number(eb.depth_with_normal_default)},
                       {"default_suffices", eb.depth_alone ? nlohmann::json(eb.default_suffices)
                                                           : nlohmann::json(nullptr)}});
  rec["engines"] = engines;
  return rec;
}

}  // namespace depthprec
