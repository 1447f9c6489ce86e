// One `depthprec shadow` measurement as JSON records, one per cascade: the set-up it derived
// (texel, depth range, the filter's reach), the proven biases and their terms, the witnessed
// ones the emulation found below them, the gaps and each engine's settings (docs/shadow.md).
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "host/shadow/shadow_emulator.h"
#include "host/shadow/shadow_engines.h"

namespace depthprec {

struct ShadowRequest {
  ShadowSetup setup;
  std::string bound_model = "binary32";
  std::vector<std::string> engines;  // empty: all
  ShadowSampling sampling;
  bool emulate = true;  // false: the bound alone, no device
};

// The set-up's own description for the JSON header.
nlohmann::json shadow_header(const ShadowRequest& r);
// The record of one cascade; rt may be null when r.emulate is false.
nlohmann::json shadow_record(OpenClRuntime* rt, const ShadowRequest& r, size_t cascade);

}  // namespace depthprec
