#version 330 core
// Floor markers (goal ring, waypoints, source-of-influence ring): instanced squares lying on the floor.
layout(location = 0) in vec2 a_corner;            // [-1, 1]^2
layout(location = 1) in vec4 i_centre_outer;      // centre on the floor (xyz), outer radius (w)
layout(location = 2) in vec4 i_colour_inner;      // colour (rgb), inner radius (a)
uniform mat4 u_view_proj;
out vec3 v_world;
out vec2 v_local;  // metres from the centre
out vec3 v_colour;
out vec2 v_radii;
void main() {
  float r = i_centre_outer.w;
  v_local = a_corner * r;
  v_world = i_centre_outer.xyz + vec3(v_local.x, 0.004, v_local.y);
  v_colour = i_colour_inner.rgb;
  v_radii = vec2(i_colour_inner.a, r);
  gl_Position = u_view_proj * vec4(v_world, 1.0);
}
