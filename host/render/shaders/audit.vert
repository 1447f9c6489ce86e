// The audit's vertex stage for `depthprec audit --source rendered`: object position to clip space
// with the matrices the emulation uses (host/audit/audit_setup.h draw_vertex_stage,
// host/model/vertex_stage.h): P (V (M p)) under the absolute transform (VIEW_ON_GPU:
// model_then_view), P (MV p) camera-relative, or (P V M) p premultiplied; then vertex-stage log
// depth. The arithmetic is the driver's.
layout(location = 0) in vec3 position;

uniform mat4 P;
uniform mat4 FIRST;   // M, MV, or P * V * M
uniform mat4 SECOND;  // V under VIEW_ON_GPU

#include "host/render/shaders/vertex_log.glsl"

void main() {
  vec4 p = vec4(position, 1.0);
#if COMPOSE_PREMULTIPLIED
  vec4 clip = FIRST * p;
#elif VIEW_ON_GPU
  vec4 clip = P * (SECOND * (FIRST * p));
#else
  vec4 clip = P * (FIRST * p);
#endif
  clip.z = vertex_log_z(clip);
  gl_Position = clip;
}
