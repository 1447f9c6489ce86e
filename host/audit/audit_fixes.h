// The cheapest fixes of each fighting pair (docs/audit.md "Fixes"), each checked by re-running
// the pair's sampled pixels through the host reference with only the triangles fighting there:
// the nearest near plane that resolves them, the other set-ups that do, the constant depth bias on
// the front surface that does (the API's rule, host/bias/bias_rule.h), and the geometry offset
// the set-up's MTS asks for at the pair's depth.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "host/audit/audit.h"

namespace depthprec {

struct FixRequest {
  std::vector<EvalPair> alternatives;  // set-ups tried in place of the audited one
  bool mts = true;                     // measure the MTS at each pair's depth (OpenCL)
  std::function<void(const std::string&)> log;
};

// measurement: the scene the MTS is measured in (the audit's near, far and pipeline, the MTS
// measurement's kernel and sampling). runtime may be null when request.mts is false.
// frames: the audit's views (a pair's fixes are checked in the view its sample comes from).
void add_fixes(OpenClRuntime* runtime, const Scene& scene, const Scene& measurement,
               const SceneGeometry& geometry, const std::vector<AuditCamera>& frames,
               SetupAudit& audit, const FixRequest& request);

// The largest constant bias tried, in API units: beyond it a bias moves the surface by more than
// any engine sets (D3D's DepthBias is an integer; engines' decals use a few to a few hundred).
constexpr double kMaxBiasUnits = 4096;

// The default alternatives: standard, reversed and log_threejs in unorm24 and float32 (each in its
// own depth range), less the audited pair. Under the absolute transform, away from the world
// origin the audited pair under camera_relative too (FixRequest::transform_fix).
std::vector<EvalPair> default_alternatives(const Scene& scene, const EvalPair& audited);

}  // namespace depthprec
