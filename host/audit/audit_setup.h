// The host half of the scene audit (docs/audit.md): the camera, and per set-up (technique, format,
// depth range under the scene's pipeline) every draw's vertex stage, clipping and triangle set-up
// in draw order, as records the per-pixel pass reads (kernels/audit.cl, or the host reference), the
// exact eye-space plane of every triangle, and the records binned into tiles.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "host/model/frame_setup.h"
#include "host/model/scene.h"
#include "host/model/scene_geometry.h"
#include "host/mts/triangle_setup.h"

namespace depthprec {

struct AuditCamera {
  std::string description;      // how it was given: "--eye ... --target ..." or "camera main"
  Mat4d view{};                 // world to eye, binary64, rigid
  std::array<double, 3> eye{};  // its position in the world
  double fov_y_deg = 0;
  int width = 0, height = 0;  // the image, pixels
};

// A camera at eye looking at target with up roughly up; throws InputError when eye and target
// coincide, up is parallel to the view direction, or a value is not finite.
AuditCamera look_at_camera(const std::array<double, 3>& eye, const std::array<double, 3>& target,
                           const std::array<double, 3>& up, double fov_y_deg, int width,
                           int height);
// The glTF camera's node transform (scale removed) as the view; its yfov.
AuditCamera gltf_view(const GltfCamera& camera, int width, int height);

// What the GPU gets per draw (host/model/vertex_stage.h; docs/audit.md "Vertex stage"): the
// draw's world matrix and the camera's view, from the one decision every vertex stage takes
// (vertex_stage), under the pipeline's transform, compose and matrix_precision. `render` uploads
// the same matrices.
VertexStage draw_vertex_stage(const Scene& scene, const ProbeConstants& pc, const Draw& draw,
                              const AuditCamera& camera);

// The scene the audit's set-ups run under: viewport, kernel and field of view from the camera.
Scene audit_scene(Scene scene, const AuditCamera& camera);

struct AuditSetup {
  EvalPair pair;
  ProbeConstants pc;
  int width = 0, height = 0, tiles_x = 0, tiles_y = 0;
  std::vector<SetupTriangle> records;  // the rasterised triangles in draw order (fans in place)
  std::vector<uint32_t> source;        // each record's scene-wide triangle
  std::vector<std::array<float, 3>> window_depths;  // each record's vertices' window depth
  // Each record's bound on how far another conformant implementation's depth lies from the
  // emulated one (host/audit/depth_tolerance.h), AUDIT_TOL_WORDS floats each, rounded up.
  std::vector<float> tolerance;
  // Per scene-wide triangle its exact eye-space plane n.p = c (nx, ny, nz, c), binary64
  // (interface/audit_layout.h), and the pixel ray's constants (hw, hh, sx, sy).
  std::vector<std::array<double, 4>> planes;
  std::array<double, 4> ray{};
  // Per tile (row-major from the bottom-left) its first entry in bin_records; tiles + 1 entries.
  std::vector<uint32_t> bins, bin_records;
  uint64_t culled = 0, clipped = 0, non_finite = 0;  // triangles the vertex stage dropped or cut
  uint32_t clear_code = 0;                           // the cleared depth buffer's code
};

AuditSetup audit_setup(const Scene& scene, const EvalPair& pair, const SceneGeometry& geometry,
                       const AuditCamera& camera);

// The records as the kernel reads them: MTS_TRI_STRIDE floats each (interface/mts_layout.h).
std::vector<float> packed_records(const AuditSetup& setup);

// The pixel ray's constants (hw, hh, sx, sy; interface/audit_layout.h): half the viewport, the
// projection's x and y scales in the matrix precision.
std::array<double, 4> pixel_ray(const Scene& scene, const ProbeConstants& pc);
// Per scene-wide triangle its exact eye-space plane (nx, ny, nz, c) seen from the camera: the
// binary32 object positions through the binary64 world and view matrices, never rounded. The
// same for every set-up.
std::vector<std::array<double, 4>> exact_planes(const SceneGeometry& geometry,
                                                const AuditCamera& camera);

// The exact eye depth of the plane (nx, ny, nz, c) along the ray of window pixel centre (px, py),
// in binary64 as kernels/audit.cl computes it.
double ray_depth(const std::array<double, 4>& ray, const std::array<double, 4>& plane, float px,
                 float py);

}  // namespace depthprec
