#version 330 core
// The floor: neutral grey with a 1 m grid (darker, wider lines every 5 m), antialiased by the screen-space
// derivative of the position and faded out with distance before it can alias, lit and shadowed.
#include "lighting.glsl"

in vec3 v_world;
uniform vec3 u_ground;
uniform vec3 u_grid_line;
out vec4 frag_colour;

float grid_line(vec2 p, float spacing, float width_px) {
  vec2 q = p / spacing;
  vec2 w = fwidth(q);
  vec2 d = abs(fract(q - 0.5) - 0.5) / max(w, vec2(1e-5));  // distance to the nearest line, in pixels
  return 1.0 - clamp(min(d.x, d.y) - 0.5 * width_px + 0.5, 0.0, 1.0);
}

void main() {
  vec2 p = v_world.xz;
  float minor = grid_line(p, 1.0, 1.0);
  float major = grid_line(p, 5.0, 2.0);
  float fade = 1.0 - clamp(max(fwidth(p).x, fwidth(p).y) * 4.0, 0.0, 1.0);  // lines vanish where a pixel spans >= 25 cm
  vec3 albedo = mix(u_ground, u_grid_line, max(minor * 0.7, major) * fade);
  vec3 colour = shade(albedo, v_world, vec3(0.0, 1.0, 0.0));
  frag_colour = vec4(apply_fog(colour, v_world), 1.0);
}
