// Fragment-stage depth (DEPTH_FROM 2), shared by the planes' and the audit's fragment shaders:
// gl_FragDepth from the perspective-correct eye distance w = 1 / gl_FragCoord.w (FRAG_DEPTH,
// host/model/technique.h FragmentDepth); the engines' forms (4 three.js, 5 Cesium) are their
// shaders' lines with their varying taken at that w, as the emulation takes it.
uniform float near_plane;
uniform float far_plane;
uniform float depth_range;  // far - near
uniform float log_k;
uniform float log_L;
uniform float threejs_fc;       // three.js's logDepthBufFC
uniform float cesium_far1;      // Cesium's czm_farDepthFromNearPlusOne
uniform float cesium_inv_log2;  // Cesium's czm_oneOverLog2FarDepthFromNearPlusOne

void write_frag_depth() {
#if DEPTH_FROM == 2
  float w = 1.0 / gl_FragCoord.w;
#if FRAG_DEPTH == 1
  gl_FragDepth = (w - near_plane) / depth_range;
#elif FRAG_DEPTH == 2
  gl_FragDepth = w / far_plane;
#elif FRAG_DEPTH == 4
  float vFragDepth = 1.0 + w;
  gl_FragDepth = log2(vFragDepth) * threejs_fc * 0.5;
#elif FRAG_DEPTH == 5
  float depth = (w - near_plane) + 1.0;
  if (depth <= 0.9999999 || depth > cesium_far1) discard;
  gl_FragDepth = log2(depth) * cesium_inv_log2;
#else
  gl_FragDepth = log(log_k * w + 1.0) / log_L;
#endif
#endif
}
