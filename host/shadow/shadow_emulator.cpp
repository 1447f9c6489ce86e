#include "host/shadow/shadow_emulator.h"

#include <cmath>

#include "host/model/matrix.h"
#include "host/runtime/opencl_runtime.h"
#include "interface/bias_formula.h"
#include "interface/shadow_layout.h"

namespace depthprec {

namespace {

// splitmix64: the same sequence on every platform, unlike std's distributions.
struct Random {
  uint64_t state;
  uint64_t next() {
    uint64_t z = (state += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
  }
  double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }  // [0, 1)
};

// Half the caster triangle's leg, texels: the triangle holds every texel the filter reads around
// the receiver grid's texel.
constexpr double kTriangle = 12;

}  // namespace

ShadowPlanes shadow_planes(const ShadowSetup& s, size_t cascade, const ShadowSampling& sampling) {
  const ShadowCascade& c = s.cascades[cascade];
  const LightMatrix L = light_matrix(s, cascade);
  const double res = s.resolution, texel = s.texel(cascade), range = c.depth_range();
  const double theta_max = radians(s.slope_max);
  const bool spot = s.light == LightType::spot;
  const auto& [right, up, forward] = L.basis;
  // A spot light's ray through texel position (u, v): its direction with axial component 1, so
  // that a point at distance w along the axis is position + w ray.
  const double step = 2 * L.tan_half / res;
  const Vec3 r1 = scaled(right, step), r2 = scaled(up, step);
  const Vec3 r0 = add(forward, add(scaled(right, -L.tan_half), scaled(up, -L.tan_half)));
  // a unit vector as a times the reciprocal of its length
  auto unit = [](const Vec3& a) { return scaled(a, 1 / std::sqrt(dot(a, a))); };
  auto ray = [&](double u, double v) { return add(r0, add(scaled(r1, u), scaled(r2, v))); };
  ShadowPlanes out;
  out.count = sampling.planes;
  Random rnd{sampling.seed};
  for (uint32_t k = 0; k < sampling.planes; ++k) {
    const double theta = k < sampling.planes / 2 ? theta_max : theta_max * rnd.uniform();
    const double phi = radians(k % 4 == 0 ? 45.0 + 90.0 * ((k / 4) % 4) : 360 * rnd.uniform());
    // The grid's texel somewhere in the middle half of the map, its depth in [0.55, 0.9] (a spot
    // light's plane through the point at the row's distance on that texel's ray).
    const double bu = std::floor(res / 4 + res / 2 * rnd.uniform());
    const double bv = std::floor(res / 4 + res / 2 * rnd.uniform());
    const double d0 = 0.55 + 0.35 * rnd.uniform();
    const double z0 = c.near + (s.reversed ? 1 - d0 : d0) * range;
    const double gu = std::tan(theta) * std::cos(phi), gv = std::tan(theta) * std::sin(phi);
    // Spot: the plane through the point at that distance on the grid texel's ray, its normal
    // theta from the ray toward the light, turned toward phi about it.
    const Vec3 ray0 = ray(bu + 0.5, bv + 0.5), p0 = add(L.position, scaled(ray0, c.distance));
    const Vec3 rh = unit(ray0), e1 = unit(add(right, scaled(rh, -dot(right, rh)))),
               e2 = cross(rh, e1);
    const Vec3 n0 =
        add(scaled(rh, -std::cos(theta)),
            scaled(add(scaled(e1, std::cos(phi)), scaled(e2, std::sin(phi))), std::sin(theta)));
    // World point at texel position (u, v) on the intended plane.
    auto world = [&](double u, double v) {
      if (spot) {
        const Vec3 d = ray(u, v);
        return add(L.position, scaled(d, dot(n0, add(p0, scaled(L.position, -1))) / dot(n0, d)));
      }
      const double x = (u / res - 0.5) * c.extent, y = (v / res - 0.5) * c.extent;
      const double z = z0 + (gu * (u - bu - 0.5) + gv * (v - bv - 0.5)) * texel;
      return add(add(add(L.centre, scaled(right, x)), scaled(up, y)), scaled(forward, z));
    };
    const double q0u = bu - kTriangle, q0v = bv - kTriangle, leg = 4 * kTriangle;
    std::array<Vec3, 3> v{world(q0u, q0v), world(q0u + leg, q0v), world(q0u, q0v + leg)};
    std::array<float, SHADOW_F_STRIDE> f{};
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        f[3 * i + j] = static_cast<float>(v[i][j]);
        v[i][j] = f[3 * i + j];  // the plane is the binary32 triangle's
      }
    std::array<double, SHADOW_D_STRIDE> d{};
    Vec3 n;
    if (!spot) {
      // Receiver points lie on that triangle: affine in (u, v) through its vertices.
      const Vec3 du = scaled(add(v[1], scaled(v[0], -1)), 1 / leg);
      const Vec3 dv = scaled(add(v[2], scaled(v[0], -1)), 1 / leg);
      const Vec3 origin = add(v[0], add(scaled(du, -q0u), scaled(dv, -q0v)));
      n = cross(du, dv);
      const double len = std::sqrt(dot(n, n));
      n = scaled(n, (dot(n, forward) > 0 ? -1 : 1) / len);  // toward the light
      std::copy(origin.begin(), origin.end(), d.begin() + SHADOW_D_ORIGIN);
      std::copy(du.begin(), du.end(), d.begin() + SHADOW_D_DU);
      std::copy(dv.begin(), dv.end(), d.begin() + SHADOW_D_DV);
      d[SHADOW_D_DENOM] = 1;
    } else {
      // On that triangle's plane n . p = n . v0 along the ray through (u, v): position + l ray
      // with l = h / (n . ray), h = n . (v0 - position): projective in (u, v).
      n = unit(cross(add(v[1], scaled(v[0], -1)), add(v[2], scaled(v[0], -1))));
      if (dot(n, add(L.position, scaled(v[0], -1))) < 0) n = scaled(n, -1);  // toward the light
      const double h = dot(n, add(v[0], scaled(L.position, -1)));
      const Vec3* rows[3] = {&r0, &r1, &r2};
      for (int i = 0; i < 3; ++i) {
        const Vec3 num = add(scaled(L.position, dot(n, *rows[i])), scaled(*rows[i], h));
        std::copy(num.begin(), num.end(), d.begin() + 3 * i);
        d[SHADOW_D_DENOM + i] = dot(n, *rows[i]);
      }
    }
    for (int j = 0; j < 3; ++j) f[SHADOW_F_NORMAL + j] = static_cast<float>(n[j]);
    // The grid starts within a quarter of its step of the texel's corner: its first column and
    // row reach the texel's edges, where the filter's farthest texels lie.
    f[SHADOW_F_BASE_U] = static_cast<float>(bu + rnd.uniform() / (4.0 * sampling.grid));
    f[SHADOW_F_BASE_V] = static_cast<float>(bv + rnd.uniform() / (4.0 * sampling.grid));
    out.f.insert(out.f.end(), f.begin(), f.end());
    out.d.insert(out.d.end(), d.begin(), d.end());
  }
  return out;
}

