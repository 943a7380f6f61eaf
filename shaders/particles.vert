#version 330 core
// Particles as shaded discs at true size: one quad per particle (instanced), its corners pushed
// one pixel beyond the disc for the anti-aliased edge. Positions are in pixels, y down.
layout(location = 0) in vec2 a_corner;  // (-1, -1) .. (1, 1)
layout(location = 1) in vec3 a_disc;    // centre x, y (px), radius (px)
layout(location = 2) in vec3 a_colour;  // the colour map's colour for the particle's value
uniform vec2 u_screen;                  // framebuffer size (px)
out vec2 v_offset;                      // from the disc's centre (px)
flat out float v_radius;
flat out float v_rim;                   // how much darker the rim is than the centre
flat out vec3 v_colour;

void main() {
  float extent = a_disc.z + 1.0;
  v_offset = a_corner * extent;
  v_radius = a_disc.z;
  // A disc a few pixels across is a dot: shading would only darken its colour; larger discs are
  // shaded as spheres so that touching particles stay apart.
  v_rim = 0.45 * clamp((a_disc.z - 2.0) / 6.0, 0.0, 1.0);
  v_colour = a_colour;
  vec2 p = a_disc.xy + v_offset;
  gl_Position = vec4(2.0 * p.x / u_screen.x - 1.0, 1.0 - 2.0 * p.y / u_screen.y, 0.0, 1.0);
}
