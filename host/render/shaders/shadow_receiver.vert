// One point per receiver sample of `shadow --source rendered`: vertex k lands on pixel
// (k % grid, k / grid) of a grid x grid target, where the fragment stage looks it up.
uniform int grid;
flat out ivec2 cell;

void main() {
  cell = ivec2(gl_VertexID % grid, gl_VertexID / grid);
  gl_Position = vec4((vec2(cell) + 0.5) / float(grid) * 2.0 - 1.0, 0.0, 1.0);
  gl_PointSize = 1.0;
}
