#version 330 core
// Velocity arrows (instanced): a unit arrow mesh placed along each arrow's vector. A mesh vertex
// says how far along it sits (in arrow lengths and head lengths) and across (in shaft and head
// half-widths), so that heads keep their shape whatever the arrow's length.
layout(location = 0) in vec4 a_mesh;    // along: x * length + y * head length;
                                        // across: z * shaft half-width + w * head half-width
layout(location = 1) in vec4 a_arrow;   // tail x, y (px); vector x, y (px, y down)
layout(location = 2) in vec3 a_size;    // shaft half-width, head length, head half-width (px)
layout(location = 3) in vec3 a_colour;
uniform vec2 u_screen;
out vec4 v_colour;

void main() {
  float len = length(a_arrow.zw);
  vec2 dir = len > 0.0 ? a_arrow.zw / len : vec2(1.0, 0.0);
  vec2 across = vec2(-dir.y, dir.x);
  vec2 p = a_arrow.xy + dir * (a_mesh.x * len + a_mesh.y * a_size.y) +
           across * (a_mesh.z * a_size.x + a_mesh.w * a_size.z);
  v_colour = vec4(a_colour, 1.0);
  gl_Position = vec4(2.0 * p.x / u_screen.x - 1.0, 1.0 - 2.0 * p.y / u_screen.y, 0.0, 1.0);
}
