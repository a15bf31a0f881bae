#include "app/render/capsule_batch.h"

#include <glm/gtc/type_ptr.hpp>

#include "app/render/capsule_mesh.h"

namespace prep::render {

using namespace prep::gl;

CapsuleBatches::CapsuleBatches() {
  const int slices[kMeshes] = {6, 4};
  for (int m = 0; m < kMeshes; ++m) {
    std::vector<float> one;
    std::vector<unsigned> one_indices;
    capsule_mesh(slices[m], 1, one, one_indices);
    const unsigned vertices_per_copy = static_cast<unsigned>(one.size() / 4);
    // Five floats per vertex: the unit mesh's four and the copy's number.
    std::vector<float> vertices;
    std::vector<unsigned> indices;
    for (int copy = 0; copy < kCopies; ++copy) {
      for (size_t v = 0; v < one.size(); v += 4) {
        vertices.insert(vertices.end(), {one[v], one[v + 1], one[v + 2], one[v + 3], static_cast<float>(copy)});
      }
      for (unsigned i : one_indices) indices.push_back(i + static_cast<unsigned>(copy) * vertices_per_copy);
    }
    indices_per_copy_[m] = static_cast<int>(one_indices.size());
    glGenVertexArrays(1, &vao_[m]);
    glBindVertexArray(vao_[m]);
    glGenBuffers(1, &vbo_[m]);
    glBindBuffer(GL_ARRAY_BUFFER, vbo_[m]);
    glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(vertices.size() * sizeof(float)), vertices.data(), GL_STATIC_DRAW);
    const GLsizei stride = 5 * sizeof(float);
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, stride, nullptr);
    glEnableVertexAttribArray(1);
    glVertexAttribPointer(1, 1, GL_FLOAT, GL_FALSE, stride, reinterpret_cast<const void*>(3 * sizeof(float)));
    glEnableVertexAttribArray(2);
    glVertexAttribPointer(2, 1, GL_FLOAT, GL_FALSE, stride, reinterpret_cast<const void*>(4 * sizeof(float)));
    glGenBuffers(1, &ibo_[m]);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, ibo_[m]);
    glBufferData(GL_ELEMENT_ARRAY_BUFFER, static_cast<GLsizeiptr>(indices.size() * sizeof(unsigned)), indices.data(), GL_STATIC_DRAW);
  }
  glBindVertexArray(0);
  glGenBuffers(1, &data_buffer_);
  glGenTextures(1, &data_texture_);
}

CapsuleBatches::~CapsuleBatches() {
  glDeleteVertexArrays(kMeshes, vao_);
  glDeleteBuffers(kMeshes, vbo_);
  glDeleteBuffers(kMeshes, ibo_);
  glDeleteBuffers(1, &data_buffer_);
  glDeleteTextures(1, &data_texture_);
}

void CapsuleBatches::upload(const std::vector<CapsuleInstance>& light, const std::vector<CapsuleInstance>& distant) {
  texels_.clear();
  for (const std::vector<CapsuleInstance>* list : {&light, &distant}) {
    for (const CapsuleInstance& c : *list) texels_.insert(texels_.end(), {c.a_radius, c.b_glow, glm::vec4(c.colour, 0.0f)});
  }
  count_[kLight] = static_cast<int>(light.size());
  count_[kDistant] = static_cast<int>(distant.size());
  if (texels_.empty()) return;
  glBindBuffer(GL_TEXTURE_BUFFER, data_buffer_);
  glBufferData(GL_TEXTURE_BUFFER, static_cast<GLsizeiptr>(texels_.size() * sizeof(glm::vec4)), texels_.data(), GL_STREAM_DRAW);
  glBindBuffer(GL_TEXTURE_BUFFER, 0);
}

int CapsuleBatches::draw(GLuint program, const glm::mat4& view_proj, int unit) const {
  if (empty()) return 0;
  glUseProgram(program);
  glUniformMatrix4fv(glGetUniformLocation(program, "u_view_proj"), 1, GL_FALSE, glm::value_ptr(view_proj));
  glUniform1i(glGetUniformLocation(program, "u_capsules"), unit);
  glUniform1i(glGetUniformLocation(program, "u_copies"), kCopies);
  const GLint first = glGetUniformLocation(program, "u_first");
  glActiveTexture(GL_TEXTURE0 + static_cast<GLenum>(unit));
  glBindTexture(GL_TEXTURE_BUFFER, data_texture_);
  glTexBuffer(GL_TEXTURE_BUFFER, GL_RGBA32F, data_buffer_);  // the buffer may have been reallocated
  int triangles = 0, start = 0;
  for (int m = 0; m < kMeshes; ++m) {
    const int n = count_[m], full = n / kCopies, rest = n % kCopies;
    glBindVertexArray(vao_[m]);
    if (full > 0) {
      glUniform1i(first, start);
      glDrawElementsInstanced(GL_TRIANGLES, kCopies * indices_per_copy_[m], GL_UNSIGNED_INT, nullptr, full);
    }
    if (rest > 0) {  // the first `rest` copies of the mesh: its indices run copy by copy
      glUniform1i(first, start + full * kCopies);
      glDrawElementsInstanced(GL_TRIANGLES, rest * indices_per_copy_[m], GL_UNSIGNED_INT, nullptr, 1);
    }
    triangles += n * indices_per_copy_[m] / 3;
    start += n;
  }
  glBindTexture(GL_TEXTURE_BUFFER, 0);
  glActiveTexture(GL_TEXTURE0);
  return triangles;
}

}  // namespace prep::render
