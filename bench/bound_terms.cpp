// The guaranteed MTS's error terms for one row at one separation (docs/bound.md): each term summed
// over both planes, and its share of the exact gap, to see which term a bound is loose in. Without
// a row: mts_bound of every row of the scene (every pair at every distance), and the host time
// they took, one after another. With --scan Z_FROM Z_TO: for every
// pair at distances a factor 1.01 apart, the bound's condition at separations a factor 1.002
// apart from mts_bound up to 64 times it plus 4 near (so that plane B passes w = 2 near, where
// the standard projection's clip z changes sign): every separation where it fails (the search
// checks only doublings and binade edges above the bound; docs/mts.md "The condition").
//   build/bench/bound_terms [--set key=value ...] [PAIR_INDEX Z S | --scan Z_FROM Z_TO]
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <string>
#include <vector>

#include "host/mts/bound_plane.h"
#include "host/mts/mts_bound.h"

using namespace depthprec;

int main(int argc, char** argv) {
  std::vector<std::string> sets, args;
  for (int i = 1; i < argc; ++i) {
    if (std::string(argv[i]) == "--set" && i + 1 < argc)
      sets.push_back(argv[++i]);
    else
      args.push_back(argv[i]);
  }
  const bool scan = !args.empty() && args[0] == "--scan";
  if (args.size() != 3 && !args.empty()) {
    fmt::print(stderr,
               "usage: bound_terms [--set key=value ...] [PAIR_INDEX Z S | --scan Z_FROM Z_TO]\n");
    return 2;
  }
  const Scene s = load_scene("", sets);
  if (scan) {
    const double z_from = std::stod(args[1]), z_to = std::stod(args[2]);
    size_t rows = 0, checks = 0, failing = 0;
    for (const EvalPair& p : s.evaluate)
      for (double z = z_from; z <= z_to; z *= 1.01) {
        const MtsBound b = mts_bound(s, p, z);
        if (!(b.s < INFINITY)) continue;
        ++rows;
        const double top = std::min(s.max_separation_factor * z, 64 * b.s + 4 * s.near);
        size_t fails = 0;
        double first = 0;
        for (double sep = b.s; sep <= top; sep *= 1.002, ++checks)
          if (!bound_holds(s, p, z, sep) && fails++ == 0) first = sep;
        if (fails == 0) continue;
        ++failing;
        fmt::print("{} z={}: mts_bound {}, fails at {} separations above it, first {} ({:.4f}x)\n",
                   p.label(), z, b.s, fails, first, first / b.s);
      }
    fmt::print("{} rows, {} separations checked above their bounds: {} rows fail somewhere\n", rows,
               checks, failing);
    return failing == 0 ? 0 : 1;
  }
  if (args.empty()) {
    const auto t0 = std::chrono::steady_clock::now();
    size_t rows = 0;
    for (const EvalPair& p : s.evaluate)
      for (const double z : s.distances) {
        const MtsBound b = mts_bound(s, p, z);
        fmt::print("{} z={}: mts_bound {} ({})\n", p.label(), z, b.s,
                   b.s == b.s ? b.dominant : b.why);
        ++rows;
      }
    const double secs =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    fmt::print("{} rows in {:.3f} s of host time, {:.2f} ms a row\n", rows, secs,
               1e3 * secs / rows);
    return 0;
  }
  const EvalPair p = s.evaluate.at(std::stoul(args[0]));
  const double z = std::stod(args[1]), sep = std::stod(args[2]);
  const bound::RowModel m = bound::row_model(s, p, z);
  const bound::PlaneGeometry gA = bound::plane_geometry(m, bound::geometry_distance(m, z));
  const bound::PlaneGeometry gB = bound::plane_geometry(m, bound::geometry_distance(m, z + sep));
  const bound::DepthError eA = bound::depth_error(m, gA), eB = bound::depth_error(m, gB);
  const double lm1 = (gB.D - gA.D) / gA.D;
  const double gap =
      std::min(bound::exact_gap(m, lm1, gA.wp_lo), bound::exact_gap(m, lm1, gA.wp_hi));
  fmt::print("{} z={} s={}: exact gap {:.4g}, pixel w [{:.9g}, {:.9g}]\n", p.label(), z, sep, gap,
             gA.wp_lo, gA.wp_hi);
  for (int t = 0; t < bound::kTermCount; ++t)
    fmt::print("  {:<14} {:.4g} ({:.3f} of the gap)\n", bound::term_name(t),
               eA.term[t] + eB.term[t], (eA.term[t] + eB.term[t]) / gap);
  const MtsBound b = mts_bound(s, p, z);
  fmt::print("bound holds at s: {}; mts_bound {} ({})\n", bound_holds(s, p, z, sep), b.s,
             b.s == b.s ? b.dominant : b.why);
}
