#include "engine/interop/motion_export.h"

#include <doctest/doctest.h>

#include <filesystem>

#include "engine/interop/character_mesh.h"
#include "engine/interop/gltf_io.h"
#include "engine/motion/body_map.h"
#include "tests/interop/gltf_validator.h"
#include "tests/interop/interop_support.h"

namespace prep {
namespace {

TEST_CASE("write_clip chooses the format by extension, and each file reads back as the clip") {
  const Clip clip = test::cmu31_clip("turn_left_69_27.bvh");
  for (const char* name : {"turn.glb", "turn.GLTF", "turn.bvh"}) {
    CAPTURE(name);
    const std::string path = test::scratch(name);
    std::filesystem::remove(path);
    write_clip(path, clip);
    REQUIRE(std::filesystem::exists(path));
    Clip back;
    if (motion_format(path) == MotionFormat::Bvh) {
      BvhReadOptions options;
      options.unit_scale = 0.01f;  // write_bvh writes centimetres
      back = read_bvh(path, options);
    } else {
      test::check_gltf_valid(path);
      back = read_gltf(path).at(0).clips.at(0);
    }
    const test::PoseDifference d = test::clip_difference(clip, back);
    CHECK(d.position < 1e-4f);
    CHECK(d.rotation < 1e-4f);
  }
  CHECK_THROWS_AS(write_clip(test::scratch("turn.fbx"), clip), std::invalid_argument);
}

TEST_CASE("Several characters with our body go into one valid glTF, and into BVH one file each") {
  const Clip walk = test::cmu31_clip("walk_69_01.bvh");
  Clip second = walk;
  second.frames.resize(40);
  for (Pose& p : second.frames) p.root_position.x += 1.5f;
  const SkinnedMesh mesh = build_character_mesh(*walk.skeleton, BodyMap::detect(*walk.skeleton));
  const std::string glb = test::scratch("two_walkers.glb");
  CHECK(export_motion(glb, {walk, second}, &mesh) == std::vector<std::string>{glb});
  test::check_gltf_valid(glb);
  const std::vector<GltfCharacter> back = read_gltf(glb);
  REQUIRE(back.size() == 2);
  CHECK(back[0].mesh.vertex_count() == mesh.vertex_count());
  CHECK(back[1].clips.at(0).frame_count() == 40);
  CHECK(back[1].skeleton->joints[0].name == "character1:" + walk.skeleton->joints[0].name);
  const std::string bvh = test::scratch("two_walkers.bvh");
  const std::vector<std::string> files = export_motion(bvh, {walk, second});
  REQUIRE(files.size() == 2);
  CHECK(files[1] == test::scratch("two_walkers_1.bvh"));
  BvhReadOptions options;
  options.unit_scale = 0.01f;
  CHECK(read_bvh(files[1], options).frame_count() == 40);
}

}  // namespace
}  // namespace prep
