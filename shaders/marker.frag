#version 330 core
// A ring (inner radius > 0) or a disc (inner radius 0), lit and shadowed like the floor.
#include "lighting.glsl"
in vec3 v_world;
in vec2 v_local;
in vec3 v_colour;
in vec2 v_radii;
out vec4 frag_colour;
void main() {
  float d = length(v_local);
  if (d > v_radii.y || d < v_radii.x) discard;
  vec3 colour = shade(v_colour, v_world, vec3(0.0, 1.0, 0.0));
  frag_colour = vec4(apply_fog(colour, v_world), 1.0);
}
