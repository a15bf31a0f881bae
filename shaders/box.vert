#version 330 core
// Instanced boxes (obstacle bars, posts, boards): a unit cube centred at the origin, placed by a
// per-instance model matrix (rotation about Y and scale, so normals transform by the inverse scale).
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
layout(location = 2) in vec4 i_model0;
layout(location = 3) in vec4 i_model1;
layout(location = 4) in vec4 i_model2;
layout(location = 5) in vec4 i_model3;
layout(location = 6) in vec4 i_colour_glow;  // albedo (rgb), source glow (a)

uniform mat4 u_view_proj;

out vec3 v_world;
out vec3 v_normal;
out vec3 v_colour;
out float v_glow;

void main() {
  mat4 model = mat4(i_model0, i_model1, i_model2, i_model3);
  vec4 world = model * vec4(a_position, 1.0);
  v_world = world.xyz;
  v_normal = transpose(inverse(mat3(model))) * a_normal;
  v_colour = i_colour_glow.rgb;
  v_glow = i_colour_glow.a;
  gl_Position = u_view_proj * world;
}
