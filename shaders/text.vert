#version 330 core
// Glyph quads from the font atlas, in pixels (y down).
layout(location = 0) in vec2 a_position;
layout(location = 1) in vec2 a_uv;
layout(location = 2) in vec4 a_colour;
uniform vec2 u_screen;
out vec2 v_uv;
out vec4 v_colour;

void main() {
  v_uv = a_uv;
  v_colour = a_colour;
  gl_Position = vec4(2.0 * a_position.x / u_screen.x - 1.0, 1.0 - 2.0 * a_position.y / u_screen.y,
                     0.0, 1.0);
}
