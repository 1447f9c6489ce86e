// Brute-force check of the guaranteed MTS's error terms (host/base/binary32_error.h and the forms
// host/mts/bound_plane.cpp bounds): random operands through every binary32 form the model allows,
// against an 80-bit extended (x87 long double: 64-bit significand, which holds every product of
// two binary32 and every difference of pixel coordinates exactly) reference, never beyond the
// bound. One ctest test per term, 10^8 trials each (TRIALS overrides); the conversion's collision
// width over every binary32 in [0, 1] instead. Prints the largest error / bound seen: how tight
// each term is.
//   binary32_error_proof TERM [TRIALS]
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include "host/base/binary32_error.h"
#include "host/model/bound_model.h"
#include "host/model/storage_format.h"
#include "interface/binary16.h"

using namespace depthprec;
using namespace depthprec::binary32_error;

namespace {

static_assert(LDBL_MANT_DIG >= 64, "the reference needs x87 extended precision");
using Exact = long double;

// xoshiro256** (Blackman and Vigna): the trials' random numbers at a few cycles each, where the
// standard library's engines and distributions took most of the run.
struct Xoshiro {
  uint64_t s[4] = {0x9E3779B97F4A7C15ull, 0xBF58476D1CE4E5B9ull, 0x94D049BB133111EBull, 20261128};
  static uint64_t rotl(uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }
  uint64_t operator()() {
    const uint64_t out = rotl(s[1] * 5, 7) * 9, t = s[1] << 17;
    s[2] ^= s[0];
    s[3] ^= s[1];
    s[1] ^= s[2];
    s[0] ^= s[3];
    s[2] ^= t;
    s[3] = rotl(s[3], 45);
    return out;
  }
};
Xoshiro rng;

// Uniform in [0, 1) with 53 random bits; an integer in [lo, hi].
double u01() {
  return static_cast<double>(rng() >> 11) * 0x1.0p-53;
}
int integer(int lo, int hi) {
  return lo + static_cast<int>(rng() % static_cast<uint64_t>(hi - lo + 1));
}

// 2^e as a binary64, built from its bits for e in binary64's normal range: x * pow2(e) is
// std::ldexp(x, e) exactly wherever the product stays normal, without the library call that took
// a fifth of a term's run.
double pow2(int e) {
  const uint64_t bits = static_cast<uint64_t>(e + 1023) << 52;
  double p;
  std::memcpy(&p, &bits, sizeof p);
  return p;
}

// A binary32 with a random significand and an exponent in [lo, hi], random sign unless positive.
float random_float(int lo, int hi, bool positive = false) {
  const int e = integer(lo, hi);  // before the significand, as the trials' stream has it
  const float v = static_cast<float>((1 + u01()) * pow2(e));
  return positive || (rng() & 1) ? v : -v;
}

struct Worst {
  double ratio = 0;
  bool failed = false;
  void see(Exact err, double bound, const char* what) {
    const double e = static_cast<double>(std::fabs(err));
    // The reference's own rounding: 2^-60 of the magnitudes, far below any bound's margin.
    if (bound > 0) ratio = std::max(ratio, e / bound);
    if (e > bound && !failed) {
      std::fprintf(stderr, "%s: error %.17g above the bound %.17g\n", what, e, bound);
      failed = true;
    }
  }
};

const binary32_error::Rounding kNearest{false, false};

// half_ulp: rounding a real x to binary32 moves it at most half_ulp(m) for any m >= |x|.
void half_ulp_term(uint64_t n, Worst& w) {
  for (uint64_t i = 0; i < n; ++i) {
    const int e = integer(-140, 120);
    const double x = (1 + u01()) * pow2(e);
    const double bound_at = x * (1 + (i & 3) * 0.37);
    const Exact err = static_cast<Exact>(static_cast<float>(x)) - x;
    w.see(err, half_ulp(bound_at), "half_ulp");
    // Flushed: a result below 2^-126 may become zero.
    if (x < 0x1.0p-126) w.see(x, half_ulp(bound_at, true), "half_ulp flushed");
    // A shader below binary32 rounds binary32's result again (interface/binary16.h): the ES 1.00
    // highp minimum's 17 bits within its range, mediump's binary16 below 65504.
    const float f = static_cast<float>(x);
    if (x > 0x1.0p-60 && x < 0x1.0p60)
      w.see(static_cast<Exact>(dp_es2_highp(f)) - x,
            binary32_error::Rounding{false, false, 17}.half_ulp(bound_at),
            "ES 1.00 highp after binary32");
    if (x < 60000)
      w.see(static_cast<Exact>(dp_binary16(f)) - x,
            binary32_error::Rounding{false, false, 11}.half_ulp(bound_at),
            "mediump after binary32");
  }
}

// row_rounding: sum_j m_j x_j of up to four terms, in five forms (left to right, right to left,
// pairwise, a chain of fma, the object-position fma with the translation first).
void row_term(uint64_t n, Worst& w) {
  for (uint64_t i = 0; i < n; ++i) {
    const int k = 1 + static_cast<int>(rng() % 4);
    float m[4] = {0, 0, 0, 0}, x[4] = {0, 0, 0, 0};
    const int spread = static_cast<int>(rng() % 30);
    for (int j = 0; j < k; ++j) {
      const uint64_t kind = rng() % 8;
      m[j] = kind == 0 ? std::ldexp(1.0f, static_cast<int>(rng() % 9) - 4)  // a power of two
                       : random_float(-spread, spread);
      x[j] = kind == 1 ? 1.0f : random_float(-8, 8);
    }
    Exact exact = 0;
    double mags[4];
    for (int j = 0; j < 4; ++j) {
      exact += static_cast<Exact>(m[j]) * x[j];
      mags[j] = std::fabs(static_cast<double>(m[j]) * x[j]);
    }
    const double bound = row_rounding(kNearest, {{mags[0], exact_factor(m[0])},
                                                 {mags[1], exact_factor(m[1])},
                                                 {mags[2], exact_factor(m[2])},
                                                 {mags[3], exact_factor(m[3])}});
    const float t0 = m[0] * x[0], t1 = m[1] * x[1], t2 = m[2] * x[2], t3 = m[3] * x[3];
    const float forms[5] = {((t0 + t1) + t2) + t3, t0 + (t1 + (t2 + t3)), (t0 + t1) + (t2 + t3),
                            std::fma(m[3], x[3], std::fma(m[2], x[2], std::fma(m[1], x[1], t0))),
                            std::fma(m[2], x[2], std::fma(m[1], x[1], std::fma(m[0], x[0], t3)))};
    for (const float f : forms) w.see(f - exact, bound, "row_rounding");
  }
}

// reciprocal_error and product_error: x~ / w~ formed as fl(x~ fl(1/w~)) or fl(x~ / w~), with
// x~ within ex of x and w~ within ew of w, against the exact x / w.
void divide_term(uint64_t n, Worst& w) {
  for (uint64_t i = 0; i < n; ++i) {
    const float wt = random_float(-10, 30, true), xt = random_float(-10, 30);
    const double ew = wt * 0x1.0p-20 * u01(), ex = std::fabs(xt) * 0x1.0p-20 * u01();
    const Exact wx = static_cast<Exact>(wt) - ew * (rng() & 1 ? 1 : -1);
    const Exact xx = static_cast<Exact>(xt) - ex * (rng() & 1 ? 1 : -1);
    const double w_min = static_cast<double>(wx);
    const float q = 1.0f / wt;
    w.see(static_cast<Exact>(q) - 1 / wx, reciprocal_error(kNearest, w_min, ew), "reciprocal");
    const double eq = reciprocal_error(kNearest, w_min, ew);
    const double x_max = std::fabs(static_cast<double>(xx)), q_max = 1 / (w_min - ew);
    const double bound = product_error(kNearest, x_max, ex, q_max, eq, x_max * q_max);
    const Exact exact = xx / wx;
    w.see(static_cast<Exact>(xt * q) - exact, bound, "product with the reciprocal");
    w.see(static_cast<Exact>(xt / wt) - exact, bound, "quotient");
    // A quotient by a constant c, correctly rounded or as x fl(1 / c), and under D3D 11's
    // reciprocal within 1 ulp (either neighbour of the correctly rounded one).
    const float c = random_float(-10, 30, true), r = 1.0f / c;
    const Exact by_c = static_cast<Exact>(xt) / c;
    const double f_max = static_cast<double>(std::fabs(by_c));
    const double one = quotient_by_constant_error(kNearest, f_max, c);
    w.see(static_cast<Exact>(xt / c) - by_c, one, "quotient by a constant");
    w.see(static_cast<Exact>(xt * r) - by_c, one, "product with the constant's reciprocal");
    // within 1 ulp: either binary32 that brackets 1 / c
    const Exact inv = Exact(1) / c;
    float r_below = static_cast<float>(inv);
    if (static_cast<Exact>(r_below) > inv) r_below = std::nextafter(r_below, 0.0f);
    const float r_ulp = rng() & 1 || static_cast<Exact>(r_below) == inv
                            ? r_below
                            : std::nextafter(r_below, INFINITY);
    w.see(static_cast<Exact>(xt * r_ulp) - by_c, quotient_by_constant_error(kNearest, f_max, c, 2),
          "product with a reciprocal within 1 ulp");
  }
}

// The viewport transform fl(fl(x h) + h) or fma(x, h, h): within half_ulp(|x h|) (unless h is a
// power of two) + half_ulp(|x h| + h).
void viewport_term(uint64_t n, Worst& w) {
  for (uint64_t i = 0; i < n; ++i) {
    const float x = random_float(-30, 2), h = static_cast<float>(1 + rng() % 4096) * 0.5f;
    const Exact exact = static_cast<Exact>(x) * h + h;
    const double xh = std::fabs(static_cast<double>(x) * h);
    const double bound = (exact_factor(h) ? 0.0 : half_ulp(xh)) + half_ulp(xh + h);
    w.see((x * h + h) - exact, bound, "viewport");
    w.see(std::fma(x, h, h) - exact, bound, "viewport fma");
  }
}

// Plane evaluation (bound_plane.cpp "Evaluation"): c0 + gx (px - x0) + gy (py - y0) as the vertex
// form, llvmpipe's origin fma form and softpipe's quad steps, within k half_ulp(V + reach) +
// k half_ulp(reach) + |gx| half_ulp(X) + |gy| half_ulp(Y), k the model's count (5 under binary32),
// V = |value|, reach = |gx| X + |gy| Y,
// X >= every |coordinate| and |px - x0|.
void evaluation_term(uint64_t n, Worst& w) {
  const BoundModel &all = bound_model("binary32"), &ideal = bound_model("ideal"),
                   &llvmpipe = bound_model("llvmpipe"), &softpipe = bound_model("softpipe");
  for (uint64_t i = 0; i < n; ++i) {
    const float c0 = random_float(-8, 0, true);
    const int ge = -8 - static_cast<int>(rng() % 24);
    const float gx = random_float(ge - 2, ge), gy = random_float(ge - 2, ge);
    const float x0 = random_float(-2, 8, true), y0 = random_float(-2, 8, true);
    const int qx = integer(0, 511) & ~1, qy = integer(0, 511) & ~1,
              odd_x = static_cast<int>(rng() & 1), odd_y = static_cast<int>(rng() & 1);
    const float px = static_cast<float>(qx + odd_x) + 0.5f,
                py = static_cast<float>(qy + odd_y) + 0.5f;
    const Exact exact = static_cast<Exact>(c0) +
                        static_cast<Exact>(gx) * (static_cast<Exact>(px) - x0) +
                        static_cast<Exact>(gy) * (static_cast<Exact>(py) - y0);
    const double X = 2 * std::max(512.0, static_cast<double>(x0)) + 2;
    const double Y = 2 * std::max(512.0, static_cast<double>(y0)) + 2;
    const double reach = std::fabs(gx) * X + std::fabs(gy) * Y;
    const double V = std::fabs(static_cast<double>(exact));
    // Each form within the binary32 model's count (5 and 5), and within its own profile's model
    // (ideal's vertex form 2 and 2, llvmpipe's fused form 3 and 3), which bound it there.
    const double at_value = half_ulp(V + reach), at_reach = half_ulp(reach),
                 coordinates = std::fabs(gx) * half_ulp(X) + std::fabs(gy) * half_ulp(Y);
    const auto bound_with = [&](const BoundModel& m) {
      return m.value_roundings * at_value + m.reach_roundings * at_reach + coordinates;
    };
    const double bound = bound_with(all);
    const float vertex = (c0 + gx * (px - x0)) + gy * (py - y0);
    w.see(vertex - exact, bound, "vertex-anchored plane");
    w.see(vertex - exact, bound_with(ideal), "vertex-anchored plane, ideal");
    const float a0 = c0 - (gx * x0 + gy * y0);
    const float origin = std::fma(gy, py, std::fma(gx, px, a0));
    // llvmpipe evaluates at (px - 1/2, py - 1/2) from a0 at the half-pixel offset; the same
    // roundings, at the pixel centre here.
    w.see(origin - exact, bound, "origin-anchored fma plane");
    w.see(origin - exact, bound_with(llvmpipe), "origin-anchored fma, llvmpipe");
    const float qxf = static_cast<float>(qx) + 0.5f, qyf = static_cast<float>(qy) + 0.5f;
    float quad = (a0 + gx * qxf) + gy * qyf;
    if (odd_x) quad = quad + gx;
    if (odd_y) quad = quad + gy;
    w.see(quad - exact, bound, "quad-stepped plane");
    w.see(quad - exact, bound_with(softpipe), "quad-stepped plane, softpipe");
  }
}

// The depth plane's set-up (bound_plane.cpp "Set-up"): gradients from a triangle's binary32
// vertices, in the vertex form, llvmpipe's (reciprocal of the area, products with it) and
// softpipe's (vertices sorted by y), against the exact gradients of the plane through the same
// vertices, at a point of the triangle: within (6 kappa + 4) u (|gx| + |gy|) (Lx + Ly), kappa
// bounding |e1| |e2| / |det| at the anchor (the model's smallest angle, 1 degree: 57.3), L the
// triangle's extent from the anchor.
void setup_term(uint64_t n, Worst& w) {
  const double kappa = 57.3, kU = 0x1.0p-24;
  for (uint64_t i = 0; i < n; ++i) {
    float x[3], y[3], d[3];
    const int ge = -6 - static_cast<int>(rng() % 24);
    const double gx = random_float(ge - 2, ge), gy = random_float(ge - 2, ge);
    const double c = 0.25 + 0.7 * u01();
    const double size = pow2(static_cast<int>(rng() % 7));
    const float ox = static_cast<float>(512 * u01()), oy = static_cast<float>(512 * u01());
    for (int k = 0; k < 3; ++k) {
      x[k] = ox + static_cast<float>(size * u01());
      y[k] = oy + static_cast<float>(size * u01());
      d[k] = static_cast<float>(c + gx * (x[k] - ox) + gy * (y[k] - oy));
    }
    const Exact ex1 = static_cast<Exact>(x[1]) - x[0], ey1 = static_cast<Exact>(y[1]) - y[0];
    const Exact ex2 = static_cast<Exact>(x[2]) - x[0], ey2 = static_cast<Exact>(y[2]) - y[0];
    const Exact det = ex1 * ey2 - ex2 * ey1;
    const Exact n1 = std::sqrt(ex1 * ex1 + ey1 * ey1), n2 = std::sqrt(ex2 * ex2 + ey2 * ey2);
    if (!(std::fabs(det) * kappa >= n1 * n2)) continue;  // an anchor angle below 1 degree
    const Exact ed1 = static_cast<Exact>(d[1]) - d[0], ed2 = static_cast<Exact>(d[2]) - d[0];
    const Exact gxe = (ed1 * ey2 - ed2 * ey1) / det, gye = (ed2 * ex1 - ed1 * ex2) / det;
    // A point of the triangle, and the triangle's extent from vertex 0.
    double a = u01(), b = u01();
    if (a + b > 1) a = 1 - a, b = 1 - b;
    const Exact px = x[0] + a * ex1 + b * ex2, py = y[0] + a * ey1 + b * ey2;
    double Lx = 0, Ly = 0;
    for (int k = 1; k < 3; ++k) {
      Lx = std::max(Lx, std::fabs(static_cast<double>(x[k]) - x[0]));
      Ly = std::max(Ly, std::fabs(static_cast<double>(y[k]) - y[0]));
    }
    const double bound =
        (6 * kappa + 4) * kU *
        (std::fabs(static_cast<double>(gxe)) + std::fabs(static_cast<double>(gye))) * (Lx + Ly);
    const auto at = [&](float sx, float sy) {
      return (static_cast<Exact>(sx) - gxe) * (px - x[0]) +
             (static_cast<Exact>(sy) - gye) * (py - y[0]);
    };
    // vertex form
    const float e1x = x[1] - x[0], e1y = y[1] - y[0], e2x = x[2] - x[0], e2y = y[2] - y[0];
    const float e1d = d[1] - d[0], e2d = d[2] - d[0];
    const float fdet = e1x * e2y - e2x * e1y;
    w.see(at((e1d * e2y - e2d * e1y) / fdet, (e2d * e1x - e1d * e2x) / fdet), bound,
          "vertex set-up");
    // llvmpipe: ooa = 1 / (dx01 dy20 - dx20 dy01), products with it
    const float dx01 = x[0] - x[1], dy01 = y[0] - y[1], dx20 = x[2] - x[0], dy20 = y[2] - y[0];
    const float dz01 = d[0] - d[1], dz20 = d[2] - d[0];
    const float ooa = 1.0f / (dx01 * dy20 - dx20 * dy01);
    w.see(at(dz01 * (dy20 * ooa) - dz20 * (dy01 * ooa), dz20 * (dx01 * ooa) - dz01 * (dx20 * ooa)),
          bound, "llvmpipe set-up");
  }
}

// The conversion's width (mts_bound.cpp storage_width): code(d) - d N stays within an interval
// of the binary32 model's width (1 + 2^-7 for unorm16, 2 for unorm24, 3 for unorm32) under every
// conversion the profiles use, and within each profile's own model's width under its own.
void conversion_term(uint64_t n, Worst& w) {
  const BoundModel& all = bound_model("binary32");
  for (const char* name : {"unorm16", "unorm24", "unorm32"}) {
    for (const Conversion c : {Conversion::exact, Conversion::llvmpipe, Conversion::softpipe}) {
      const BoundModel& own = bound_model(c == Conversion::exact      ? "ideal"
                                          : c == Conversion::llvmpipe ? "llvmpipe"
                                                                      : "softpipe");
      const StorageFormat f =
          StorageFormat::parse(name, depthprec::Rounding::nearest_even, Denormals::keep, c);
      const double N = f.max_code();
      const int slot = unorm_entry(f.bits());
      double lo = INFINITY, hi = -INFINITY;
      for (uint64_t i = 0; i < n / 9; ++i) {
        // a step of 2^-24 in [0, 1), or a binary32 of any binade from 2^-30 up
        const float d =
            (i & 1) ? static_cast<float>(rng() >> 40) * 0x1.0p-24f : random_float(-30, -1, true);
        const double off = static_cast<double>(f.encode(d)) - static_cast<Exact>(d) * N;
        lo = std::min(lo, off);
        hi = std::max(hi, off);
      }
      w.see(hi - lo, all.unorm_width[slot], name);
      w.see(hi - lo, own.unorm_width[slot], own.name);
    }
  }
}

// The collision width (mts_bound.cpp collision_width, BoundModel::unorm_collision), exhaustively:
// for llvmpipe's and softpipe's unorm24 conversions (a binary32 product rounded before the code is
// taken), every binary32 in [0, 1] in ascending order, the codes never falling (the conversion is
// monotone, so the depths that store one code are a run of consecutive binary32 values), and each
// run's (last - first) N within the binary32 model's collision width and within the conversion's
// own profile's. The exact conversion needs no scan: its codes are round(d N) or trunc(d N) of the
// exact product (the exhaustive format proof, tests/formats/exhaustive_formats.cpp), whose runs lie
// in [(k - 1/2) / N, (k + 1/2) / N] or [k / N, (k + 1) / N): one code wide at most.
void collision_term(uint64_t, Worst& w) {
  const BoundModel& all = bound_model("binary32");
  for (const Conversion c : {Conversion::llvmpipe, Conversion::softpipe}) {
    const BoundModel& own = bound_model(to_string(c));
    const StorageFormat f =
        StorageFormat::parse("unorm24", depthprec::Rounding::nearest_even, Denormals::keep, c);
    const Exact N = f.max_code();
    uint32_t code = f.encode(0.0f);
    float first = 0.0f, last = 0.0f;
    Exact widest = 0;
    // 0 < d < 1 straight to the conversion, which df_encode calls there (this loop then runs
    // in three fifths of the time); 1 itself through df_encode, which stores the largest code
    for (uint32_t bits = 1; bits <= 0x3f800000u; ++bits) {
      float d;
      std::memcpy(&d, &bits, sizeof d);
      const uint32_t k = bits == 0x3f800000u         ? f.encode(d)
                         : c == Conversion::llvmpipe ? df_encode_unorm_llvmpipe(d, f.spec())
                                                     : df_encode_unorm_softpipe(d, f.spec());
      if (k != code) {
        if (k < code) {
          std::fprintf(stderr, "unorm24/%s: code %u at %a after %u: not monotone\n", to_string(c),
                       k, d, code);
          w.failed = true;
        }
        widest = std::max(widest, (static_cast<Exact>(last) - first) * N);
        code = k;
        first = d;
      }
      last = d;
    }
    widest = std::max(widest, (static_cast<Exact>(last) - first) * N);
    std::printf("  unorm24 %s: widest run %.12f codes\n", to_string(c),
                static_cast<double>(widest));
    w.see(widest, all.unorm_collision[unorm_entry(24)], "unorm24");
    w.see(widest, own.unorm_collision[unorm_entry(24)], own.name);
  }
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(
        stderr,
        "usage: binary32_error_proof half_ulp|row|divide|viewport|evaluation|setup|conversion|"
        "collision "
        "[TRIALS]\n");
    return 2;
  }
  const uint64_t n = argc > 2 ? std::strtoull(argv[2], nullptr, 10) : 100000000ull;
  const std::string term = argv[1];
  Worst w;
  if (term == "half_ulp")
    half_ulp_term(n, w);
  else if (term == "row")
    row_term(n, w);
  else if (term == "divide")
    divide_term(n, w);
  else if (term == "viewport")
    viewport_term(n, w);
  else if (term == "evaluation")
    evaluation_term(n, w);
  else if (term == "setup")
    setup_term(n, w);
  else if (term == "conversion")
    conversion_term(n, w);
  else if (term == "collision")
    collision_term(n, w);
  else {
    std::fprintf(stderr, "unknown term '%s'\n", argv[1]);
    return 2;
  }
  if (term == "collision")  // exhaustive: no trials
    std::printf("%s: every binary32 in [0, 1], largest width / bound %.4f\n", term.c_str(),
                w.ratio);
  else
    std::printf("%s: %llu trials, largest error / bound %.4f\n", term.c_str(),
                static_cast<unsigned long long>(n), w.ratio);
  return w.failed ? 1 : 0;
}
