#include "host/audit/audit_reference.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "host/audit/depth_tolerance.h"
#include "host/runtime/kernel_variant.h"
#include "interface/audit_layout.h"

namespace depthprec {

namespace {

struct PixelState {
  uint32_t stored, front_code = 0, second_code = 0;
  float front_lo = 0, front_hi = 0, second_lo = 0, second_hi = 0;  // tolerance16's intervals
  int64_t winner = -1, front = -1;
  double winner_s = INFINITY, front_s = INFINITY, second_s = INFINITY;
  bool coplanar = false, discarded = false;
};

bool same_depth(double a, double b) {
  return std::fabs(a - b) <= AUDIT_COPLANAR_RELATIVE * std::fmin(a, b);
}

// One fragment of record r at (px, py) through the depth test and the exact front surface's
// bookkeeping, as kernels/audit.cl's loop body.
void take(const Scene& s, const AuditSetup& a, const StorageFormat& fmt, bool greater, size_t r,
          float px, float py, PixelState& p) {
  const SetupTriangle& t = a.records[r];
  if (!t.valid || py < t.ymin || py > t.ymax || !covers(t, px, py)) return;
  uint32_t code = 0;
  float v = 0, d = 0;
  if (fragment_code(s, a.pair, fmt, a.pc, t, px, py, code, t.bias != 0.0f, &v, &d) != fragment_ok) {
    p.discarded = true;
    return;
  }
  // kernels/audit.cl tolerance16
  const float* TL = &a.tolerance[r * AUDIT_TOL_WORDS];
  const float plane =
      TL[AUDIT_TOL_E0] + TL[AUDIT_TOL_EX] * (px - t.x0) + TL[AUDIT_TOL_EY] * (py - t.y0);
  const float tv = (TL[AUDIT_TOL_C] + std::fmax(plane, 0.0f)) * (1.0f + 0x1.0p-20f);
  float lo = d - tv, hi = d + tv;
  if (info(depth_path(s, a.pair.technique)).from == DepthFrom::fragment) {
    const float d1 = depth_of_value(s, a.pair, a.pc, v - tv),
                d2 = depth_of_value(s, a.pair, a.pc, v + tv);
    const float shader = TL[AUDIT_TOL_SHADER] * (1.0f + 0x1.0p-20f);
    lo = std::fmin(d1, d2) - shader;
    hi = std::fmax(d1, d2) + shader;
  }
  const uint32_t src = a.source[r];
  const double sd = ray_depth(a.ray, a.planes[src], px, py);
  if (greater ? code > p.stored : code < p.stored) {
    p.stored = code;
    p.winner = src;
    p.winner_s = sd;
  }
  const bool same = same_depth(sd, p.front_s);
  const bool nearer = !same && sd < p.front_s;
  const bool behind = !same && !nearer && sd < p.second_s;
  // coplanar with the front surface; a nearer surface hides the pair, so it starts afresh
  p.coplanar = (p.coplanar || same) && !nearer;
  if (nearer) {
    p.second_s = p.front_s;
    p.second_code = p.front_code;
    p.second_lo = p.front_lo;
    p.second_hi = p.front_hi;
  } else if (behind) {
    p.second_s = sd;
    p.second_code = code;
    p.second_lo = lo;
    p.second_hi = hi;
  }
  // in one plane the front is the surface drawn last (kernels/audit.cl)
  if (nearer || same) {
    p.front_s = sd;
    p.front = src;
    p.front_code = code;
    p.front_lo = lo;
    p.front_hi = hi;
  }
}

void finish(const PixelState& p, const StorageFormat& fmt, bool greater, size_t i,
            AuditPixels& out) {
  const auto ahead = [greater](uint32_t behind, uint32_t front) {
    return greater ? static_cast<int64_t>(front) - behind : static_cast<int64_t>(behind) - front;
  };
  const bool covered = p.front >= 0;
  const bool lost = covered && p.winner != p.front;
  const bool tie = same_depth(p.winner_s, p.front_s);
  int64_t m = lost ? -ahead(p.front_code, p.stored) : ahead(p.second_code, p.front_code);
  if (!covered || (!lost && std::isinf(p.second_s))) m = std::numeric_limits<int32_t>::max();
  m = std::clamp<int64_t>(m, std::numeric_limits<int32_t>::min(),
                          std::numeric_limits<int32_t>::max());
  uint32_t f = 0;
  if (covered) f |= AUDIT_COVERED;
  const bool undrawn = covered && p.winner < 0;
  if (lost && !tie && !undrawn) f |= AUDIT_FIGHT;
  if (undrawn) f |= AUDIT_UNDRAWN;
  if (p.coplanar || (lost && tie)) f |= AUDIT_COPLANAR;
  if (p.discarded) f |= AUDIT_DISCARDED;
  const bool no_margin = covered && !lost && std::isinf(p.second_s);
  if (no_margin) f |= AUDIT_NO_MARGIN;
  // kernels/audit.cl's at_risk
  const auto unit = [](float x) { return std::fmin(std::fmax(x, 0.0f), 1.0f); };
  const uint32_t front_worst = fmt.encode(unit(greater ? p.front_lo : p.front_hi));
  const uint32_t second_worst = fmt.encode(unit(greater ? p.second_hi : p.second_lo));
  if (covered && !lost && !no_margin && !p.coplanar &&
      ahead(second_worst, front_worst) <= conversion_codes(fmt))
    f |= AUDIT_AT_RISK;
  out.winner[i] = static_cast<uint32_t>(p.winner);
  out.front[i] = static_cast<uint32_t>(p.front);
  out.margin[i] = static_cast<int32_t>(m);
  out.flags[i] = f;
}

}  // namespace

void AuditPixels::resize(int w, int h) {
  width = w;
  height = h;
  const size_t n = static_cast<size_t>(w) * h;
  winner.assign(n, AUDIT_NONE);
  front.assign(n, AUDIT_NONE);
  flags.assign(n, 0);
  margin.assign(n, 0);
}

AuditPixels audit_reference(const Scene& s, const AuditSetup& a) {
  const StorageFormat fmt = s.storage_format(a.pair);
  const bool greater = info(a.pair.technique).greater;
  AuditPixels out;
  out.resize(a.width, a.height);
  for (int y = 0; y < a.height; ++y) {
    const float py = static_cast<float>(y) + 0.5f;
    std::vector<size_t> row;  // the records whose y-range holds the row, in draw order
    for (size_t r = 0; r < a.records.size(); ++r)
      if (a.records[r].ymin <= py && py <= a.records[r].ymax) row.push_back(r);
    for (int x = 0; x < a.width; ++x) {
      const float px = static_cast<float>(x) + 0.5f;
      PixelState p;
      p.stored = a.clear_code;
      for (size_t r : row) take(s, a, fmt, greater, r, px, py, p);
      finish(p, fmt, greater, static_cast<size_t>(y) * a.width + x, out);
    }
  }
  return out;
}

AuditPixels audit_reference_at(const Scene& s, const AuditSetup& a,
                               const std::vector<std::pair<int, int>>& pixels,
                               const std::vector<uint32_t>& keep) {
  const StorageFormat fmt = s.storage_format(a.pair);
  const bool greater = info(a.pair.technique).greater;
  std::vector<size_t> records;
  for (size_t r = 0; r < a.records.size(); ++r)
    if (keep.empty() || std::find(keep.begin(), keep.end(), a.source[r]) != keep.end())
      records.push_back(r);
  AuditPixels out;
  out.resize(static_cast<int>(pixels.size()), 1);
  for (size_t i = 0; i < pixels.size(); ++i) {
    const float px = static_cast<float>(pixels[i].first) + 0.5f;
    const float py = static_cast<float>(pixels[i].second) + 0.5f;
    PixelState p;
    p.stored = a.clear_code;
    for (size_t r : records) take(s, a, fmt, greater, r, px, py, p);
    finish(p, fmt, greater, i, out);
  }
  return out;
}

}  // namespace depthprec
