// The caster of `shadow --source rendered`: a world position through the light's rows (x / w and
// y / w in normalized device coordinates, z / w the window depth in [0, 1] under glClipControl's
// zero-to-one; a directional light's w is 1).
layout(location = 0) in vec3 world;
uniform vec4 light_x, light_y, light_z, light_w;

void main() {
  const vec4 p = vec4(world, 1.0);
  gl_Position = vec4(dot(light_x, p), dot(light_y, p), dot(light_z, p), dot(light_w, p));
}
