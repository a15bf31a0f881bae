// A manifest is all a scenario needs: no Params file names the controller's core motions, which default
// to the set's own, whether the manifest is ours or one `prep manifest` wrote.
#include <doctest/doctest.h>

#include <filesystem>
#include <string>

#include "engine/scan/folder_scan.h"
#include "engine/util/files.h"
#include "engine/world/world.h"
#include "tests/support/paths.h"

using namespace prep;
namespace fs = std::filesystem;

namespace {

const std::string kBall = "[0.22, 0.22, 0.22]";
const std::string kHurdle = "[3.0, 0.45, 0.1]";

// A kick (or another target) at 6 m straight ahead, its object the goal too, launched automatically.
std::string scenario_text(const std::string& motions, const std::string& type, const std::string& action,
                          const std::string& size) {
  return R"({"name": "manifest only", "auto": true, "motions": ")" + motions + R"(",
    "characters": [{"position": [0, 0], "heading": 0, "control": "user"}],
    "objects": [{"type": ")" + type + R"(", "action": ")" + action + R"(", "position": [0, 6], "size": )" + size + R"(}],
    "goal": [0, 8]})";
}

// Runs the scenario for 30 s and returns the alpha at its one launch.
float launch_alpha(const std::string& text, const std::string& source) {
  const Scenario scenario = parse_scenario(text, source);
  REQUIRE(scenario.params_file.empty());
  const Params params = load_scenario_params(scenario);
  CHECK(params.quantization.core_roles.empty());  // the set's own core motions
  const auto assets = prepare_world_assets(scenario, params, test::tmp_dir() + "/policy-cache");
  World world(scenario, assets);
  for (int k = 0; k < static_cast<int>(30.0f / params.runtime.fixed_dt); ++k) world.step();
  const RunSummary summary = summarize(world);
  REQUIRE(summary.launches.size() == 1);
  MESSAGE(source << ": " << std::string(target_action_name(summary.launches[0].action)) << " at alpha " << summary.launches[0].alpha_at_launch);
  CHECK(summary.goal_reached);
  return summary.launches[0].alpha_at_launch;
}

}  // namespace

TEST_CASE("a scenario naming only our daz43 manifest, with no Params file, kicks at alpha 0.85 or more") {
  CHECK(launch_alpha(scenario_text("assets/manifests/daz43.json", "ball", "kick", kBall), "daz43 kick") >= 0.85f);
}

TEST_CASE("a scenario naming only a manifest prep manifest wrote jumps its hurdle and kicks at alpha 0.85 or more") {
  for (const char* folder : {"cmu31", "daz43"}) {
    CAPTURE(std::string(folder));
    const FolderScan scan = scan_motion_folder(test::mocap() + "/" + folder, Params{});
    const std::string out = test::tmp_dir() + "/scanned-sets/" + folder + "/set.json";
    fs::create_directories(fs::path(out).parent_path());
    write_file_atomic(out, scan_manifest_json(scan, out).dump(2));
    const std::string manifest = fs::absolute(out).string();
    const bool cmu = std::string(folder) == "cmu31";
    const std::string text = cmu ? scenario_text(manifest, "hurdle", "jump", kHurdle) : scenario_text(manifest, "ball", "kick", kBall);
    CHECK(launch_alpha(text, std::string("scanned ") + folder) >= 0.85f);
  }
}
