// prep make-character: builds our skinned body for the built-in skeleton and writes it as glTF
// (assets/character.glb is made by this command and committed).
#include <iostream>
#include <string>

#include "app/cli/command.h"
#include "engine/interop/character_mesh.h"
#include "engine/interop/gltf_io.h"
#include "engine/library/builtin.h"
#include "engine/motion/body_map.h"

namespace {

struct MakeCharacterOptions {
  std::string out = "assets/character.glb";
};

prep::cli::RegisterCommand make_character_command(
    "make-character", "Build our skinned humanoid body for the built-in skeleton and write it as .glb/.gltf", 80,
    [](CLI::App& app) {
      auto options = std::make_shared<MakeCharacterOptions>();
      app.add_option("--out", options->out, "output file (.glb or .gltf)")->capture_default_str();
      app.callback([options] {
        const auto skeleton = prep::builtin_skeleton();
        const prep::BodyMap body = prep::BodyMap::detect(*skeleton);
        const prep::SkinnedMesh mesh = prep::build_character_mesh(*skeleton, body);
        // The bind pose as a one-frame clip: nodes carry the rest pose, no animation is needed.
        prep::Clip bind;
        bind.name = "bind";
        bind.skeleton = skeleton;
        prep::GltfScene scene;
        scene.characters = {bind};
        scene.mesh = &mesh;
        prep::write_gltf(scene, options->out);
        std::cout << options->out << ": " << mesh.vertex_count() << " vertices, " << mesh.triangle_count()
                  << " triangles, " << skeleton->size() << " joints\n";
      });
    });

}  // namespace
