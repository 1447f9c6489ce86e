// Rounding-error bounds of binary32 operations, as the guaranteed MTS (host/mts/mts_bound.h,
// docs/bound.md) adds them up: each function bounds |computed - exact| of one
// step from upper bounds on the magnitudes involved, whatever order or fusion an implementation
// picks. tests/base/binary32_error.cpp checks each against exact arithmetic by brute force.
#pragma once

#include <algorithm>
#include <cmath>
#include <initializer_list>

namespace depthprec::binary32_error {

// Half the spacing of binary32 in the binade of m: the most rounding to nearest moves a real x with
// |x| <= m. For x in [2^(e-1), 2^e) the spacing is 2^(e-24), and a real that rounds up into the
// next binade still moved by at most half the spacing of its own; m an upper bound keeps it one
// (the binade of m is at least x's). Below 2^-126 the subnormal spacing 2^-149, or, where
// denormals are flushed, the whole value (at most 2^-126). `directed` (rounding towards zero or
// any directed mode) moves by up to the full spacing.
inline double half_ulp(double m, bool flush = false, bool directed = false) {
  double h = 0x1.0p-150;  // half the subnormal spacing 2^-149
  if (m >= 0x1.0p-126) {
    int e = 0;
    std::frexp(m, &e);  // m = f 2^e, f in [0.5, 1): binade [2^(e-1), 2^e)
    h = std::ldexp(1.0, e - 25);
  }
  if (directed) h *= 2;
  // A result of magnitude below 2^-126 (m bounds it from above only) flushed to zero moves by
  // its whole magnitude.
  return flush ? std::max(h, 0x1.0p-126) : h;
}

// Binary64's own rounding of the bounds below (2^-53 per step, a few dozen steps) stays far below
// this relative margin, which every sum of error terms is multiplied by.
constexpr double kMargin = 1.0 + 0x1.0p-30;

// How an implementation rounds: to nearest (every profile), or directed; whether it flushes
// results below 2^-126 to zero. bits: the significand's precision, 24 for binary32; a shader's
// mediump may carry as few as 11 (GLSL ES: relative precision 2^-10, normal from 2^-14), where
// half_ulp scales accordingly.
struct Rounding {
  bool flush = false, directed = false;
  int bits = 24;
  double half_ulp(double m) const {
    if (bits == 24) return binary32_error::half_ulp(m, flush, directed);
    // Below 2^-14 a mediump value may be flushed: its whole magnitude.
    double h = 0x1.0p-14;
    if (m >= 0x1.0p-14) {
      int e = 0;
      std::frexp(m, &e);
      h = std::ldexp(1.0, e - 1 - bits);
    }
    // A shader that computes in binary32 and rounds to its precision after (as the emulation
    // does, interface/binary16.h) rounds twice: binary32's half-ulp on top (2^-13 of mediump's,
    // 2^-7 of the ES 1.00 highp minimum's).
    return (directed ? 2 * h : h) + binary32_error::half_ulp(m, flush, directed);
  }
};

// One term m_j x_j of a row times a vector: an upper bound on its magnitude, and whether the
// product is exact (a factor zero or a power of two, the other in range).
struct RowTerm {
  double magnitude;
  bool exact_product;
};

// The rounding error of sum_j m_j x_j over its nonzero terms, in any association, each product
// rounded or fused into the next sum: every inexact product rounds once (within half_ulp of its
// magnitude; a fused multiply-add skips that rounding), and each of the k - 1 sums rounds once at a
// magnitude no larger than the sum of the terms' magnitudes (every partial sum, in any order, is a
// sum of a subset of the rounded terms).
inline double row_rounding(const Rounding& r, std::initializer_list<RowTerm> terms) {
  double products = 0, total = 0;
  int k = 0;
  for (const RowTerm& t : terms) {
    if (t.magnitude == 0) continue;
    ++k;
    total += t.magnitude;
    if (!t.exact_product) products += r.half_ulp(t.magnitude);
  }
  // The rounded products exceed their magnitudes by at most half an ulp each: 2^-23 relative.
  const double sums = k > 1 ? (k - 1) * r.half_ulp(total * (1 + 0x1.0p-22)) : 0.0;
  return (products + sums) * kMargin;
}

// Whether m times any binary32 in range is exact: m zero or a power of two.
inline bool exact_factor(double m) {
  int e = 0;
  return m == 0 || std::fabs(std::frexp(m, &e)) == 0.5;
}

// The reciprocal of a computed value w~ within ew of w > 0 (ew < w / 2), rounded: |fl(1/w~) - 1/w|
// <= ew / (w (w - ew)) + half_ulp(1 / (w - ew)), w the smallest w of the range. A divide x / w in
// its place rounds once instead of twice: product_error covers it. half_ulps: how far the
// reciprocal may lie from the correctly rounded one (2: within 1 ulp, as D3D 11.3 allows).
inline double reciprocal_error(const Rounding& r, double w_min, double ew, double half_ulps = 1) {
  return (ew / (w_min * (w_min - ew)) + half_ulps * r.half_ulp(1.0 / (w_min - ew))) * kMargin;
}

// The product x~ q~ of computed values, |x~ - x| <= ex, |q~ - q| <= eq, with |x| <= x_max,
// |q| <= q_max, rounded: within q_max ex + x_max eq + ex eq + half_ulp(result_max + that), with
// result_max >= |x q| (from the exact map where x_max q_max would cross a binade the values never
// reach). The quotient x~ / w~ correctly rounded is within the same bound, eq the reciprocal's.
inline double product_error(const Rounding& r, double x_max, double ex, double q_max, double eq,
                            double result_max) {
  const double carried = q_max * ex + x_max * eq + ex * eq;
  return (carried + r.half_ulp(result_max + carried)) * kMargin;
}

// x / c for a constant c the shader holds in binary32 (a near plane's range, a log's L), |x / c|
// <= f_max: as a correctly rounded quotient (one rounding), or as x times the reciprocal
// fl(1 / c) a compiler forms in its place, that within half_ulps of 1 / c: |x| half_ulps
// half_ulp(1 / |c|) carried, then the product's rounding. (The carried part reaches twice the
// result's half-ulp where 1 / c sits low in its binade and x / c high in its own.)
inline double quotient_by_constant_error(const Rounding& r, double f_max, double c,
                                         double half_ulps = 1) {
  const double carried = f_max * std::fabs(c) * half_ulps * r.half_ulp(1.0 / std::fabs(c));
  return (carried + r.half_ulp(f_max + carried)) * kMargin;
}

}  // namespace depthprec::binary32_error
