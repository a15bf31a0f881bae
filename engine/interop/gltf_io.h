// glTF 2.0 in and out (tinygltf): skinned humanoids, their node hierarchies and animations.
//
// Reading turns a glTF rig into engine types. glTF joints may carry rest rotations and scales; our
// Skeleton has none (its rest pose is all-identity rotations), so the imported skeleton's offsets are
// the rest pose's world-space bone vectors, and each frame's rotations are re-expressed relative to the
// rest pose: our world rotation of joint j is  G_j(t) * G_j(rest)^-1  (G = glTF world rotation). The
// inverse bind matrices are re-expressed the same way so that the mesh skins identically. Animated
// translations of non-root joints are ignored (our bones have fixed lengths). A leaf node named "*_end"
// (any case) below a joint becomes that joint's End Site (Mixamo's HeadTop_End, our own exports).
//
// Every accessor read is checked against its buffer view and buffer with overflow-safe arithmetic; any
// malformed file throws InputError naming the file and the accessor or field. Nothing is trusted.
#pragma once

#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "engine/interop/skinned_mesh.h"
#include "engine/motion/clip.h"

namespace prep {

// One skeleton found in a glTF file (one per skin, or one per scene root tree when there is no skin).
struct GltfCharacter {
  std::string name;                          // the skin's name, or the root node's
  std::shared_ptr<const Skeleton> skeleton;  // metres, rest pose = the nodes' rest transforms
  SkinnedMesh mesh;                          // empty if no mesh uses the skin
  std::vector<Clip> clips;                   // one per animation that moves this character
};

struct GltfReadOptions {
  float fps = 0.0f;  // resampling rate of the animations; 0: from the key spacing (30 if keys are irregular)
};

// Reads a .gltf (embedded or external buffers next to it) or .glb, chosen by content (the GLB magic).
std::vector<GltfCharacter> read_gltf(const std::string& path, const GltfReadOptions& options = {});
// The same from bytes in memory; external buffer files are looked up in base_dir (none if empty).
std::vector<GltfCharacter> parse_gltf(std::string_view bytes, const std::string& source_name,
                                      const GltfReadOptions& options = {}, const std::string& base_dir = "");

// What to write: one or more characters on their skeletons, each with its clip (all clips must share the
// frame rate; clips may differ in length). With a mesh, every character gets a skin and a mesh node.
struct GltfScene {
  std::vector<Clip> characters;     // each clip's skeleton is that character's skeleton
  const SkinnedMesh* mesh = nullptr;  // bound to characters[i].skeleton for every i (same joint count)
  std::string animation_name;       // default: the first clip's name
};

// Writes .glb (binary) or .gltf (JSON with the buffer embedded as a data URI), chosen by the extension,
// atomically. Joints become nodes (End Sites become leaf nodes named "<joint>_end"); one animation holds a
// translation channel for each root and a rotation channel for every joint, LINEAR, at times i / fps
// (strictly increasing), quaternions normalised and hemisphere-continuous. With several characters the
// node names are prefixed "character<i>:".
void write_gltf(const GltfScene& scene, const std::string& path);
std::string format_gltf(const GltfScene& scene, bool binary);

// Reads a character mesh written for `skeleton` (e.g. assets/character.glb for the built-in skeleton) and
// binds it to `skeleton` by joint name. Throws InputError if the file has no skinned mesh, a joint is
// missing, or the file's bone offsets differ from the skeleton's by more than 1 mm.
SkinnedMesh load_character_mesh(const std::string& path, const Skeleton& skeleton);

}  // namespace prep
