#include "host/analysis/world_sweep.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "host/analysis/advise.h"
#include "host/base/errors.h"
#include "host/model/bound_model.h"
#include "host/mts/worst_case.h"

namespace depthprec {

namespace {

std::array<double, 3> unit(const std::array<double, 3>& d) {
  const double n = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  return {d[0] / n, d[1] / n, d[2] / n};
}

const char* const kAxisNames[] = {"x", "y", "z"};

// The spacing of a `precision`-bit significand in the binade holding m.
double grid_spacing(double m, int precision) {
  if (!(m > 0)) return 0;
  int e = 0;
  std::frexp(m, &e);
  return std::ldexp(1.0, e - precision);
}

// The vertex shader's significand: binary32's 24 bits, or its precision's below it (the
// gles_mediump bound model's 11, gles2_highp's 17).
int shader_bits(const Scene& scene) {
  const BoundModel* reduced =
      shader_precision_model(static_cast<int>(scene.pipeline.shader_precision));
  return reduced ? reduced->shader_bits : 24;
}

// The magnitudes the sweep considers: from below any vertex's reach to above world_position's
// bound plus the content's distance.
constexpr int kFirstExponent = -30, kLastExponent = 62;

// The largest vertex coordinate at world distance R (the centre's, plus the plane's reach) and
// its axis.
double largest_coordinate(const WorldRequest& r, double reach, double R, int* axis) {
  const auto d = unit(r.direction);
  const std::array<double, 3> centre = {R * d[0], R * d[1], R * d[2] - r.z};
  double m = -1;
  for (int i = 0; i < 3; ++i)
    if (std::abs(centre[i]) + reach > m) {
      m = std::abs(centre[i]) + reach;
      *axis = i;
    }
  return m;
}

// The planes' steepest slope against the view over the orientations the scene allows (each axis
// within +-rotation_range_deg; the turn about z tilts nothing): a lateral error e of a vertex moves
// the depth under a pixel by up to e times this.
double steepest_slope(const Scene& scene) {
  const double a = scene.rotation_range_deg * M_PI / 180;
  const double nz = std::cos(a) * std::cos(a);  // the normal's view component, turned about x and y
  if (!(nz > 0) || a >= M_PI / 2) return INFINITY;
  return std::sqrt(1 - nz * nz) / nz;
}

// The MTS at eye distance z with the world at distance R along the direction (infinite when the
// search does not resolve it), every position searched, and how many searches ran.
struct WorldProbe {
  const WorldRequest& r;
  OpenClRuntime& rt;
  const Scene& scene;
  const EvalPair& pair;
  Transform t;
  int searches = 0;
  nlohmann::json probes = nlohmann::json::array();

  bool holds(double mts) const { return mts <= r.separation; }

