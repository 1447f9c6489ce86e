// The audit's report (docs/audit.md "Output"): JSON with every set-up and pair, a CSV row per
// (set-up, pair), or text tables.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "host/audit/audit.h"

namespace depthprec {

struct AuditReport {
  nlohmann::json header;  // output_header's, plus the file, camera and image
  const SceneGeometry* geometry = nullptr;
  std::vector<SetupAudit> setups;
  std::vector<std::string> pngs, margin_pngs;  // per set-up, "" for none
  nlohmann::json rendered;                     // per set-up the rendering's agreement, or null
};

nlohmann::json audit_json(const AuditReport& report, bool timing);
// format: "text", "markdown" or "csv"
std::string audit_text(const AuditReport& report, const std::string& format, bool timing);

}  // namespace depthprec
