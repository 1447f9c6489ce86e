#include "host/output/audit_images.h"

#include <algorithm>
#include <cmath>

#include "interface/audit_layout.h"

namespace depthprec {

namespace {

// Pixel i of the audit (rows from the bottom) into rgb (rows from the top).
template <class Colour>
std::vector<uint8_t> image(const SetupAudit& a, Colour colour) {
  const AuditPixels& p = a.image;
  std::vector<uint8_t> rgb(static_cast<size_t>(p.width) * p.height * 3);
  for (int y = 0; y < p.height; ++y)
    for (int x = 0; x < p.width; ++x) {
      const size_t i = static_cast<size_t>(y) * p.width + x;
      const size_t o = (static_cast<size_t>(p.height - 1 - y) * p.width + x) * 3;
      const std::array<uint8_t, 3> c = colour(i);
      std::copy(c.begin(), c.end(), rgb.begin() + o);
    }
  return rgb;
}

}  // namespace

std::vector<uint8_t> fight_image(const SetupAudit& a) {
  return image(a, [&a](size_t i) -> std::array<uint8_t, 3> {
    const uint32_t f = a.image.flags[i];
    if (f & AUDIT_FIGHT) return {255, 0, 0};
    if (f & AUDIT_COPLANAR) return {40, 90, 255};
    if (f & AUDIT_AT_RISK) return {255, 150, 0};
    if (!(f & AUDIT_COVERED)) return {0, 0, 0};
    const uint8_t s = a.shade[i];
    return {s, s, s};
  });
}

std::vector<uint8_t> margin_image(const SetupAudit& a) {
  return image(a, [&a](size_t i) -> std::array<uint8_t, 3> {
    const uint32_t f = a.image.flags[i];
    if (f & AUDIT_FIGHT) return {255, 0, 0};
    if (f & AUDIT_COPLANAR) return {40, 90, 255};
    if (!(f & AUDIT_COVERED)) return {0, 0, 0};
    if (f & AUDIT_NO_MARGIN) {
      const uint8_t s = static_cast<uint8_t>(a.shade[i] / 2);
      return {s, s, s};
    }
    const int32_t m = a.image.margin[i];
    if (m <= 0) return {255, 0, 0};  // a tie the draw order decided
    const double t = std::min(1.0, std::log2(static_cast<double>(m)) / 24.0);
    return {static_cast<uint8_t>(255 * (1 - t)), static_cast<uint8_t>(230 - 90 * t), 0};
  });
}

}  // namespace depthprec