  double mts_at(double R) {
    for (const auto& p : probes)
      if (p[0].get<double>() == R) return p[1].get<double>();
    const auto d = unit(r.direction);
    const Scene s = with_world(scene, {R * d[0], R * d[1], R * d[2]}, t);
    ++searches;
    const std::vector<MtsRow> rows = search_sampled(rt, s, pair, {r.z});
    const MtsRow& row = rows.at(0);
    const double mts = row.verdict() == Verdict::resolved ? row.mts : INFINITY;
    probes.push_back({R, mts});
    return mts;
  }
};

struct WorldLimit {
  double distance = 0;
  int axis = -1;
  double coordinate = 0, spacing = 0;
  std::string from;                       // "spacing", "bound" or "measured"
  double fails_at = -1, mts_at_fail = 0;  // fails_at < 0: no search failed
};

WorldLimit first_limit(const WorldProbe& probe, const SpacingLimit& by_spacing, double bound,
                       double reach) {
  WorldLimit l;
  l.distance = std::min(by_spacing.distance, bound);
  l.axis = by_spacing.axis;
  l.coordinate = by_spacing.coordinate;
  l.spacing = by_spacing.spacing;
  l.from = "spacing";
  if (!std::isfinite(by_spacing.distance)) {
    l.coordinate = largest_coordinate(probe.r, reach, bound, &l.axis);
    l.spacing = coordinate_spacing(probe.t, probe.scene, l.coordinate);
    l.from = "bound";
  }
  return l;
}

// A binade decided without a search: each plane's vertex coordinates are off by at most a
// spacing u (the translation rounds, then its sum with the vertex's offset), so the planes'
// separation along any view moves by at most two spacings per axis, lateral ones through the
// planes' slope; the eye-space coordinates round too where the view's subtraction is inexact.
bool holds_without_search(const WorldProbe& probe, double origin, double reach, double u) {
  const double eye = grid_spacing(probe.r.z + reach, shader_bits(probe.scene));
  const double slope = steepest_slope(probe.scene);
  return origin + 2 * (u + eye) * (std::sqrt(3.0) + 2 * slope) <= probe.r.separation;
}

// The last exponent from e on whose binade, below the coordinate, has e's spacing u: binades of
// one spacing are searched as one (relative to eye's low part has the same grid from 32768 on).
int same_spacing_top(const WorldProbe& probe, int e, double u, double coordinate) {
  int top_e = e;
  while (top_e + 1 < kLastExponent && std::ldexp(1.0, top_e + 1) < coordinate &&
         coordinate_spacing(probe.t, probe.scene, std::ldexp(1.0, top_e + 1)) == u)
    ++top_e;
  return top_e;
}

// The binades below the limit, lowest first; each that holds_without_search leaves open is
// searched at its sawtooth's peak and just below its end, where its coordinates are largest, and
// the first to fail lowers the limit to its start. The binade just below the limit is searched
// whatever holds_without_search says, as evidence.
void search_binades(WorldProbe& probe, double origin, double reach, WorldLimit& l) {
  const WorldRequest& r = probe.r;
  const Scene& scene = probe.scene;
  for (int e = kFirstExponent; e < kLastExponent && l.fails_at < 0; ++e) {
    const double M = std::ldexp(1.0, e);
    if (M >= l.coordinate) break;
    const double u = coordinate_spacing(probe.t, scene, M);
    const int top_e = same_spacing_top(probe, e, u, l.coordinate);
    int start_axis = -1, unused = -1;
    const double a = first_reach(r, scene, M, &start_axis);
    const double b =
        std::min(first_reach(r, scene, std::ldexp(1.0, top_e + 1), &unused), l.distance);
    e = top_e;
    if (!(a < b) || (holds_without_search(probe, origin, reach, u) && b < l.distance)) continue;
    const double top = std::max(a, b * (1 - std::ldexp(1.0, -12)));
    for (const double R : {sawtooth_peak(r, scene, probe.t, top), top}) {
      if (R < a) continue;
      const double m = probe.mts_at(R);
      if (probe.holds(m)) continue;
      l.fails_at = R;
      l.mts_at_fail = m;
      l.distance = a;
      l.coordinate = M;
      l.spacing = u;
      l.axis = start_axis;
      l.from = "measured";
      break;
    }
  }
}

// The evidence past a spacing limit: the depth axis's own sawtooth peak just inside the binade
// where its spacing reaches the separation (a lateral axis has none: this view sees it only
// through the planes' slope).
void search_past_spacing_limit(WorldProbe& probe, const SpacingLimit& by_spacing, double bound,
                               WorldLimit& l) {
  const auto d = unit(probe.r.direction);
  if (!(l.fails_at < 0 && l.from == "spacing" && l.distance > 0 && d[2] != 0)) return;
  const double past = by_spacing.coordinate * (1 + std::ldexp(1.0, -8));
  const double R0 = ((d[2] > 0 ? past : -past) + probe.r.z) / d[2];
  if (!(R0 > 0 && R0 <= bound)) return;
  const double R = sawtooth_peak(probe.r, probe.scene, probe.t, R0);
  const double m = probe.mts_at(R);
  if (!probe.holds(m)) {
    l.fails_at = R;
    l.mts_at_fail = m;
  }
}

void write_limit(const WorldProbe& probe, double origin, const WorldLimit& l, nlohmann::json& j) {
  double below = origin, below_at = 0;
  for (const auto& p : probe.probes)
    if (p[0].get<double>() < l.distance && p[1].get<double>() > below) {
      below = p[1].get<double>();
      below_at = p[0].get<double>();
    }
  j["limit"] = l.distance;
  j["holds_to_bound"] = l.from == "bound";
  j["limit_from"] = l.from;
  j["spacing"] = l.spacing;
  j["coordinate"] = l.coordinate;
  j["axis"] = kAxisNames[l.axis];
  j["mts_below"] = below;
  j["mts_below_at"] = below_at;
  if (l.fails_at >= 0) {
    j["fails_at"] = l.fails_at;
    j["mts_at_fail"] = l.mts_at_fail;
  }
}

nlohmann::json sweep(WorldProbe& probe) {
  nlohmann::json j;
  const double origin = probe.mts_at(0);
  j["mts_at_origin"] = origin;
  if (probe.holds(origin)) {
    const double bound = world_distance_limit(probe.r);
    const double reach = plane_reach(probe.scene, probe.r);
    const SpacingLimit by_spacing = spacing_limit(probe.r, probe.scene, probe.t);
    WorldLimit l = first_limit(probe, by_spacing, bound, reach);
    search_binades(probe, origin, reach, l);
    search_past_spacing_limit(probe, by_spacing, bound, l);
    write_limit(probe, origin, l, j);
  } else {
    j["holds_to_bound"] = false;
  }
  j["probes"] = probe.probes;
  j["searches"] = probe.searches;
  return j;
}

}  // namespace

void validate(const WorldRequest& r, const Scene& scene) {
  if (!(r.z > 0) || !std::isfinite(r.z))
    throw InputError(fmt::format("--distance {}: the content's eye distance must be > 0", r.z));
  if (!(r.z > scene.near))
    throw InputError(
        fmt::format("--distance {}: the content must lie beyond the near plane ({}); set --near",
                    r.z, scene.near));
  const auto& d = r.direction;
  if (!(d[0] * d[0] + d[1] * d[1] + d[2] * d[2] > 0) || !std::isfinite(d[0] + d[1] + d[2]))
    throw InputError(
        fmt::format("--direction {},{},{}: must be a finite, non-zero vector", d[0], d[1], d[2]));
  if (r.transforms.empty()) throw InputError("--transforms: name at least one transform");
  check_content_request(scene, r.z, r.separation);
}

Scene with_world(const Scene& scene, const std::array<double, 3>& world_position, Transform t) {
  nlohmann::json j = scene.json;
  j["world_position"] = world_position;
  j["pipeline"]["transform"] = to_string(t);
  Scene s = scene_from_json(j, scene.source);
  s.name = scene.name;
  return s;
}

double world_distance_limit(const WorldRequest& r) {
  const auto d = unit(r.direction);
  const double m = std::max({std::abs(d[0]), std::abs(d[1]), std::abs(d[2])});
  return kMaxWorldCoordinate / m;
}

double coordinate_spacing(Transform t, const Scene& scene, double magnitude) {
  switch (t) {
    case Transform::absolute: {
      // Premultiplied in binary64, the host forms P * V * M before anything is rounded; a mediump
      // shader holds even that matrix in binary16.
      const bool host64 = scene.pipeline.compose == Compose::premultiplied &&
                          scene.pipeline.matrix_precision == MatrixPrecision::binary64;
      return grid_spacing(magnitude, std::min(host64 ? 53 : 24, shader_bits(scene)));
    }
    case Transform::camera_relative:
      return grid_spacing(magnitude, 53);
    case Transform::relative_to_eye: {
      // The low part is below 65536 (interface/relative_to_eye.h), whatever the coordinate.
      const double low = std::min(magnitude, static_cast<double>(std::nextafter(65536.0f, 0.0f)));
      return std::max(grid_spacing(low, 24), grid_spacing(magnitude, 53));
    }
  }
  return 0;
}

double plane_reach(const Scene& scene, const WorldRequest& r) {
  // The square of docs/spec.md 5.1 (side plane_margin times the view at its distance) at plane
  // B's distance, B as far behind as twice the separation the search needs.
  const double D = r.z + 2 * r.separation;
  const double side = scene.plane_margin * 2 * D * std::tan(scene.fov_y_deg * M_PI / 360);
  return side / std::sqrt(2.0);
}

double first_reach(const WorldRequest& r, const Scene& scene, double magnitude, int* axis) {
  const auto d = unit(r.direction);
  const double need = magnitude - plane_reach(scene, r);  // of the centre's coordinate
  const std::array<double, 3> o = {0, 0, -r.z};
  double best = INFINITY;
  for (int i = 0; i < 3; ++i) {
    double R = INFINITY;
    if (std::abs(o[i]) >= need)
      R = 0;
    else if (d[i] > 0)
      R = (need - o[i]) / d[i];
    else if (d[i] < 0)
      R = (need + o[i]) / -d[i];
    if (R < best) {
      best = R;
      *axis = i;
    }
  }
  return best;
}

SpacingLimit spacing_limit(const WorldRequest& r, const Scene& scene, Transform t) {
  SpacingLimit out;
  out.distance = INFINITY;
  for (int e = kFirstExponent; e <= kLastExponent; ++e) {
    const double M = std::ldexp(1.0, e);
    const double u = coordinate_spacing(t, scene, M);
    if (u < r.separation) continue;
    out.coordinate = M;
    out.spacing = u;
    const double R = first_reach(r, scene, M, &out.axis);
    if (R <= world_distance_limit(r)) out.distance = R;
    return out;
  }
  return out;
}

double sawtooth_peak(const WorldRequest& r, const Scene& scene, Transform t, double at) {
  const auto d = unit(r.direction);
  if (d[2] == 0) return at;
  // Plane A's translation along the view, t0 = R d_z - z; B's is t0 - s. fl(t0 - s) leaves
  // fl(t0) once s > (t0 - fl(t0)) + u/2, which approaches u as t0 approaches the midpoint above
  // fl(t0); 1/256 of a spacing below it keeps clear of ties and of B's own rounding to binary32.
  const double t0 = at * d[2] - r.z;
  const double u = coordinate_spacing(t, scene, std::abs(t0));
  if (!(u > 0)) return at;
  double peak = std::floor(t0 / u) * u + u / 2 - u / 256;
  if (d[2] > 0 && peak > t0) peak -= u;
  if (d[2] < 0 && peak < t0) peak += u;
  return std::max(0.0, (peak + r.z) / d[2]);
}

nlohmann::json world_record(OpenClRuntime& rt, const Scene& scene, const EvalPair& pair,
                            const WorldRequest& r) {
  nlohmann::json rec = pair.fields();
  for (const Transform t : r.transforms) {
    WorldProbe probe{r, rt, scene, pair, t};
    rec["transforms"][to_string(t)] = sweep(probe);
  }
  return rec;
}

}  // namespace depthprec
