#include "app/render/skinned_body.h"

#include <cstddef>
#include <exception>

#include "engine/interop/character_mesh.h"
#include "engine/interop/gltf_io.h"
#include "engine/motion/body_map.h"
#include "engine/util/files.h"

namespace prep::render {

using namespace prep::gl;

std::string default_character_path() { return source_dir() + "/assets/character.glb"; }

std::shared_ptr<const SkinnedMesh> body_for_skeleton(const Skeleton& skeleton, const std::string& character_path,
                                                     std::string* why) {
  if (skeleton.size() > kMaxSkinJoints) {
    if (why) *why = std::to_string(skeleton.size()) + " joints, more than a skinned body may have";
    return nullptr;
  }
  std::string reason;
  if (!character_path.empty()) {
    try {
      auto mesh = std::make_shared<SkinnedMesh>(load_character_mesh(character_path, skeleton));
      mesh->validate(skeleton);
      return mesh;
    } catch (const std::exception& e) {
      reason = e.what();  // not made for this skeleton (or unreadable): build one instead
    }
  }
  try {
    auto mesh = std::make_shared<SkinnedMesh>(build_character_mesh(skeleton, BodyMap::detect(skeleton)));
    if (why) *why = reason;
    return mesh;
  } catch (const std::exception& e) {
    if (why) *why = (reason.empty() ? "" : reason + "; ") + e.what();
    return nullptr;
  }
}

namespace {

// Interleaved vertex: what shaders/skinned.vert reads at locations 0-3.
struct SkinVertex {
  glm::vec3 position;
  glm::vec3 normal;
  glm::ivec4 joints;
  glm::vec4 weights;
};

}  // namespace

SkinnedBody::SkinnedBody(std::shared_ptr<const SkinnedMesh> mesh) : mesh_(std::move(mesh)) {
  std::vector<SkinVertex> vertices(mesh_->positions.size());
  for (size_t v = 0; v < vertices.size(); ++v)
    vertices[v] = {mesh_->positions[v], mesh_->normals[v], mesh_->joints[v], mesh_->weights[v]};
  glGenVertexArrays(1, &vao_);
  glBindVertexArray(vao_);
  glGenBuffers(1, &vertex_buffer_);
  glBindBuffer(GL_ARRAY_BUFFER, vertex_buffer_);
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(vertices.size() * sizeof(SkinVertex)), vertices.data(), GL_STATIC_DRAW);
  const auto at = [](size_t offset) { return reinterpret_cast<const void*>(offset); };
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, sizeof(SkinVertex), at(offsetof(SkinVertex, position)));
  glEnableVertexAttribArray(1);
  glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, sizeof(SkinVertex), at(offsetof(SkinVertex, normal)));
  glEnableVertexAttribArray(2);
  glVertexAttribIPointer(2, 4, GL_INT, sizeof(SkinVertex), at(offsetof(SkinVertex, joints)));
  glEnableVertexAttribArray(3);
  glVertexAttribPointer(3, 4, GL_FLOAT, GL_FALSE, sizeof(SkinVertex), at(offsetof(SkinVertex, weights)));
  glGenBuffers(1, &index_buffer_);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, index_buffer_);
  glBufferData(GL_ELEMENT_ARRAY_BUFFER, static_cast<GLsizeiptr>(mesh_->indices.size() * sizeof(std::uint32_t)),
               mesh_->indices.data(), GL_STATIC_DRAW);
  glBindVertexArray(0);
}

SkinnedBody::~SkinnedBody() {
  const GLuint buffers[] = {vertex_buffer_, index_buffer_};
  glDeleteBuffers(2, buffers);
  glDeleteVertexArrays(1, &vao_);
}

void SkinnedBody::draw() const {
  glBindVertexArray(vao_);
  glDrawElements(GL_TRIANGLES, static_cast<GLsizei>(mesh_->indices.size()), GL_UNSIGNED_INT, nullptr);
}

}  // namespace prep::render
