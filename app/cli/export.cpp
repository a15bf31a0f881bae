// prep export: writes clips of a motion set as glTF (.glb/.gltf: skeleton as nodes, one animation,
// optionally our skinned body) or BVH, chosen by the output's extension. Every named clip becomes one
// character of the file (a BVH holds one skeleton: further clips go to <stem>_<i>.bvh). The scenario form
// (--scenario) joins when the world (scenarios) lands; it will call the same export_motion().
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include "app/cli/command.h"
#include "engine/interop/character_mesh.h"
#include "engine/interop/motion_export.h"
#include "engine/library/builtin.h"
#include "engine/motion/motion_set.h"
#include "engine/params/params.h"
#include "engine/util/error.h"

namespace {

struct ExportOptions {
  std::string motions;
  std::string params;
  std::vector<std::string> clips;
  std::string out;
  bool with_mesh = false;
};

prep::cli::RegisterCommand export_command(
    "export", "Export clips as glTF (.glb/.gltf, optionally with our skinned body) or BVH, by extension", 70,
    [](CLI::App& app) {
      auto o = std::make_shared<ExportOptions>();
      app.add_option("--motions", o->motions, "Motion-set manifest (JSON); default: the built-in library");
      app.add_option("--params", o->params, "Params JSON file (default: the built-in defaults)");
      app.add_option("--clip", o->clips, "Clip name (repeat for several characters in one file)")->required();
      app.add_option("--out", o->out, "Output file: .glb, .gltf or .bvh")->required();
      app.add_flag("--with-mesh", o->with_mesh, "glTF only: add our skinned body, bound to the set's skeleton");
      app.callback([o] {
        const prep::MotionFormat format = prep::motion_format(o->out);
        if (o->with_mesh && format == prep::MotionFormat::Bvh)
          throw std::invalid_argument("--with-mesh: a BVH holds no mesh (write .glb or .gltf)");
        const prep::Params params = o->params.empty() ? prep::Params{} : prep::load_params(o->params);
        const prep::MotionSet set = o->motions.empty() ? prep::make_builtin_motion_set(params)
                                                       : prep::load_motion_set(o->motions, params);
        std::vector<prep::Clip> characters;
        for (const std::string& name : o->clips) {
          const int index = set.find(name);
          if (index < 0) {
            std::string known;
            for (const prep::MotionClip& c : set.clips) known += (known.empty() ? "" : ", ") + c.clip.name;
            throw std::invalid_argument("--clip " + name + ": no such clip in " + set.name + " (" + known + ")");
          }
          characters.push_back(set.clips[static_cast<size_t>(index)].clip);
        }
        prep::SkinnedMesh mesh;
        if (o->with_mesh) mesh = prep::build_character_mesh(*set.skeleton, set.body);
        const std::vector<std::string> written = prep::export_motion(o->out, characters, o->with_mesh ? &mesh : nullptr);
        for (size_t i = 0; i < written.size(); ++i) {
          const prep::Clip& c = characters[std::min(i, characters.size() - 1)];
          std::cout << written[i] << ": " << std::filesystem::file_size(written[i]) << " bytes";
          if (format == prep::MotionFormat::Bvh || characters.size() == 1)
            std::cout << ", clip " << c.name << ", " << c.frame_count() << " frames at " << c.fps << " fps";
          else
            std::cout << ", " << characters.size() << " characters";
          std::cout << ", " << c.skeleton->size() << " joints";
          if (o->with_mesh) std::cout << ", body " << mesh.vertex_count() << " vertices";
          std::cout << "\n";
        }
      });
    });

}  // namespace
