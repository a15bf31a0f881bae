#version 330 core
// Lit, shadowed surface for capsules and boxes; the source of influence glows magenta at its rim.
#include "lighting.glsl"

in vec3 v_world;
in vec3 v_normal;
in vec3 v_colour;
in float v_glow;

uniform vec3 u_source_colour;

out vec4 frag_colour;

void main() {
  vec3 n = normalize(v_normal);
  vec3 colour = shade(v_colour, v_world, n);
  if (v_glow > 0.0) {
    float rim = 1.0 - abs(dot(n, normalize(u_eye - v_world)));
    colour = mix(colour, u_source_colour, clamp(rim * rim * v_glow, 0.0, 0.9));
  }
  frag_colour = vec4(apply_fog(colour, v_world), 1.0);
}