struct ShadowEmulator::Impl {
  OpenClRuntime& rt;
  const ShadowSetup& setup;
  ShadowSampling sampling;
  BiasRule rule;
  cl::Kernel kernel;
  cl::Buffer light, planes_f, planes_d, acne;
  ShadowArgs args{};
};

ShadowEmulator::ShadowEmulator(OpenClRuntime& rt, const ShadowSetup& s, size_t cascade,
                               const ShadowSampling& sampling)
    : impl_(new Impl{rt, s, sampling, bias_rule(s.raster, s.format), {}, {}, {}, {}, {}, {}}) {
  const ShadowPlanes planes = shadow_planes(s, cascade, sampling);
  const LightMatrix L = light_matrix(s, cascade);
  std::array<float, SHADOW_LIGHT_WORDS> m{};
  for (int r = 0; r < 4; ++r)
    for (int j = 0; j < 4; ++j) m[4 * r + j] = L.m[r][j];
  cl::Program program =
      rt.program("kernels/shadow.cl", base_build_options(false) + " " + s.format.defines());
  Impl& I = *impl_;
  I.kernel = cl::Kernel(program, "shadow_acne");
  auto in = [&](const void* data, size_t bytes) {
    return cl::Buffer(rt.context(), CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, bytes,
                      const_cast<void*>(data));
  };
  I.light = in(m.data(), sizeof(m));
  I.planes_f = in(planes.f.data(), planes.f.size() * sizeof(float));
  I.planes_d = in(planes.d.data(), planes.d.size() * sizeof(double));
  I.acne = cl::Buffer(rt.context(), CL_MEM_WRITE_ONLY, planes.count * sizeof(cl_uint));
  I.args.half_res = static_cast<float>(s.resolution / 2.0);
  I.args.reach = static_cast<float>(s.filter.reach);
  I.args.count = planes.count;
  I.args.grid = sampling.grid;
  I.args.float_rule = I.rule.float_rule ? 1 : 0;
  I.args.slope_form = s.raster.slope == SlopeForm::sqrt ? BIAS_SLOPE_SQRT : BIAS_SLOPE_MAX;
  I.args.reversed = s.reversed ? 1 : 0;
  I.args.snap_bits = 8;
}

