#include "engine/interop/motion_export.h"

#include <algorithm>
#include <cctype>
#include <stdexcept>

#include "engine/interop/gltf_io.h"
#include "engine/motion/bvh.h"

namespace prep {

namespace {
bool ends_with(const std::string& path, const std::string& ext) {
  if (path.size() < ext.size()) return false;
  std::string tail = path.substr(path.size() - ext.size());
  std::transform(tail.begin(), tail.end(), tail.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return tail == ext;
}
}  // namespace

MotionFormat motion_format(const std::string& path) {
  if (ends_with(path, ".bvh")) return MotionFormat::Bvh;
  if (ends_with(path, ".glb")) return MotionFormat::Glb;
  if (ends_with(path, ".gltf")) return MotionFormat::Gltf;
  throw std::invalid_argument(path + ": unknown motion format (use .bvh, .glb or .gltf)");
}

void write_clip(const std::string& path, const Clip& clip, const SkinnedMesh* mesh) {
  export_motion(path, {clip}, mesh);
}

std::vector<std::string> export_motion(const std::string& path, const std::vector<Clip>& characters,
                                       const SkinnedMesh* mesh) {
  if (characters.empty()) throw std::invalid_argument(path + ": nothing to export (no character)");
  const MotionFormat format = motion_format(path);
  if (format != MotionFormat::Bvh) {
    GltfScene scene;
    scene.characters = characters;
    scene.mesh = mesh;
    write_gltf(scene, path);
    return {path};
  }
  std::vector<std::string> written;
  const std::string stem = path.substr(0, path.size() - 4);
  for (size_t i = 0; i < characters.size(); ++i) {
    const std::string file = i == 0 ? path : stem + "_" + std::to_string(i) + path.substr(path.size() - 4);
    write_bvh(characters[i], file);
    written.push_back(file);
  }
  return written;
}

}  // namespace prep
