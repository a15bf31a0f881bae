// Writing motion out of prep, in the format the file name asks for: .bvh (the conventions Blender's BVH
// importer reads), .glb or .gltf (skeleton as nodes, one animation, optionally the skinned body).
#pragma once

#include <string>
#include <vector>

#include "engine/interop/skinned_mesh.h"
#include "engine/motion/clip.h"

namespace prep {

enum class MotionFormat { Bvh, Glb, Gltf };

// By extension (case-insensitive); throws std::invalid_argument naming the path for anything else.
MotionFormat motion_format(const std::string& path);

// One clip to one file. `mesh` (bound to the clip's skeleton) is written only to glTF.
void write_clip(const std::string& path, const Clip& clip, const SkinnedMesh* mesh = nullptr);

// Every character's clip. glTF holds them all in one file and one animation; a BVH holds one skeleton, so
// characters after the first go to "<stem>_<i>.bvh" beside it. Returns the paths written. Atomic writes.
std::vector<std::string> export_motion(const std::string& path, const std::vector<Clip>& characters,
                                       const SkinnedMesh* mesh = nullptr);

}  // namespace prep
