#version 330 core
// Instanced capsules (bones, balls, the goal pole). The mesh is a unit-radius capsule of zero length:
// each vertex is an offset from one of the two cap centres (a_end 0: end A, 1: end B) in a frame whose
// Y axis is the capsule's axis. Per instance: both ends, the radius, the colour and the source glow.
layout(location = 0) in vec3 a_offset;
layout(location = 1) in float a_end;
layout(location = 2) in vec4 i_a_radius;  // end A (xyz), radius (w)
layout(location = 3) in vec4 i_b_glow;    // end B (xyz), source-of-influence glow 0..1 (w)
layout(location = 4) in vec3 i_colour;

uniform mat4 u_view_proj;

out vec3 v_world;
out vec3 v_normal;
out vec3 v_colour;
out float v_glow;

void main() {
  vec3 a = i_a_radius.xyz;
  vec3 b = i_b_glow.xyz;
  vec3 axis = b - a;
  float len = length(axis);
  vec3 y = len > 1e-6 ? axis / len : vec3(0.0, 1.0, 0.0);
  vec3 helper = abs(y.y) < 0.99 ? vec3(0.0, 1.0, 0.0) : vec3(1.0, 0.0, 0.0);
  vec3 x = normalize(cross(helper, y));
  vec3 z = cross(x, y);
  vec3 n = mat3(x, y, z) * a_offset;
  v_world = mix(a, b, a_end) + n * i_a_radius.w;
  v_normal = n;
  v_colour = i_colour;
  v_glow = i_b_glow.w;
  gl_Position = u_view_proj * vec4(v_world, 1.0);
}
