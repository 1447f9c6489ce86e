// The planes' fragment stage for `depthprec render`: a flat colour (the host picks the channel
// each pass writes), and for the fragment-depth techniques gl_FragDepth from the perspective-
// correct eye distance w = 1 / gl_FragCoord.w. Defines as in plane.vert, plus FRAG_DEPTH
// (host/model/technique.h FragmentDepth). The engines' forms (4 three.js, 5 Cesium) are their
// shaders' lines with their varying taken at that w, as the emulation takes it.
uniform vec4 colour;
uniform float near_plane;
uniform float far_plane;
uniform float depth_range;  // far - near
uniform float log_k;
uniform float log_L;
uniform float threejs_fc;       // three.js's logDepthBufFC
uniform float cesium_far1;      // Cesium's czm_farDepthFromNearPlusOne
uniform float cesium_inv_log2;  // Cesium's czm_oneOverLog2FarDepthFromNearPlusOne

layout(location = 0) out vec4 out_colour;

void main() {
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
  out_colour = colour;
}