ShadowEmulator::~ShadowEmulator() {
  delete impl_;
}

uint64_t ShadowEmulator::points() const {
  return static_cast<uint64_t>(impl_->sampling.planes) * impl_->sampling.grid *
         impl_->sampling.grid;
}

uint64_t ShadowEmulator::acne(const ShadowProbe& p) {
  Impl& I = *impl_;
  ShadowArgs a = I.args;
  a.units_term = I.rule.units_term(p.units);
  a.factor = static_cast<float>(p.factor);
  a.normal_offset = static_cast<float>(p.normal);
  int index = 0;
  for (cl::Buffer* b : {&I.light, &I.planes_f, &I.planes_d, &I.acne}) I.kernel.setArg(index++, *b);
  I.kernel.setArg(index, a);
  cl::CommandQueue& q = I.rt.queue();
  q.enqueueNDRangeKernel(I.kernel, cl::NullRange, cl::NDRange(padded_size(a.count)),
                         cl::NDRange(kWorkGroup));
  std::vector<cl_uint> counts(a.count);
  q.enqueueReadBuffer(I.acne, CL_TRUE, 0, counts.size() * sizeof(cl_uint), counts.data());
  ++launches_;
  uint64_t total = 0;
  for (cl_uint c : counts) total += c;
  return total;
}

ShadowWitness shadow_witness(ShadowEmulator& e, const ShadowBound& b, bool reversed) {
  const double sign = reversed ? -1 : 1;  // the raster bias moves the caster away from the light
  ShadowWitness w;
  // Bisection on [0, hi] for the smallest clean value, hi the bound's; 16 halvings.
  auto smallest = [&](double hi, auto probe_of) {
    if (e.acne(probe_of(hi)) != 0) {
      w.bound_clean = false;
      return hi;
    }
    double lo = 0;
    if (e.acne(probe_of(lo)) == 0) return 0.0;
    for (int i = 0; i < 16; ++i) {
      const double mid = 0.5 * (lo + hi);
      (e.acne(probe_of(mid)) == 0 ? hi : lo) = mid;
    }
    return hi;
  };
  w.constant_units = smallest(b.constant_units, [&](double u) {
    return ShadowProbe{sign * u, 0, 0};
  });
  w.slope_factor = smallest(b.slope_factor, [&](double f) {
    return ShadowProbe{sign * b.error_units, sign * f, 0};
  });
  if (!std::isfinite(b.normal_metres)) {  // no normal offset suffices: nothing to witness
    w.normal_metres = NAN;
  } else
    w.normal_metres = smallest(b.normal_metres, [&](double o) {
      return ShadowProbe{sign * b.error_units, 0, o};
    });
  w.acne_below = e.acne(ShadowProbe{sign * 0.9 * b.constant_units, 0, 0});
  return w;
}

}  // namespace depthprec
