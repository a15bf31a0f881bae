// Skinned bodies in the renderer: the glTF character (assets/character.glb, read through tinygltf) for the
// built-in skeleton, and for any other humanoid skeleton our own body built to its proportions
// (engine/interop/character_mesh.h). The renderer draws a SceneCharacter with its skeleton's body when it
// has one, and with capsules per bone otherwise.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <glm/mat4x4.hpp>

#include "app/render/gl_api.h"
#include "engine/interop/skinned_mesh.h"
#include "engine/motion/skeleton.h"

namespace prep::render {

// Joints a body may have: the size of the skinning uniform block in shaders/skinned.vert (128 mat4 = 8 KB,
// half of the 16 KB every GL 3.3 implementation must allow). Every skeleton we meet has 22-43 joints.
constexpr int kMaxSkinJoints = 128;

// The glTF file of our character, made by `prep make-character` for the built-in skeleton.
std::string default_character_path();

// The body for a skeleton: the character file when it was made for this skeleton (load_character_mesh
// binds it by joint name and checks the bone offsets), else our body built for the skeleton's body map,
// else nullptr (not a humanoid we recognise, or more than kMaxSkinJoints joints). Never throws: a missing
// or broken character file falls back to the built body, and the reason is written to `why` if given.
std::shared_ptr<const SkinnedMesh> body_for_skeleton(const Skeleton& skeleton, const std::string& character_path,
                                                     std::string* why = nullptr);

// A SkinnedMesh on the GPU: positions, normals, joint indices and weights, triangles. Requires a current
// context with gl::load() done.
class SkinnedBody {
 public:
  explicit SkinnedBody(std::shared_ptr<const SkinnedMesh> mesh);
  ~SkinnedBody();
  SkinnedBody(const SkinnedBody&) = delete;
  SkinnedBody& operator=(const SkinnedBody&) = delete;

  const SkinnedMesh& mesh() const { return *mesh_; }
  int triangle_count() const { return mesh_->triangle_count(); }
  // Draws the triangles with the bound program; the caller has filled the skinning block.
  void draw() const;

 private:
  std::shared_ptr<const SkinnedMesh> mesh_;
  GLuint vao_ = 0, vertex_buffer_ = 0, index_buffer_ = 0;
};

}  // namespace prep::render
