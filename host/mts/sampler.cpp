#include "host/mts/sampler.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

namespace depthprec {

namespace {

// Point n of the R3 sequence in [0, 1)^3 (M. Roberts, "The unreasonable effectiveness of
// quasirandom sequences", 2018): x_i = frac(1/2 + n / g^(i+1)), g the real root of
// x^4 = x + 1. Its points fill the cube evenly at every length, so a round's points lie between
// the earlier rounds' rather than on them.
std::array<double, 3> r3(uint64_t n) {
  constexpr double g = 1.2207440846057594754;
  std::array<double, 3> x{};
  double a = 1;
  for (int i = 0; i < 3; ++i) {
    a /= g;
    const double v = 0.5 + a * static_cast<double>(n);
    x[i] = v - std::floor(v);
  }
  return x;
}

}  // namespace

size_t round_size(const Scene& scene, int round) {
  return static_cast<size_t>(scene.worst_case.round_size) << (round - 1);
}

std::vector<Angles> round_orientations(const Scene& scene, int round) {
  const double r = std::abs(scene.rotation_range_deg) * M_PI / 180.0;
  // Each axis as the paper's path distributes it, r sin(phase) with the phase uniform: a sine
  // dwells near its extremes, where the planes are steepest.
  const auto in_cube = [r](const std::array<double, 3>& u) {
    Angles a{};
    for (int i = 0; i < 3; ++i) a[i] = r * std::sin(M_PI * (u[i] - 0.5));
    return a;
  };
  const size_t n = round_size(scene, round);
  std::vector<Angles> out;
  out.reserve(n);
  // Round 1 starts with the cube's corners (every axis at its limit: the steepest planes).
  const size_t corners = round == 1 ? std::min<size_t>(8, n) : 0;
  for (size_t c = 0; c < corners; ++c)
    out.push_back({c & 1 ? r : -r, c & 2 ? r : -r, c & 4 ? r : -r});
  // The sequence's points so far: the earlier rounds' sizes less the corners.
  uint64_t next = 0;
  for (int k = 1; k < round; ++k) next += round_size(scene, k);
  if (round > 1) next -= std::min<size_t>(8, round_size(scene, 1));
  while (out.size() < n) out.push_back(in_cube(r3(next++)));
  return out;
}

std::vector<std::vector<Angles>> round_chunks(const Scene& scene, int round) {
  const std::vector<Angles> list = round_orientations(scene, round);
  const auto chunk = static_cast<size_t>(scene.worst_case.round_size);
  std::vector<std::vector<Angles>> out;
  for (size_t first = 0; first < list.size(); first += chunk) {
    const auto from = list.begin() + static_cast<long>(first);
    out.emplace_back(from, from + static_cast<long>(std::min(chunk, list.size() - first)));
  }
  return out;
}

}  // namespace depthprec
