// The planes' fragment stage for `depthprec render`: a flat colour (the host picks the channel
// each pass writes), and for the fragment-depth techniques gl_FragDepth from the perspective-
// correct eye distance w = 1 / gl_FragCoord.w. Defines as in plane.vert, plus FRAG_DEPTH
// (host/model/technique.h FragmentDepth). The engines' forms (4 three.js, 5 Cesium) are their
// shaders' lines with their varying taken at that w, as the emulation takes it.
uniform vec4 colour;
#include "host/render/shaders/frag_depth.glsl"

layout(location = 0) out vec4 out_colour;

void main() {
  write_frag_depth();
  out_colour = colour;
}
