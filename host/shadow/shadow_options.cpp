#include "host/shadow/shadow_options.h"

#include <fmt/format.h>

#include <functional>
#include <map>

#include "host/base/errors.h"

namespace depthprec {

const std::vector<double>& default_shadow_splits() {
  static const std::vector<double> splits{10, 40, 150, 600};
  return splits;
}

ShadowRequest shadow_request(const ShadowOptions& o, bool emulate) {
  ShadowRequest r;
  ShadowSetup& s = r.setup;
  if (o.light != "directional" && o.light != "spot")
    throw InputError(fmt::format("unknown light '{}': expected directional or spot", o.light));
  s.light = o.light == "spot" ? LightType::spot : LightType::directional;
  const bool boxes = !o.extent.empty() || !o.light_near.empty() || !o.light_far.empty();
  if (s.light == LightType::spot) {
    if (!o.splits.empty() || !o.extent.empty())
      throw InputError(
          "shadow: a spot light has one map, measured at receiver distances (--distances): "
          "--splits and --extent are a directional light's");
    if (o.light_near.size() > 1 || o.light_far.size() > 1)
      throw InputError(
          "shadow: a spot light has one near and one far plane (--light-near N "
          "--light-far F, metres from the light)");
    s.spot_angle = o.spot_angle;
    s.cascades = spot_rows(o.distances.empty() ? std::vector<double>{5, 20, 50} : o.distances,
                           o.light_near.empty() ? 0.1 : o.light_near[0],
                           o.light_far.empty() ? 100 : o.light_far[0], o.spot_angle);
  } else {
    if (!o.distances.empty())
      throw InputError(
          "shadow: --distances are a spot light's (--light spot); a directional "
          "light's cascades come from --splits or --extent");
    if (o.spot_angle_given)
      throw InputError(
          "shadow: --spot-angle is a spot light's cone (--light spot); a directional light's "
          "maps cover its cascades (--splits or --extent)");
    if (boxes && !o.splits.empty())
      throw InputError(
          "shadow: give the cascades as camera splits (--splits) or as light boxes (--extent "
          "with --light-near and --light-far), not both");
    if (boxes) {
      if (o.light_near.size() != o.extent.size() || o.light_far.size() != o.extent.size())
        throw InputError(fmt::format(
            "shadow: --extent names {} cascades, --light-near {} and --light-far {}: one value "
            "each per cascade",
            o.extent.size(), o.light_near.size(), o.light_far.size()));
      for (size_t i = 0; i < o.extent.size(); ++i) {
        ShadowCascade c;
        c.extent = o.extent[i];
        c.near = o.light_near[i];
        c.far = o.light_far[i];
        s.cascades.push_back(c);
      }
    } else {
      s.cascades = cascades_from_splits(o.splits.empty() ? default_shadow_splits() : o.splits,
                                        o.camera_near, o.fov, o.aspect, o.caster_padding);
    }
  }
  s.resolution = o.resolution;
  s.format = StorageFormat::parse(o.format);
  s.reversed = o.reversed;
  s.filter = parse_shadow_filter(o.filter);
  s.raster.api = parse_bias_api(o.api);
  if (!o.r_unorm.empty()) s.raster.unorm_r = parse_unorm_r(o.r_unorm);
  s.raster.slope = parse_slope_form(o.slope);
  validate(s.raster);
  s.slope_max = o.slope_max;
  if (o.world_position.size() != 3)
    throw InputError("shadow: the world position takes three numbers: X,Y,Z");
  s.world_position = {o.world_position[0], o.world_position[1], o.world_position[2]};
  s.light_elevation = o.light_elevation;
  s.light_azimuth = o.light_azimuth;
  validate(s);
  for (const std::string& e : o.engines) engine_info(e);  // unknown names fail here
  r.engines = o.engines;
  bound_model(o.bound_model);
  r.bound_model = o.bound_model;
  if (o.planes < 16 || o.grid < 1 || o.grid > 64)
    throw InputError(
        fmt::format("shadow: planes {} (16 or more), grid {} (1 to 64)", o.planes, o.grid));
  r.sampling = {o.planes, o.grid, o.seed};
  r.emulate = emulate;
  return r;
}

ShadowOptions shadow_options_from_json(const nlohmann::json& block, const std::string& where) {
  if (!block.is_object())
    throw InputError(fmt::format("{}: shadow must be an object of shadow's options", where));
  ShadowOptions o;
  using Read = std::function<void(const nlohmann::json&)>;
  auto number = [](double& field) {
    return Read([&field](const nlohmann::json& v) { field = v.get<double>(); });
  };
  auto text = [](std::string& field) {
    return Read([&field](const nlohmann::json& v) { field = v.get<std::string>(); });
  };
  auto numbers = [](std::vector<double>& field) {
    return Read([&field](const nlohmann::json& v) { field = v.get<std::vector<double>>(); });
  };
  const std::map<std::string, Read> fields = {
      {"light", text(o.light)},
      {"spot_angle", number(o.spot_angle)},
      {"distances", numbers(o.distances)},
      {"splits", numbers(o.splits)},
      {"extent", numbers(o.extent)},
      {"light_near", numbers(o.light_near)},
      {"light_far", numbers(o.light_far)},
      {"camera_near", number(o.camera_near)},
      {"fov", number(o.fov)},
      {"aspect", number(o.aspect)},
      {"caster_padding", number(o.caster_padding)},
      {"resolution", [&o](const nlohmann::json& v) { o.resolution = v.get<int>(); }},
      {"format", text(o.format)},
      {"filter", text(o.filter)},
      {"api", text(o.api)},
      {"r_unorm", text(o.r_unorm)},
      {"slope", text(o.slope)},
      {"reversed", [&o](const nlohmann::json& v) { o.reversed = v.get<bool>(); }},
      {"slope_max", number(o.slope_max)},
      {"light_elevation", number(o.light_elevation)},
      {"light_azimuth", number(o.light_azimuth)},
      {"world_position", numbers(o.world_position)},
      {"engines", [&o](const nlohmann::json& v) { o.engines = v.get<std::vector<std::string>>(); }},
      {"bound_model", text(o.bound_model)},
      {"planes", [&o](const nlohmann::json& v) { o.planes = v.get<uint32_t>(); }},
      {"grid", [&o](const nlohmann::json& v) { o.grid = v.get<uint32_t>(); }},
      {"seed", [&o](const nlohmann::json& v) { o.seed = v.get<uint64_t>(); }},
  };
  for (const auto& item : block.items()) {
    const auto f = fields.find(item.key());
    if (f == fields.end()) {
      std::string known;
      for (const auto& [k, unused] : fields) known += (known.empty() ? "" : ", ") + k;
      throw InputError(
          fmt::format("{}: unknown key '{}' in shadow; known keys: {}", where, item.key(), known));
    }
    try {
      f->second(item.value());
    } catch (const nlohmann::json::exception&) {
      throw InputError(fmt::format("{}: shadow.{}: {} is not a value of the kind it takes", where,
                                   item.key(), item.value().dump()));
    }
  }
  return o;
}

}  // namespace depthprec
