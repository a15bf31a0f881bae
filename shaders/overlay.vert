#version 330 core
// Unlit, translucent overlays drawn over the scene (support polygons and centres of mass on the floor).
layout(location = 0) in vec3 a_position;  // world
layout(location = 1) in vec4 a_colour;    // rgba, straight alpha
uniform mat4 u_view_proj;
out vec4 v_colour;
void main() {
  v_colour = a_colour;
  gl_Position = u_view_proj * vec4(a_position, 1.0);
}
