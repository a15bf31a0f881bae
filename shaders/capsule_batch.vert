#version 330 core
// Capsules many to an instance (the light bodies of a crowd): the mesh holds u_copies copies of the unit
// capsule, a_copy telling which, and copy c of instance i is capsule u_first + i * u_copies + c, read from
// a buffer texture of three texels per capsule (end A and radius, end B and glow, colour). On llvmpipe each
// instance of a draw costs about as much as shading a few hundred vertices: thousands of one-capsule
// instances cost more than their triangles.
#include "capsule_frame.glsl"

layout(location = 0) in vec3 a_offset;
layout(location = 1) in float a_end;
layout(location = 2) in float a_copy;

uniform samplerBuffer u_capsules;
uniform int u_first;
uniform int u_copies;
uniform mat4 u_view_proj;

out vec3 v_world;
out vec3 v_normal;
out vec3 v_colour;
out float v_glow;

void main() {
  int k = 3 * (u_first + gl_InstanceID * u_copies + int(a_copy));
  vec4 a_radius = texelFetch(u_capsules, k);
  vec4 b_glow = texelFetch(u_capsules, k + 1);
  place_capsule_vertex(a_radius.xyz, b_glow.xyz, a_radius.w, a_offset, a_end, v_world, v_normal);
  v_colour = texelFetch(u_capsules, k + 2).rgb;
  v_glow = b_glow.w;
  gl_Position = u_view_proj * vec4(v_world, 1.0);
}
