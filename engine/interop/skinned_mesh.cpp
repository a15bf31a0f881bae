#include "engine/interop/skinned_mesh.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace prep {

namespace {
bool finite(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }
}  // namespace

void SkinnedMesh::validate(const Skeleton& skeleton) const {
  const size_t n = positions.size();
  if (normals.size() != n || joints.size() != n || weights.size() != n)
    throw std::invalid_argument("skinned mesh: positions, normals, joints and weights differ in size");
  if (indices.size() % 3 != 0) throw std::invalid_argument("skinned mesh: index count is not a multiple of 3");
  if (inverse_bind.size() != static_cast<size_t>(skeleton.size()))
    throw std::invalid_argument("skinned mesh: " + std::to_string(inverse_bind.size()) +
                                " inverse bind matrices for " + std::to_string(skeleton.size()) + " joints");
  for (size_t i = 0; i < indices.size(); ++i)
    if (indices[i] >= n) throw std::invalid_argument("skinned mesh: index " + std::to_string(i) + " out of range");
  for (size_t v = 0; v < n; ++v) {
    if (!finite(positions[v]) || !finite(normals[v]))
      throw std::invalid_argument("skinned mesh: vertex " + std::to_string(v) + " is not finite");
    float sum = 0.0f;
    for (int k = 0; k < 4; ++k) {
      if (joints[v][k] < 0 || joints[v][k] >= skeleton.size())
        throw std::invalid_argument("skinned mesh: vertex " + std::to_string(v) + " joint out of range");
      if (!(weights[v][k] >= 0.0f)) throw std::invalid_argument("skinned mesh: vertex " + std::to_string(v) + " weight < 0");
      sum += weights[v][k];
    }
    if (std::fabs(sum - 1.0f) > 1e-3f)
      throw std::invalid_argument("skinned mesh: vertex " + std::to_string(v) + " weights sum to " + std::to_string(sum));
  }
  for (size_t j = 0; j < inverse_bind.size(); ++j)
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 4; ++r)
        if (!std::isfinite(inverse_bind[j][c][r]))
          throw std::invalid_argument("skinned mesh: inverse bind matrix " + std::to_string(j) + " is not finite");
}

glm::mat4 rigid_inverse(const glm::vec3& position, const glm::quat& rotation) {
  const glm::quat inv = glm::conjugate(glm::normalize(rotation));
  glm::mat4 m = glm::mat4_cast(inv);
  const glm::vec3 t = -(inv * position);
  m[3] = glm::vec4(t, 1.0f);
  m[0][3] = m[1][3] = m[2][3] = 0.0f;
  return m;
}

void skinning_matrices(const SkinnedMesh& mesh, const std::vector<glm::vec3>& world_positions,
                       const std::vector<glm::quat>& world_rotations, std::vector<glm::mat4>& out) {
  out.resize(mesh.inverse_bind.size());
  for (size_t j = 0; j < out.size(); ++j) {
    glm::mat4 world = glm::mat4_cast(world_rotations[j]);
    world[3] = glm::vec4(world_positions[j], 1.0f);
    out[j] = world * mesh.inverse_bind[j];
  }
}

void skin_vertices(const SkinnedMesh& mesh, const std::vector<glm::mat4>& skinning, std::vector<glm::vec3>& positions,
                   std::vector<glm::vec3>* normals) {
  const size_t n = mesh.positions.size();
  positions.resize(n);
  if (normals) normals->resize(n);
  for (size_t v = 0; v < n; ++v) {
    glm::mat4 m(0.0f);
    for (int k = 0; k < 4; ++k) {
      const float w = mesh.weights[v][k];
      if (w != 0.0f) m += skinning[static_cast<size_t>(mesh.joints[v][k])] * w;
    }
    positions[v] = glm::vec3(m * glm::vec4(mesh.positions[v], 1.0f));
    if (normals) {
      const glm::vec3 nrm = glm::mat3(m) * mesh.normals[v];
      const float len = glm::length(nrm);
      (*normals)[v] = len > 0.0f ? nrm / len : mesh.normals[v];
    }
  }
}

}  // namespace prep
