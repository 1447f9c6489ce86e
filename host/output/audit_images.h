// The audit's pictures of one set-up (docs/audit.md "Images"): the view with its fighting pixels
// marked, and the margin heat map: how many stored codes each pixel's front surface is ahead of
// the next surface behind it.
#pragma once

#include <cstdint>
#include <vector>

#include "host/audit/audit.h"

namespace depthprec {

// RGB, rows from the top. The view: surfaces grey by how squarely they face the eye, fighting
// pixels red, pixels where two surfaces share a plane blue, nothing drawn black.
std::vector<uint8_t> fight_image(const SetupAudit& audit);
// The margin: red where it fights, then from yellow (1 code ahead) to green (2^24 codes and more)
// on a log scale; surfaces with nothing behind them grey, nothing drawn black.
std::vector<uint8_t> margin_image(const SetupAudit& audit);

}  // namespace depthprec
