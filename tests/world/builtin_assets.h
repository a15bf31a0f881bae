// The built-in library's assets and policy as the obstacles scenario loads them, shared by the world tests:
// made once per test binary (the policy is cached under the build's scratch folder, keyed by the Params
// hash, so reruns skip training).
#pragma once

#include <memory>

#include "engine/world/scenario.h"
#include "engine/world/world.h"
#include "tests/support/paths.h"

namespace prep::test {

inline std::shared_ptr<const WorldAssets> builtin_assets() {
  static std::shared_ptr<const WorldAssets> assets = [] {
    const Scenario s = load_scenario(repo() + "/assets/scenarios/obstacles.json");
    return prepare_world_assets(s, load_scenario_params(s), tmp_dir() + "/policy-cache");
  }();
  return assets;
}

}  // namespace prep::test
