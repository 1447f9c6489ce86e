// The scene audit's per-pixel pass (interface/audit_layout.h) in plain C++: the reference the
// kernel (kernels/audit.cl) is checked against, pixel for pixel, and what the audit's fixes re-run
// on a pair's pixels. Slow: every record whose y-range holds the row, per pixel.
#pragma once

#include <cstdint>
#include <vector>

#include "host/audit/audit_setup.h"

namespace depthprec {

// Per pixel, row-major from the bottom-left (interface/audit_layout.h audit_pixels' outputs).
struct AuditPixels {
  int width = 0, height = 0;
  std::vector<uint32_t> winner, front, flags;
  std::vector<int32_t> margin;
  void resize(int w, int h);
};

AuditPixels audit_reference(const Scene& scene, const AuditSetup& setup);

// The same at the listed pixels only (x, y pairs), drawing only the records whose source
// triangle `keep` accepts (every record when keep is empty): one entry per listed pixel. A record
// with a bias has it added to its fragments' depth (the fixes' depth bias).
AuditPixels audit_reference_at(const Scene& scene, const AuditSetup& setup,
                               const std::vector<std::pair<int, int>>& pixels,
                               const std::vector<uint32_t>& keep = {});

}  // namespace depthprec
