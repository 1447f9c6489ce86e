// The planes' vertex stage for `depthprec render`: object position to clip space with the host's
// binary32 matrices, as an application's shader would; vertex-stage log depth rewrites z_clip here
// (VERTEX_LOG 0: Gilg eq. 5; 1: three.js's fallback, logdepthbuf_vertex.glsl.js up to r162, with
// FC / 2 in the [0, 1] range WebGL lacks). The host prepends #version and the defines DEPTH_FROM
// (host/model/technique.h DepthFrom), VERTEX_LOG, DEPTH_RANGE_GL, COMPOSE_PREMULTIPLIED,
// VIEW_TRANSLATE (the absolute transform away from the world origin: the camera's view matrix
// after the model matrix) and RELATIVE_TO_EYE (Cesium's czm_translateRelativeToEye on the host's
// split world positions, interface/relative_to_eye.h); the arithmetic is the driver's.
layout(location = 0) in vec2 obj_xy;
layout(location = 1) in vec3 world_high;  // RELATIVE_TO_EYE: per vertex, set per plane
layout(location = 2) in vec3 world_low;

uniform mat4 P;
uniform mat4 MV;  // P * MV when COMPOSE_PREMULTIPLIED
uniform mat4 V;   // VIEW_TRANSLATE: the view matrix, the camera's translation
uniform vec3 eye_high;
uniform vec3 eye_low;

#include "host/render/shaders/vertex_log.glsl"

void main() {
#if RELATIVE_TO_EYE
  vec3 eye = (world_high - eye_high) + (world_low - eye_low);
  vec4 clip = P * vec4(eye, 1.0);
#else
  vec4 obj = vec4(obj_xy, 0.0, 1.0);
#if COMPOSE_PREMULTIPLIED
  vec4 clip = MV * obj;
#elif VIEW_TRANSLATE
  vec4 clip = P * (V * (MV * obj));
#else
  vec4 clip = P * (MV * obj);
#endif
#endif
  clip.z = vertex_log_z(clip);
  gl_Position = clip;
}
