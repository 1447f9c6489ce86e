// A receiver sample: its world position on the plane (binary64, rounded to binary32 as a varying
// is; (origin + u du + v dv) / (c0 + u c1 + v c2), c = (1, 0, 0) for a directional light), moved
// along its normal, through the light's rows and divided by w; then every texel whose centre lies
// closer than the filter's reach on each axis, compared as the depth test would (nearer the
// light passes). Writes 1 where one of them shadows the sample: acne.
flat in ivec2 cell;
uniform int grid;
uniform dvec3 origin, du, dv, denom;
uniform vec2 base;
uniform vec3 normal;
uniform float normal_offset, receiver_offset, reach, half_res;
uniform bool reversed;
uniform vec4 light_x, light_y, light_z, light_w;
uniform sampler2D depth_map;  // the map's texels from window_origin on
uniform ivec2 window_origin;
layout(location = 0) out float acne;

void main() {
  const double u = double(base.x) + double(cell.x) / double(grid);
  const double v = double(base.y) + double(cell.y) / double(grid);
  const vec3 p =
      vec3((origin + u * du + v * dv) / (denom.x + u * denom.y + v * denom.z)) + normal_offset * normal;
  const vec4 q = vec4(p, 1.0);
  const float cw = dot(light_w, q);
  const vec2 w = vec2(dot(light_x, q) / cw, dot(light_y, q) / cw) * half_res + half_res;
  const float ref = dot(light_z, q) / cw + (reversed ? receiver_offset : -receiver_offset);
  const ivec2 lo = ivec2(ceil(w - reach - 0.5)), hi = ivec2(floor(w + reach - 0.5));
  float found = 0.0;
  for (int j = lo.y; j <= hi.y; ++j) {
    if (!(abs(float(j) + 0.5 - w.y) < reach)) continue;
    for (int i = lo.x; i <= hi.x; ++i) {
      if (!(abs(float(i) + 0.5 - w.x) < reach)) continue;
      const float s = texelFetch(depth_map, ivec2(i, j) - window_origin, 0).r;
      if (reversed ? ref < s : ref > s) found = 1.0;
    }
  }
  acne = found;
}
