#include "host/model/resolve.h"

#include <fmt/format.h>

#include <cmath>

#include "host/base/errors.h"

namespace depthprec {

namespace {

using quad = __float128;

quad distance_q(const ResolveSetup& s, double depth) {
  return distance_of_depth<quad>(s.technique, s.near, s.far, s.params, depth);
}

}  // namespace

void validate(const ResolveSetup& s) {
  if (!(s.near > 0) || !std::isfinite(s.near))
    throw InputError(fmt::format("--near must be a finite distance > 0, not {}", s.near));
  if (!(s.far > s.near))
    throw InputError(fmt::format("--far must be > near ({}), not {}", s.near, s.far));
  // As the scenes' log_k (scene_parse.cpp): log(k w + 1) needs k > 0, and a finite one.
  if (!(s.params.log_k > 0) || !std::isfinite(s.params.log_k))
    throw InputError(fmt::format("--log-k must be a finite k > 0, not {}", s.params.log_k));
  if (s.technique == Technique::layered)
    throw InputError(
        "resolve: layered has one mapping per layer; ask for its layer mapping with "
        "the layer's near and far");
  const bool infinite_ok = s.technique == Technique::infinite ||
                           s.technique == Technique::reversed_infinite ||
                           s.technique == Technique::inverse_w;
  if (!std::isfinite(s.far) && !infinite_ok)
    throw InputError(
        fmt::format("--far inf has no mapping for {}: only infinite, "
                    "reversed_infinite and inverse_w have no far plane",
                    info(s.technique).name));
}

ResolveSetup mapping_at(Technique t, double near, double far, const TechniqueParams& p, double z) {
  if (t != Technique::layered) return {t, near, far, p};
  const Layer l = layer_bounds(layer_of(z, near, far, p), near, far, p);
  return {p.layer_mapping, l.near, l.far, p};
}

double distance_gap(const ResolveSetup& s, double a, double b) {
  quad d = distance_q(s, a) - distance_q(s, b);
  if (d == 0 && a != b) {
    // Depths this close can map to distances binary128 does not tell apart (a reversed float
    // buffer's last code at the far plane: 1.4e-45 of depth is about 1e-36 of distance at 1e4):
    // the mapping's slope over a step of 2^-40 of depth toward b, times their difference.
    const double h = std::ldexp(b > a ? 1.0 : -1.0, -40);
    d = (distance_q(s, a + h) - distance_q(s, a)) / static_cast<quad>(h) * static_cast<quad>(b - a);
  }
  return static_cast<double>(d < 0 ? -d : d);
}

CodeInterval resolve_code(const ResolveSetup& s, const StorageFormat& f, uint32_t code) {
  validate(s);
  if (code > f.max_code())
    throw InputError(
        fmt::format("--code {} is beyond {}'s largest code {}", code, f.name(), f.max_code()));
  CodeInterval ci;
  ci.code = code;
  ci.depth = f.decode(code);
  ci.distance = distance_of_depth(s.technique, s.near, s.far, s.params, ci.depth);
  // The depths stored as this code: [value, next) when truncating; between the midpoints to the
  // neighbours when rounding to nearest.
  const double below = code > 0 ? f.decode(code - 1) : ci.depth;
  const double above = code < f.max_code() ? f.decode(code + 1) : ci.depth;
  if (f.rounding() == Rounding::truncate) {
    ci.depth_lo = ci.depth;
    ci.depth_hi = above;
  } else {
    ci.depth_lo = code > 0 ? ci.depth - 0.5 * (ci.depth - below) : 0.0;
    ci.depth_hi = code < f.max_code() ? ci.depth + 0.5 * (above - ci.depth) : ci.depth;
  }
  const double a = distance_of_depth(s.technique, s.near, s.far, s.params, ci.depth_lo);
  const double b = distance_of_depth(s.technique, s.near, s.far, s.params, ci.depth_hi);
  ci.distance_lo = std::min(a, b);
  ci.distance_hi = std::max(a, b);
  return ci;
}

void check_stored_distance(const ResolveSetup& s, double w, const std::string& option) {
  if (!(w > 0) || !std::isfinite(w))
    throw InputError(fmt::format("{} must be a finite eye distance > 0, not {}", option, w));
  // Outside the clip volume there is no stored depth to resolve: the pipeline clips the fragment.
  if (info(s.technique).clips_near && w < s.near)
    throw InputError(
        fmt::format("{} {} is nearer than the near plane {}: {} clips it (no depth is stored)",
                    option, w, s.near, info(s.technique).name));
  if (has_far_plane(s.technique) && w > s.far)
    throw InputError(
        fmt::format("{} {} is beyond the far plane {}: {} clips it (no depth is stored)", option, w,
                    s.far, info(s.technique).name));
}

DistanceResolution resolve_distance(const ResolveSetup& s, const StorageFormat& f, double w) {
  validate(s);
  check_stored_distance(s, w, "--distance");
  DistanceResolution r;
  r.distance = w;
  r.depth = depth_of_distance(s.technique, s.near, s.far, s.params, w);
  // The code the exact depth rounds to (binary64 depth; the pipeline's binary32 depth may differ
  // by its own rounding, which `mts` measures).
  uint32_t c = f.code_floor(r.depth);
  if (f.rounding() == Rounding::nearest_even && c < f.max_code()) {
    const double lo = f.decode(c), hi = f.decode(c + 1);
    if (r.depth - lo > hi - r.depth || (r.depth - lo == hi - r.depth && (c & 1u))) ++c;
  }
  r.code = c;
  const double v = f.decode(c);
  // The first and last codes have one neighbour: the other gap is none (NaN), not zero.
  r.gap_below = c > 0 ? distance_gap(s, v, f.decode(c - 1)) : NAN;
  r.gap_above = c < f.max_code() ? distance_gap(s, v, f.decode(c + 1)) : NAN;
  r.resolution = std::fmax(r.gap_below, r.gap_above);
  return r;
}

double code_interval_width(const ResolveSetup& s, const StorageFormat& f, double w) {
  const CodeInterval ci = resolve_code(s, f, resolve_distance(s, f, w).code);
  return ci.distance_hi - ci.distance_lo;
}

std::vector<DistanceResolution> resolution_curve(const ResolveSetup& s, const StorageFormat& f,
                                                 int points) {
  validate(s);
  if (points < 2 || points > 1000000)
    throw InputError(fmt::format("--points must be 2..1000000, not {}", points));
  if (!std::isfinite(s.far)) throw InputError("--curve needs a finite --far to span the range");
  std::vector<DistanceResolution> out;
  for (int i = 0; i < points; ++i) {
    const double w = i + 1 == points
                         ? s.far
                         : s.near * std::pow(s.far / s.near, static_cast<double>(i) / (points - 1));
    out.push_back(resolve_distance(s, f, w));
  }
  return out;
}

}  // namespace depthprec
