#include "host/render/render_shadow.h"

#include <algorithm>
#include <cmath>

#include "host/model/matrix.h"
#include "host/render/shadow_pass.h"
#include "interface/shadow_layout.h"

namespace depthprec {

namespace {

// One bias setting as the rendered passes apply it: glPolygonOffset's factor and units on the
// caster, a window-depth offset and a normal offset on the receiver.
struct RenderedProbe {
  const char* recipe;
  double level;  // 1: the bound's value, 0.9: 10 % below
  float factor = 0, units = 0, receiver_offset = 0, normal = 0;
};

// Texels a normal offset may carry a lookup and still read the window drawn around the caster.
constexpr double kLargestRenderedOffset = ShadowPass::kWindow / 4;

// Whether the normal recipe is drawn: it has a value, and its lookups stay in the window.
bool normal_rendered(const nlohmann::json& bound) {
  return bound["normal_metres"].is_number() &&
         bound["normal_texels"].get<double>() <= kLargestRenderedOffset;
}

std::vector<RenderedProbe> probes_of(const nlohmann::json& bound, bool reversed) {
  const float sign = reversed ? -1.0f : 1.0f;
  const bool normal = normal_rendered(bound);
  std::vector<RenderedProbe> out;
  for (const double level : {1.0, 0.9}) {
    // The constant as a receiver offset: exact in window depth, free of the driver's r.
    RenderedProbe c{"constant", level};
    c.receiver_offset = static_cast<float>(level * bound["constant"].get<double>());
    RenderedProbe s{"slope", level};
    s.factor = sign * static_cast<float>(level * bound["slope_factor"].get<double>());
    s.units = sign * static_cast<float>(bound["error_units"].get<double>());
    RenderedProbe n{"normal", level};
    n.receiver_offset = static_cast<float>(bound["error_constant"].get<double>());
    out.insert(out.end(), {c, s});
    if (!normal) continue;
    n.normal = static_cast<float>(level * bound["normal_metres"].get<double>());
    out.push_back(n);
  }
  return out;
}

Vec3 along(const Vec3& p, const Vec3& d, double t) {
  return add(p, scaled(d, t));
}

// Where a ray from ground point p toward the light meets the wall (the plane through `foot` facing
// the light horizontally, `height` tall): the distance along the light, or infinity if it passes.
double wall_hit(const Vec3& p, const Vec3& to_light, const Vec3& foot, const Vec3& facing,
                double height) {
  const double den = dot(to_light, facing);
  const double t = dot(sub(foot, p), facing) / den;
  if (!(t >= 0)) return INFINITY;
  const double y = p[1] + t * to_light[1];
  return y >= foot[1] && y <= foot[1] + height ? t : INFINITY;
}

}  // namespace

nlohmann::json rendered_shadow_check(const ShadowRequest& r, size_t cascade,
                                     const nlohmann::json& record) {
  const ShadowSetup& s = r.setup;
  ShadowSampling sampling = r.sampling;
  sampling.planes = std::min(sampling.planes, kRenderedShadowPlanes);
  const ShadowPlanes planes = shadow_planes(s, cascade, sampling);
  const int grid = static_cast<int>(sampling.grid);
  ShadowPass pass(s, cascade, grid);
  const std::vector<RenderedProbe> probes = probes_of(record["bound"], s.reversed);
  std::vector<uint64_t> acne(probes.size(), 0);
  for (uint32_t k = 0; k < planes.count; ++k) {
    const float* f = &planes.f[k * SHADOW_F_STRIDE];
    const double* d = &planes.d[k * SHADOW_D_STRIDE];
    const std::vector<float> triangle(f, f + 9);
    const int x0 = static_cast<int>(f[SHADOW_F_BASE_U]) - ShadowPass::kWindow / 2;
    const int y0 = static_cast<int>(f[SHADOW_F_BASE_V]) - ShadowPass::kWindow / 2;
    ShadowReceivers rc;
    rc.origin = {d[0], d[1], d[2]};
    rc.du = {d[3], d[4], d[5]};
    rc.dv = {d[6], d[7], d[8]};
    rc.denom = {d[SHADOW_D_DENOM], d[SHADOW_D_DENOM + 1], d[SHADOW_D_DENOM + 2]};
    rc.base = {f[SHADOW_F_BASE_U], f[SHADOW_F_BASE_V]};
    rc.normal = {f[SHADOW_F_NORMAL], f[SHADOW_F_NORMAL + 1], f[SHADOW_F_NORMAL + 2]};
    rc.reach = s.filter.reach;
    for (size_t p = 0; p < probes.size(); ++p) {
      pass.draw_casters(triangle, x0, y0, probes[p].factor, probes[p].units);
      rc.receiver_offset = probes[p].receiver_offset;
      rc.normal_offset = probes[p].normal;
      for (float v : pass.receivers(rc)) acne[p] += v != 0.0f ? 1 : 0;
    }
  }
  nlohmann::json out;
  out["planes"] = planes.count;
  out["points"] = static_cast<uint64_t>(planes.count) * grid * grid;
  bool clean = true;
  for (size_t p = 0; p < probes.size(); ++p) {
    const std::string key = probes[p].level == 1.0 ? "acne_at_bound" : "acne_at_90_percent";
    out[probes[p].recipe][key] = acne[p];
    if (probes[p].level == 1.0 && acne[p] != 0) clean = false;
  }
  if (!normal_rendered(record["bound"]))
    out["normal"] = {
        {"not_rendered", "the normal offset, if any, carries lookups beyond the window drawn"}};
  out["clean_at_bound"] = clean;
  // The gap's wall and ground under parallel light rays: a directional light's.
  if (s.light == LightType::directional)
    out["gap"] = rendered_shadow_gap(s, cascade, record["bound"]["constant_metres"].get<double>());
  return out;
}

nlohmann::json rendered_shadow_gap(const ShadowSetup& s, size_t cascade, double bias_metres) {
  const LightMatrix L = light_matrix(s, cascade);
  const Vec3 up{0, 1, 0}, to_light = scaled(L.basis[2], -1);
  const Vec3 facing = normalized(Vec3{to_light[0], 0, to_light[2]});  // the wall's normal
  const Vec3 side = cross(up, facing);
  const double texel = s.texel(cascade), range = s.cascades[cascade].depth_range();
  const double gap = gap_of(s, bias_metres), reach_out = 2 * gap;  // receivers up to here
  const double tan_el = std::tan(radians(s.light_elevation));
  // Tall enough that its top's shadow lands beyond the receivers; 16 texels wide.
  const double height = 4 * reach_out * tan_el + texel, half_width = 8 * texel;
  const int grid = 64;
  ShadowPass pass(s, cascade, grid);
  // The ray-cast reference: the first ground point whose ray to the light meets the wall farther
  // than the bias, by bisection along the ground away from the light.
  const Vec3 centre = L.centre;  // the wall's foot for the ray cast; the rendered foot moves
  auto shadowed = [&](double dist) {
    return wall_hit(along(centre, facing, -dist), to_light, centre, facing, height) > bias_metres;
  };
  double lo = 0, hi = reach_out;
  for (int i = 0; i < 60; ++i) (shadowed(0.5 * (lo + hi)) ? hi : lo) = 0.5 * (lo + hi);
  const double raycast = hi;
  // Rendered: the wall and the ground drawn into the map, ground points behind the wall looked up
  // through the nearest texel with the bias on the receiver, at 8 placements a texel apart by
  // eighths (the edge's texel phase averages out).
  double rendered = 0;
  const int phases = 8;
  for (int k = 0; k < phases; ++k) {
    // Off the texel boundaries across the light (a nearest lookup exactly between two texels
    // reads neither), and k eighths of a texel along it.
    const Vec3 foot =
        along(along(centre, L.basis[0], 0.37 * texel), L.basis[1], texel * k / phases);
    auto corner = [&](double across, double toward, double rise) {
      return along(along(along(foot, side, across), facing, toward), up, rise);
    };
    std::vector<float> tris;
    auto quad = [&](const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
      for (const Vec3* v : {&a, &b, &c, &a, &c, &d})
        for (double x : *v) tris.push_back(static_cast<float>(x));
    };
    quad(corner(-half_width, 0, 0), corner(half_width, 0, 0), corner(half_width, 0, height),
         corner(-half_width, 0, height));
    quad(corner(-half_width, half_width, 0), corner(half_width, half_width, 0),
         corner(half_width, -2 * reach_out, 0), corner(-half_width, -2 * reach_out, 0));
    const double mx =
        (dot(L.basis[0], sub(foot, L.centre)) / s.cascades[cascade].extent + 0.5) * s.resolution;
    const double my =
        (dot(L.basis[1], sub(foot, L.centre)) / s.cascades[cascade].extent + 0.5) * s.resolution;
    pass.draw_casters(tris, static_cast<int>(mx) - ShadowPass::kWindow / 2,
                      static_cast<int>(my) - ShadowPass::kWindow / 2, 0, 0);
    // Receiver (gx, gy) at distance (gy + gx / grid) * step behind the wall's foot.
    const double step = reach_out / grid;
    ShadowReceivers rc;
    rc.origin = foot;
    rc.du = scaled(facing, -step);
    rc.dv = scaled(facing, -step * grid);
    rc.normal = {0, 1, 0};
    rc.receiver_offset = static_cast<float>(bias_metres / range);
    rc.reach = 0.5;
    const std::vector<float> flags = pass.receivers(rc);
    size_t first = flags.size();
    for (size_t i = 0; i < flags.size(); ++i) {
      // Row-major by gy: index gy * grid + gx is distance (gy + gx / grid) * step, in order.
      if (flags[i] != 0.0f) {
        first = i;
        break;
      }
    }
    rendered += step * static_cast<double>(first) / grid;
  }
  rendered /= phases;
  return {{"bias_metres", bias_metres},
          {"formula", gap},
          {"raycast", raycast},
          {"rendered", rendered},
          {"filter", "nearest"}};
}

}  // namespace depthprec
