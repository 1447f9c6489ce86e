// The audit's fragment stage for `depthprec audit --source rendered`: the technique's depth
// (host/render/shaders/frag_depth.glsl) and, as an integer colour, which triangle this is: the
// draw's first scene-wide triangle plus gl_PrimitiveID, plus one (0 is the cleared "nothing").
uniform uint first_triangle;
#include "host/render/shaders/frag_depth.glsl"

layout(location = 0) out uint triangle;

void main() {
  write_frag_depth();
  triangle = first_triangle + uint(gl_PrimitiveID) + 1u;
}
