// prep export: writes clips of a motion set as glTF (.glb/.gltf: skeleton as nodes, one animation,
// optionally our skinned body) or BVH, chosen by the output's extension. Either a scenario run headless
// for --seconds (every character's synthesized motion, one frame per engine tick) or named clips of a
// motion set; each becomes one character of the file (a BVH holds one skeleton: further characters go to
// <stem>_<i>.bvh).
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
#include "engine/motion/body_map.h"
#include "engine/util/error.h"
#include "engine/world/policy_cache.h"
#include "engine/world/recording.h"
#include "engine/world/scenario.h"
#include "engine/world/world.h"

namespace {

struct ExportOptions {
  std::string scenario;
  float seconds = 10.0f;
  std::string cache;
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
      app.add_option("--scenario", o->scenario, "Scenario JSON to run headless and export (every character)");
      app.add_option("--seconds", o->seconds, "With --scenario: simulated seconds (default 10)");
      app.add_option("--cache", o->cache, "With --scenario: policy cache folder (default: as prep run)");
      app.add_option("--motions", o->motions, "Motion-set manifest (JSON); default: the built-in library");
      app.add_option("--params", o->params, "Params JSON file (default: the built-in defaults)");
      app.add_option("--clip", o->clips, "Clip name (repeat for several characters in one file)");
      app.add_option("--out", o->out, "Output file: .glb, .gltf or .bvh")->required();
      app.add_flag("--with-mesh", o->with_mesh, "glTF only: add our skinned body, bound to the set's skeleton");
      app.callback([o] {
        const prep::MotionFormat format = prep::motion_format(o->out);
        if (o->with_mesh && format == prep::MotionFormat::Bvh)
          throw std::invalid_argument("--with-mesh: a BVH holds no mesh (write .glb or .gltf)");
        if (o->scenario.empty() == o->clips.empty())
          throw std::invalid_argument("give either --scenario FILE or one or more --clip NAME");
        if (!o->scenario.empty()) {
          if (!(o->seconds > 0.0f)) throw std::invalid_argument("--seconds must be positive");
          const prep::Scenario scenario = prep::load_scenario(o->scenario);
          const prep::Params params = o->params.empty() ? prep::load_scenario_params(scenario) : prep::load_params(o->params);
          const std::string cache = o->cache.empty() ? prep::default_policy_cache_dir() : o->cache;
          const auto assets = prep::prepare_world_assets(scenario, params, cache);
          prep::World world(scenario, assets);
          const std::vector<prep::Clip> characters = prep::record_world(world, o->seconds);
          const int ticks = characters.front().frame_count();
          prep::SkinnedMesh mesh;
          if (o->with_mesh) {
            const auto& skeleton = *characters.front().skeleton;
            mesh = prep::build_character_mesh(skeleton, prep::BodyMap::detect(skeleton));
          }
          for (const std::string& file : prep::export_motion(o->out, characters, o->with_mesh ? &mesh : nullptr))
            std::cout << file << ": " << std::filesystem::file_size(file) << " bytes, " << characters.size()
                      << " character(s), " << ticks << " frames at " << characters.front().fps << " fps\n";
          return;
        }
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
