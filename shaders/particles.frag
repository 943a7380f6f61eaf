#version 330 core
// A sphere lit from the viewer: the exact colour-map colour at the centre, darker to the rim;
// the edge's coverage goes into alpha (one pixel wide) for anti-aliasing.
in vec2 v_offset;
flat in float v_radius;
flat in float v_rim;
flat in vec3 v_colour;
out vec4 o_colour;

void main() {
  float d = length(v_offset);
  float coverage = clamp(v_radius - d + 0.5, 0.0, 1.0);
  if (coverage <= 0.0) discard;
  float r = min(d / v_radius, 1.0);
  float nz = sqrt(1.0 - r * r);  // the sphere's normal towards the viewer
  o_colour = vec4(v_colour * (1.0 - v_rim * (1.0 - nz)), coverage);
}
