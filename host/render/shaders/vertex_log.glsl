// Vertex-stage log depth (DEPTH_FROM 1), shared by the planes' and the audit's vertex shaders:
// z_clip from Gilg eq. 5 (VERTEX_LOG 0) or three.js's fallback (VERTEX_LOG 1,
// logdepthbuf_vertex.glsl.js up to r162, with FC / 2 in the [0, 1] range WebGL lacks); other
// techniques keep the projection's z_clip.
uniform float log_k;
uniform float log_L;
uniform float threejs_fc;  // three.js's logDepthBufFC

float vertex_log_z(vec4 clip) {
#if DEPTH_FROM == 1 && VERTEX_LOG == 1
  float t = log2(max(1e-6, clip.w + 1.0));
#if DEPTH_RANGE_GL
  clip.z = t * threejs_fc - 1.0;
#else
  clip.z = t * (0.5 * threejs_fc);
#endif
  clip.z *= clip.w;
#elif DEPTH_FROM == 1
  float t = log(log_k * clip.w + 1.0);
#if DEPTH_RANGE_GL
  clip.z = ((2.0 * t) / log_L - 1.0) * clip.w;
#else
  clip.z = (t / log_L) * clip.w;
#endif
#endif
  return clip.z;
}
