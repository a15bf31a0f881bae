// prep retarget: motion from another humanoid onto our skeleton, or ours onto another humanoid (its mesh
// included when it comes from a skinned glTF), by a JSON joint map (engine/interop/retarget.h; maps for the
// CMU conversions and Mixamo names are in assets/retarget/).
//
//   prep retarget --in their.bvh|.glb --map MAP.json --out ours.bvh|.glb [--with-mesh]
//       their clip onto the built-in skeleton (with --with-mesh: our body in the glTF)
//   prep retarget --clip walk --onto their.glb|.bvh --map MAP.json --out theirs.glb
//       a built-in clip onto their skeleton (their mesh in the glTF when --onto is a skinned glTF)
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>

#include "app/cli/command.h"
#include "engine/interop/character_mesh.h"
#include "engine/interop/gltf_io.h"
#include "engine/interop/motion_export.h"
#include "engine/interop/retarget.h"
#include "engine/library/builtin.h"
#include "engine/motion/body_map.h"
#include "engine/motion/bvh.h"
#include "engine/util/error.h"

namespace {

struct RetargetOptions {
  std::string in, clip, onto, map, out;
  float unit_scale = 0.01f;
  bool with_mesh = false;
};

// A character from a file: a BVH (its skeleton and clip) or the first character of a glTF that has an
// animation (or, for a target, any skeleton with its mesh).
prep::GltfCharacter read_character(const std::string& path, float unit_scale, bool need_clip) {
  if (prep::motion_format(path) == prep::MotionFormat::Bvh) {
    prep::BvhReadOptions options;
    options.unit_scale = unit_scale;
    prep::Clip clip = prep::read_bvh(path, options);
    prep::GltfCharacter c;
    c.name = clip.name;
    c.skeleton = clip.skeleton;
    c.clips.push_back(std::move(clip));
    return c;
  }
  std::vector<prep::GltfCharacter> characters = prep::read_gltf(path);
  for (prep::GltfCharacter& c : characters)
    if (!need_clip || !c.clips.empty()) return std::move(c);
  throw prep::InputError(path, need_clip ? "no character with an animation in the file" : "no character in the file");
}

void run(const RetargetOptions& o) {
  if (o.in.empty() == o.clip.empty()) throw std::invalid_argument("give either --in FILE (theirs onto ours) or --clip NAME with --onto FILE (ours onto theirs)");
  if (!o.clip.empty() && o.onto.empty()) throw std::invalid_argument("--clip needs --onto FILE: the skeleton to retarget onto");
  if (!o.in.empty() && !o.onto.empty()) throw std::invalid_argument("--onto goes with --clip (with --in the target is the built-in skeleton)");
  if (!(o.unit_scale > 0.0f)) throw std::invalid_argument("--unit-scale must be positive");
  const prep::JointMap map = prep::load_joint_map(o.map);  // theirs -> ours
  const prep::MotionFormat format = prep::motion_format(o.out);
  if (o.with_mesh && format == prep::MotionFormat::Bvh) throw std::invalid_argument("--with-mesh: a BVH holds no mesh (write .glb or .gltf)");

  prep::Clip result;
  std::shared_ptr<const prep::SkinnedMesh> mesh;
  if (!o.in.empty()) {
    const prep::GltfCharacter theirs = read_character(o.in, o.unit_scale, true);
    const auto ours = prep::builtin_skeleton();
    const prep::Retargeter retargeter(theirs.skeleton, ours, map);
    result = retargeter.retarget(theirs.clips.front());
    if (o.with_mesh) mesh = std::make_shared<prep::SkinnedMesh>(prep::build_character_mesh(*ours, prep::BodyMap::detect(*ours)));
    std::cout << o.in << " (" << theirs.skeleton->size() << " joints) -> the built-in skeleton (" << ours->size()
              << " joints), root scale " << retargeter.root_scale() << "\n";
  } else {
    const prep::MotionSet set = prep::make_builtin_motion_set(prep::Params{});
    const int index = set.find(o.clip);
    if (index < 0) throw std::invalid_argument("--clip " + o.clip + ": no such clip in the built-in library");
    const prep::GltfCharacter theirs = read_character(o.onto, o.unit_scale, false);
    const prep::Retargeter retargeter(set.skeleton, theirs.skeleton, prep::inverted(map));
    result = retargeter.retarget(set.clips[static_cast<size_t>(index)].clip);
    if (!theirs.mesh.empty()) mesh = std::make_shared<prep::SkinnedMesh>(theirs.mesh);  // their body moves with our motion
    std::cout << "built-in " << o.clip << " -> " << o.onto << " (" << theirs.skeleton->size() << " joints), root scale "
              << retargeter.root_scale() << (mesh ? ", with its mesh" : "") << "\n";
  }
  const bool write_mesh = mesh && format != prep::MotionFormat::Bvh;
  for (const std::string& file : prep::export_motion(o.out, {result}, write_mesh ? mesh.get() : nullptr))
    std::cout << file << ": " << std::filesystem::file_size(file) << " bytes, " << result.frame_count() << " frames at "
              << result.fps << " fps" << (write_mesh ? ", skinned mesh included" : "") << "\n";
}

prep::cli::RegisterCommand retarget_command(
    "retarget", "Retarget motion by a joint map: another humanoid's BVH/glTF onto our skeleton, or a built-in clip onto theirs", 75,
    [](CLI::App& app) {
      auto o = std::make_shared<RetargetOptions>();
      app.add_option("--in", o->in, "Their motion (.bvh, .glb or .gltf) to put on the built-in skeleton");
      app.add_option("--clip", o->clip, "A built-in clip to put on the skeleton of --onto");
      app.add_option("--onto", o->onto, "With --clip: their skeleton (.bvh, or a .glb/.gltf whose mesh comes along)");
      app.add_option("--map", o->map, "Joint map JSON, their joint names -> ours (assets/retarget/*.json)")->required();
      app.add_option("--unit-scale", o->unit_scale, "BVH units to metres (default 0.01: centimetres)");
      app.add_option("--out", o->out, "Output .bvh, .glb or .gltf")->required();
      app.add_flag("--with-mesh", o->with_mesh, "With --in and glTF output: add our skinned body");
      app.callback([o] { run(*o); });
    });

}  // namespace
