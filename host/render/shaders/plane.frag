// The planes' fragment stage for `depthprec render`: a flat colour (the host picks the channel
// each pass writes), and for the fragment-depth techniques gl_FragDepth from the perspective-
// correct eye distance w = 1 / gl_FragCoord.w. Defines as in plane.vert, plus FRAG_DEPTH
// (host/model/technique.h FragmentDepth).
uniform vec4 colour;
uniform float near_plane;
uniform float far_plane;
uniform float depth_range;  // far - near
uniform float log_k;
uniform float log_L;

layout(location = 0) out vec4 out_colour;

void main() {
#if DEPTH_FROM == 2
  float w = 1.0 / gl_FragCoord.w;
#if FRAG_DEPTH == 1
  gl_FragDepth = (w - near_plane) / depth_range;
#elif FRAG_DEPTH == 2
  gl_FragDepth = w / far_plane;
#else
  gl_FragDepth = log(log_k * w + 1.0) / log_L;
#endif
#endif
  out_colour = colour;
}
