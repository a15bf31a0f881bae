// What `prep export --scenario` writes, for each scenario of Sec. 7.2: a glTF with every character and our
// body that the Khronos validator accepts with no error and no warning, and that reads back with the same
// joint transforms as the recorded run; and BVH files (one per character) that read back likewise.
#include <doctest/doctest.h>

#include <string>

#include "engine/interop/character_mesh.h"
#include "engine/interop/gltf_io.h"
#include "engine/interop/motion_export.h"
#include "engine/motion/body_map.h"
#include "engine/world/policy_cache.h"
#include "engine/world/recording.h"
#include "engine/world/scenario.h"
#include "engine/world/world.h"
#include "tests/interop/gltf_validator.h"
#include "tests/interop/interop_support.h"

namespace prep {
namespace {

TEST_CASE("every scenario's export is valid glTF and BVH that read back as the recorded run") {
  for (const char* name : {"kick", "fight", "obstacles"}) {
    CAPTURE(name);
    const Scenario scenario = load_scenario(test::repo() + "/assets/scenarios/" + name + ".json");
    const Params params = load_scenario_params(scenario);
    // Policies are cached under the build's scratch folder by Params hash (as in tests/world).
    const auto assets = prepare_world_assets(scenario, params, test::tmp_dir() + "/policy-cache");
    World world(scenario, assets);
    const std::vector<Clip> run = record_world(world, 4.0f);
    REQUIRE(run.size() == world.characters().size());
    REQUIRE(run.front().frame_count() == static_cast<int>(std::lround(4.0f / params.runtime.fixed_dt)));
    // The last recorded frame is the pose the world holds now.
    CHECK(run.front().frames.back().root_position == world.characters().front().pose.root_position);

    const SkinnedMesh body = build_character_mesh(*assets->set->skeleton, BodyMap::detect(*assets->set->skeleton));
    const std::string glb = test::scratch(std::string("scenario_") + name + ".glb");
    export_motion(glb, run, &body);
    test::check_gltf_valid(glb);
    const std::vector<GltfCharacter> back = read_gltf(glb);
    REQUIRE(back.size() == run.size());
    for (size_t i = 0; i < run.size(); ++i) {
      CAPTURE(i);
      REQUIRE(back[i].clips.size() == 1);
      // Joint names carry the "character<i>:" prefix in a file with several characters; compare by name.
      Clip read = back[i].clips[0];
      if (run.size() > 1) {
        auto renamed = std::make_shared<Skeleton>(*read.skeleton);
        const std::string prefix = "character" + std::to_string(i) + ":";
        for (Joint& j : renamed->joints)
          if (j.name.rfind(prefix, 0) == 0) j.name = j.name.substr(prefix.size());
        read.skeleton = renamed;
      }
      const test::PoseDifference d = test::clip_difference(run[i], read);
      CHECK(d.position < 1e-4f);
      CHECK(d.rotation < 1e-4f);
    }

    const std::vector<std::string> bvhs = export_motion(test::scratch(std::string("scenario_") + name + ".bvh"), run);
    REQUIRE(bvhs.size() == run.size());
    BvhReadOptions options;
    options.unit_scale = 0.01f;  // write_bvh writes centimetres
    for (size_t i = 0; i < run.size(); ++i) {
      const test::PoseDifference d = test::clip_difference(run[i], read_bvh(bvhs[i], options));
      CHECK(d.position < 1e-4f);
      CHECK(d.rotation < 1e-4f);
    }
  }
}

}  // namespace
}  // namespace prep
