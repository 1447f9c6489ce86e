#include "host/mts/mts_bound.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "host/base/errors.h"
#include "host/model/bound_model.h"
#include "host/mts/bound_plane.h"

namespace depthprec {

namespace {

using bound::DepthError;
using bound::PlaneGeometry;
using bound::RowModel;

// The conversion's freedom in depth units: two depths that differ by more than it never store one
// code, and every conversion is monotone, so the farther one stores the larger (or, reversed,
// the smaller) code. A unorm code c(d) lies within an interval of width W of d N (N the largest
// code), W the model's (host/model/bound_model.h). A float format stores one code for an interval
// at most its spacing wide; binary32 depth into a binary32 buffer is stored as it is, where only
// a strict difference counts. A format that flushes stores one code for [0, smallest normal).
double storage_width(const RowModel& m, double d_min, double d_max) {
  const StorageFormat& f = m.format;
  if (f.is_unorm()) {
    const double* w = m.model->unorm_width;
    const int e = unorm_entry(f.bits());
    return (e < 2 ? w[e] : std::max(w[2], w[1])) / f.max_code();
  }
  // Flushed, every depth below the smallest normal stores code 0: one code for [0, normal).
  if (f.denormals() == Denormals::flush) {
    const double normal = f.decode(1u << f.spec().man_bits);
    if (d_min < normal) return std::max(f.spacing_at(d_max), normal);
  }
  if (f.name() == "float32" && d_min > 0x1.0p-126) return 0;
  return f.spacing_at(d_max);
}

// The conversion's part in the gap a fight needs: two depths that store one code lie at most this
// far apart. Every conversion the profiles use is monotone in the depth, so the depths storing a
// code are one run of binary32 values, at most the model's collision width wide (measured over
// every binary32 in [0, 1]: tests/base/binary32_error_proof.cpp collision): farther apart, the
// farther depth stores a code strictly beyond the nearer one's. A model without one (an API's
// envelope) and the float formats take storage_width, which bounds the same.
double collision_width(const RowModel& m, double d_min, double d_max) {
  const StorageFormat& f = m.format;
  if (f.is_unorm()) {
    const double c = m.model->unorm_collision[unorm_entry(f.bits())];
    if (c > 0) return c / f.max_code();
  }
  return storage_width(m, d_min, d_max);
}

// softpipe's 16-bit fast path (BoundModel::unorm16_step_pixels; Mesa's sp_quad_depth_test_tmp.h):
// a quad dx pixels into a run (one row of quads, dx <= 14) stores its first quad's codes,
// trunc(fl(z0 N)) for each of its pixels (each from its own binary32 value, as the conversion
// would), plus dx trunc(fl(G)), G = N dz/dx as the set-up computed it; the computed plane itself
// would be z0 + dx dz/dx there. trunc(G) lies within min(1, |G|) of G (towards zero), and fl(G)
// within |G| 2^-24 of G, so the code drifts from the conversion's interval by at most
// dx (min(1, |G|) + |G| 2^-23); |G| exceeds the exact plane's gradient bound g by the set-up's
// relative error, (6 kappa + 4) u < 2^-14 (bound_plane.cpp). The plane's evaluation at z0 is the
// interpolation term's. The codes are 16-bit sums: intermediate wraps cancel, and the stored code
// lies between the run's first code and the conversion's, so it stays in range when the run's
// first pixel's depth does (assumed: a run starts at most 15 pixels left of a kernel pixel, whose
// depth the check keeps inside the range). Only a plane whose depth comes from the rasterizer takes
// the path (a fragment shader writing depth does not). In depth units, per plane.
double stepped_codes(const RowModel& m, const PlaneGeometry& g) {
  const int steps = m.model->unorm16_step_pixels;
  if (steps == 0 || m.fragment || !m.format.is_unorm() || m.format.bits() > 16) return 0;
  const double n = m.format.max_code();
  const double computed = bound::window_gradient(m, g)[0] * n * (1 + 0x1.0p-14);
  return stepped_code_drift(computed, steps) / n;
}

constexpr const char* kBeyondShaderRange =
    "a vertex coordinate or shader value exceeds the shaders' range";
constexpr const char* kBeyondFar = "plane B lies beyond the far plane at every pixel";

struct BoundCheck {
  bool holds = false;
  std::array<double, bound::kTermCount> terms{};
  std::string why;
};

BoundCheck check(const RowModel& m, double z, double s) {
  BoundCheck v;
  const double DA = bound::geometry_distance(m, z), DB = bound::geometry_distance(m, z + s);
  if (!(DB > DA)) {
    v.why = "plane B coincides with plane A";
    return v;
  }
  const PlaneGeometry gA = bound::plane_geometry(m, DA), gB = bound::plane_geometry(m, DB);
  if (!(gA.wv_lo > 0) || !(m.ortho || 1 - m.tan_tilt * (m.xn_max / m.P00 + m.yn_max / m.P11) > 0)) {
    v.why = "the plane can pass the eye";
    return v;
  }
  // The shaders hold every vertex coordinate, eye and clip, and under the absolute transform the
  // world's too (camera-relative and relative-to-eye rendering never hand them a world one).
  double largest = std::max(gB.wv_hi, std::fabs(m.a) * gB.wv_hi + std::fabs(m.b));
  largest = std::max(largest, std::max(m.P00, m.P11) * gB.lateral);
  if (m.path == VertexPath::model_then_view)
    for (const double w : m.scene->world_position)
      largest = std::max(largest, std::fabs(w) + gB.wv_hi);
  // a mediump fragment shader's uniforms, and its log's argument (k w + 1, 1 + w, (w - n) + 1)
  if (m.fragment_mediump)
    largest = std::max({largest, m.fragment_uniform_max,
                        std::max(1.0, static_cast<double>(m.pc.log_k)) * gB.wv_hi + 1});
  if (!(largest < m.shader_range)) {
    v.why = kBeyondShaderRange;
    return v;
  }
  const DepthError eA = bound::depth_error(m, gA), eB = bound::depth_error(m, gB);
  const double EA = eA.total(), EB = eB.total();
  if (!std::isfinite(EA + EB)) {
    v.why = "an error bound is not finite (w's error reaches half of w)";
    return v;
  }
  // Plane A's fragments stay inside the depth range (a clipped A would leave B alone at the pixel).
  const bound::PixelDepths a = bound::pixel_depths(m, gA), b = bound::pixel_depths(m, gB);
  const double a_lo = a.lo - EA, a_hi = a.hi + EA;
  const bool a_inside =
      m.fragment ? gA.wp_lo > m.pc.near && gA.wp_hi < m.pc.far : a_lo > 0 && a_hi < 1;
  if (!a_inside) {
    v.why = "plane A's fragments can be clipped";
    return v;
  }
  // The exact gap is monotone in w for every map (its derivative has one sign), so its least value
  // over A's pixels is at an end of their range; log_vertex interpolates per-vertex depths, whose
  // gap is a convex combination of the vertices'.
  // Orthographic: plane B's fragments all beyond the depth range (its linear depth leaves [0, 1]
  // at the far plane, where a perspective map's approaches 1): B is clipped at every pixel and
  // never drawn, so nothing fights.
  if (m.ortho && b.lo - EB > 1) {
    v.holds = true;
    v.why = kBeyondFar;
    return v;
  }
  const double lo = m.vertex_log ? gA.wv_lo : gA.wp_lo, hi = m.vertex_log ? gA.wv_hi : gA.wp_hi;
  const double lm1 = (DB - DA) / DA;
  const double gap = std::min(bound::exact_gap(m, lm1, lo), bound::exact_gap(m, lm1, hi));
  const double d_max = std::max(a_hi, b.magnitude() + EB);
  const double d_min = std::max(0.0, std::min(a_lo, b.lo - EB));
  for (int t = 0; t < bound::kTermCount; ++t) v.terms[t] = eA.term[t] + eB.term[t];
  v.terms[bound::kStorage] =
      collision_width(m, d_min, d_max) + stepped_codes(m, gA) + stepped_codes(m, gB);
  double need = 0;
  for (const double t : v.terms) need += t;
  v.holds = gap > need * binary32_error::kMargin;
  if (!v.holds) v.why = "the gap does not clear the error bounds";
  return v;
}

std::string dominant_term(const BoundCheck& v) {
  int best = 0;
  for (int t = 1; t < bound::kTermCount; ++t)
    if (v.terms[t] > v.terms[best]) best = t;
  return bound::term_name(best);
}

// The separations above lo where an error bound can step up: each term is taken at magnitudes of
// plane B (its vertices' and pixels' eye distances, clip z, window depth), each monotone in B's
// distance, and a term's half-ulp doubles where its magnitude enters the next binade while the
// exact gap has grown only a little. Per magnitude, every power of two it passes between lo and
// hi, located by bisection to binary64 resolution (in no order); the check runs just above each.
std::vector<double> binade_crossings(const RowModel& m, double z, double lo, double hi) {
  using Magnitude = double (*)(const RowModel&, const PlaneGeometry&);
  static const Magnitude magnitudes[] = {
      [](const RowModel&, const PlaneGeometry& g) { return g.wv_lo; },
      [](const RowModel&, const PlaneGeometry& g) { return g.wv_hi; },
      [](const RowModel&, const PlaneGeometry& g) { return g.wp_lo; },
      [](const RowModel&, const PlaneGeometry& g) { return g.wp_hi; },
      [](const RowModel& r, const PlaneGeometry& g) { return std::fabs(-r.a * g.wv_lo + r.b); },
      [](const RowModel& r, const PlaneGeometry& g) { return std::fabs(-r.a * g.wv_hi + r.b); },
      [](const RowModel& r, const PlaneGeometry& g) {
        return std::fabs(bound::exact_depth(r, g.wp_lo));
      },
      [](const RowModel& r, const PlaneGeometry& g) {
        return std::fabs(bound::exact_depth(r, g.wp_hi));
      },
      [](const RowModel& r, const PlaneGeometry& g) {
        return std::fabs(bound::exact_depth(r, g.wv_lo));
      },
      [](const RowModel& r, const PlaneGeometry& g) {
        return std::fabs(bound::exact_depth(r, g.wv_hi));
      },
      // the plane's extent, which the lateral and set-up terms take
      [](const RowModel&, const PlaneGeometry& g) { return g.side; },
      [](const RowModel&, const PlaneGeometry& g) { return g.lateral; },
      // a log shader's argument k w + 1 and its log, at the pixels' farthest w
      [](const RowModel& r, const PlaneGeometry& g) {
        return r.fragment ? r.pc.log_k * g.wp_hi + 1 : 0.0;
      },
      [](const RowModel& r, const PlaneGeometry& g) {
        return r.fragment ? std::log(r.pc.log_k * g.wp_hi + 1) : 0.0;
      },
  };
  const auto at = [&](Magnitude f, double s) {
    return f(m, bound::plane_geometry(m, bound::geometry_distance(m, z + s)));
  };
  std::vector<double> out;
  for (const Magnitude f : magnitudes) {
    const double a = at(f, lo), b = at(f, hi);
    if (!(a > 0) || !(b > 0) || !std::isfinite(a) || !std::isfinite(b)) continue;
    const bool rising = b > a;
    int e_a = 0, e_b = 0;
    std::frexp(a, &e_a);
    std::frexp(b, &e_b);
    for (int e = std::min(e_a, e_b) + 1; e <= std::max(e_a, e_b); ++e) {
      const double edge = std::ldexp(1.0, e - 1);  // the binade [edge, 2 edge) begins here
      double l = lo, h = hi;  // the magnitude lies on lo's side of the edge at l, the other at h
      for (int k = 0; k < 200 && h > std::nextafter(l, INFINITY); ++k) {
        const double mid = 0.5 * (l + h);
        ((at(f, mid) >= edge) == rising ? h : l) = mid;
      }
      out.push_back(h);
      out.push_back(std::nextafter(h, INFINITY));
      out.push_back(l);
    }
  }
  return out;
}

}  // namespace

double stepped_code_drift(double codes_per_pixel, int pixels) {
  const double g = std::fabs(codes_per_pixel);
  return pixels * (std::min(1.0, g) + g * 0x1.0p-23);
}

CoplanarSpread coplanar_spread(const Scene& scene, const EvalPair& pair, double z) {
  CoplanarSpread out;
  RowModel m;
  try {
    m = bound::row_model(scene, pair, z);
  } catch (const InputError&) {
    return out;
  }
  const PlaneGeometry g = bound::plane_geometry(m, bound::geometry_distance(m, z));
  const double E = bound::depth_error(m, g).total();
  const bound::PixelDepths d = bound::pixel_depths(m, g);
  out.depth_min = std::max(0.0, d.lo - E);
  out.depth_max = d.hi + E;
  if (std::isfinite(E))
    out.spread =
        (2 * E + storage_width(m, out.depth_min, out.depth_max) + 2 * stepped_codes(m, g)) *
        binary32_error::kMargin;
  return out;
}

void set_mts_bound(MtsRow& row, const Scene& scene) {
  if (row.verdict() != Verdict::resolved) return;
  // A final row's MTS against the world grid's reach: the sampled answer's trust, beside the bound.
  const double reach = world_grid_reach(scene, row.z);
  row.below_world_grid = row.mts_seen < reach;
  if (row.below_world_grid) row.world_grid_reach = reach;
  const MtsBound b = mts_bound(scene, row.pair, row.z);
  row.mts_bound = b.s;
  row.bound_model = scene.bound_model;
  row.bound_note = std::isfinite(b.s) ? b.dominant : b.why;
}

bool bound_holds(const Scene& scene, const EvalPair& pair, double z, double s) {
  return check(bound::row_model(scene, pair, z), z, s).holds;
}

MtsBound mts_bound(const Scene& scene, const EvalPair& pair, double z) {
  MtsBound out;
  RowModel m;
  try {
    m = bound::row_model(scene, pair, z);
  } catch (const InputError& e) {
    out.why = e.what();
    return out;
  }
  const double cap = scene.max_separation_factor * z;
  // Doubling from below the vertex bound up to the first separation that holds, then bisection to
  // the scene's rel_precision, as the search brackets mts.
  double lo = 0, hi = std::max(vertex_bound(z), z * 0x1.0p-40);
  BoundCheck at_hi = check(m, z, hi);
  while (!at_hi.holds) {
    if (at_hi.why == "plane A's fragments can be clipped" ||
        at_hi.why == "the plane can pass the eye" || at_hi.why == kBeyondShaderRange) {
      out.why = at_hi.why;
      return out;
    }
    lo = hi;
    hi *= 2;
    if (hi > cap) {
      out.s = INFINITY;
      out.why = "no separation up to max_separation_factor z clears the error bounds";
      return out;
    }
    at_hi = check(m, z, hi);
  }
  // lo fails, hi holds: bisected to the scene's rel_precision, as the search brackets mts.
  const auto narrow = [&] {
    while ((hi - lo) / hi > scene.rel_precision) {
      const double mid = 0.5 * (lo + hi);
      BoundCheck at_mid = check(m, z, mid);
      if (at_mid.holds) {
        hi = mid;
        at_hi = at_mid;
      } else {
        lo = mid;
      }
    }
  };
  narrow();
  // The bound is meant for every separation above it: the error bounds change with plane B's
  // distance, so it is checked again at every doubling up to the search's ceiling and on both
  // sides of every binade edge a magnitude of plane B crosses there (binade_crossings). Where one
  // fails, the bound is searched again above it. Where plane B leaves the shaders' range
  // (gles_mediump's 2^14) or lies beyond the far plane the checks end: no content there can be
  // drawn at all.
  for (int pass = 0;; ++pass) {
    std::vector<double> above = binade_crossings(m, z, hi, cap);
    for (double t = 2 * hi; t <= cap; t *= 2) above.push_back(t);
    std::sort(above.begin(), above.end());
    double failed = 0;
    for (const double t : above) {
      if (!(t > hi)) continue;
      const BoundCheck at = check(m, z, t);
      if (at.why == kBeyondShaderRange || at.why == kBeyondFar) break;
      if (!at.holds) failed = t;  // the last one below the ceiling counts
    }
    if (failed == 0) break;
    if (pass == 8) {
      out.why = "the error bounds fail again at a larger separation";
      return out;
    }
    // The smallest separation above the failure that holds, doubling then bisecting as before.
    hi = failed;
    do {
      lo = hi;
      hi *= 2;
      if (hi > cap) {
        out.why = "the error bounds fail again at a larger separation";
        return out;
      }
      at_hi = check(m, z, hi);
    } while (!at_hi.holds);
    narrow();
  }
  out.s = hi;
  out.dominant = dominant_term(at_hi);
  return out;
}

}  // namespace depthprec
