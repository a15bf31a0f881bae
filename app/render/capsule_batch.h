// The light bodies' capsules drawn many to an instance (shaders/capsule_batch.vert): llvmpipe pays for
// each instance of a draw about what shading a few hundred vertices costs, so a crowd's thousands of
// one-capsule instances cost more than their triangles. Here a mesh holds kCopies copies of the unit
// capsule and the capsules' data sits in a buffer texture, so a draw of n capsules is n / kCopies
// instances (and one more, part of the mesh, for the rest).
#pragma once

#include <glm/mat4x4.hpp>
#include <glm/vec4.hpp>
#include <vector>

#include "app/render/gl_api.h"
#include "app/render/instances.h"

namespace prep::render {

class CapsuleBatches {
 public:
  static constexpr int kCopies = 64;
  // Two meshes: the light body's capsule (6 slices, 36 triangles) and the distant one (4 slices, 24).
  enum Mesh { kLight = 0, kDistant = 1, kMeshes = 2 };

  CapsuleBatches();  // needs a current context with gl::load() done
  ~CapsuleBatches();
  CapsuleBatches(const CapsuleBatches&) = delete;
  CapsuleBatches& operator=(const CapsuleBatches&) = delete;

  // The capsules to draw with each mesh, until the next upload.
  void upload(const std::vector<CapsuleInstance>& light, const std::vector<CapsuleInstance>& distant);
  // Draws what was uploaded with `program` (of capsule_batch.vert, its other uniforms set), reading the
  // capsules through texture unit `unit`; returns the triangles drawn.
  int draw(GLuint program, const glm::mat4& view_proj, int unit) const;
  bool empty() const { return count_[kLight] + count_[kDistant] == 0; }

 private:
  GLuint vao_[kMeshes] = {}, vbo_[kMeshes] = {}, ibo_[kMeshes] = {};
  int indices_per_copy_[kMeshes] = {};
  GLuint data_buffer_ = 0, data_texture_ = 0;
  int count_[kMeshes] = {};
  std::vector<glm::vec4> texels_;  // three per capsule: end A and radius, end B and glow, colour
};

}  // namespace prep::render
