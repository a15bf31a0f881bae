// A skinned triangle mesh bound to a Skeleton: what the renderer draws and what glTF files carry.
//
// Plain data, no GL. Vertex v is skinned (linear blend skinning) by
//   skin(v) = sum_i weights[v][i] * S[joints[v][i]],   S[j] = W[j] * inverse_bind[j],
// where W[j] = translate(world position of j) * mat4_cast(world rotation of j) comes from
// forward_kinematics for the pose being drawn (see skinning_matrices below). positions and normals are in
// bind space: for the bind pose, S[j] is the identity for every joint.
#pragma once

#include <cstdint>
#include <glm/gtc/quaternion.hpp>
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>
#include <vector>

#include "engine/motion/skeleton.h"

namespace prep {

struct SkinnedMesh {
  std::vector<glm::vec3> positions;     // bind-space positions, metres
  std::vector<glm::vec3> normals;       // unit length, one per position
  std::vector<glm::ivec4> joints;       // four skeleton joint indices per vertex (unused slots: 0 with weight 0)
  std::vector<glm::vec4> weights;       // four weights per vertex, summing to 1
  std::vector<std::uint32_t> indices;   // triangles, counter-clockwise seen from outside
  std::vector<glm::mat4> inverse_bind;  // one per skeleton joint (index = skeleton joint index)

  bool empty() const { return positions.empty(); }
  int vertex_count() const { return static_cast<int>(positions.size()); }
  int triangle_count() const { return static_cast<int>(indices.size() / 3); }

  // Throws std::invalid_argument naming the first inconsistency (sizes, index or joint out of range,
  // non-finite values, weights not summing to 1).
  void validate(const Skeleton& skeleton) const;
};

// S[j] = W[j] * inverse_bind[j] for every joint, from forward_kinematics' world positions and rotations.
void skinning_matrices(const SkinnedMesh& mesh, const std::vector<glm::vec3>& world_positions,
                       const std::vector<glm::quat>& world_rotations, std::vector<glm::mat4>& out);

// Skins every vertex on the CPU (tests and headless tools; the renderer does the same in its shader).
void skin_vertices(const SkinnedMesh& mesh, const std::vector<glm::mat4>& skinning, std::vector<glm::vec3>& positions,
                   std::vector<glm::vec3>* normals = nullptr);

// The rigid inverse of translate(position) * mat4_cast(rotation), computed exactly as a rigid transform
// (its last row is exactly 0 0 0 1).
glm::mat4 rigid_inverse(const glm::vec3& position, const glm::quat& rotation);

}  // namespace prep
