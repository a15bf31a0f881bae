#version 330 core
// Skinned bodies (assets/character.glb, or our body built for another skeleton): linear blend skinning,
//   skin(v) = sum_i weight_i * S[joint_i],   S[j] = W[j] * inverse_bind[j]   (engine/interop/skinned_mesh.h),
// with the S matrices of the character being drawn in a uniform block. Positions and normals are in bind
// space. The normal goes through the blended matrix's upper 3x3: every S is rigid, and a blend of nearby
// rotations stays close enough to one that normalizing in the fragment shader is all it needs.
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
layout(location = 2) in ivec4 a_joints;
layout(location = 3) in vec4 a_weights;

const int kMaxSkinJoints = 128;  // app/render/skinned_body.h
layout(std140) uniform Skin {
  mat4 u_skin[kMaxSkinJoints];
};

uniform mat4 u_view_proj;
uniform vec3 u_colour;
uniform float u_glow;  // source of influence: rim glow 0..1

out vec3 v_world;
out vec3 v_normal;
out vec3 v_colour;
out float v_glow;

void main() {
  mat4 s = a_weights.x * u_skin[a_joints.x] + a_weights.y * u_skin[a_joints.y] +
           a_weights.z * u_skin[a_joints.z] + a_weights.w * u_skin[a_joints.w];
  vec4 world = s * vec4(a_position, 1.0);
  v_world = world.xyz;
  v_normal = mat3(s) * a_normal;
  v_colour = u_colour;
  v_glow = u_glow;
  gl_Position = u_view_proj * world;
}
