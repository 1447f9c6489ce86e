// `audit --source rendered`: the same geometry, camera and set-up drawn by the system's OpenGL
// (host/render/shaders/audit.vert, audit.frag), each pixel's winning triangle read back, and its
// fights found as the emulation finds them (against the exact front surface), so the two agree
// pixel for pixel or show where they do not.
#pragma once

#include <nlohmann/json.hpp>

#include "host/audit/audit.h"
#include "host/render/gl_context.h"

namespace depthprec {

// The winning triangle per pixel (row-major from the bottom-left; AUDIT_NONE where none).
std::vector<uint32_t> render_winners(GlContext& gl, const Scene& scene, const EvalPair& pair,
                                     const SceneGeometry& geometry, const AuditCamera& camera);

// The rendering of frame 0 against audit (the emulation's): renderer, pixels, winner_agree and
// fight_agree, the pixels whose winners or fight verdicts differ by why (winners_differ,
// fights_differ: seam, coplanar, at_risk, tie, edge, other; fights_missed: the rendered fights the
// emulation did not call fights, sorted alike), fighting_pixels (rendered; a neighbour of the front
// surface on its own surface is no fight) and fighting_pixels_emulated, and the first pixels whose
// winners differ.
nlohmann::json render_audit(GlContext& gl, const Scene& scene, const EvalPair& pair,
                            const SceneGeometry& geometry, const AuditCamera& camera,
                            const SetupAudit& audit);

}  // namespace depthprec
