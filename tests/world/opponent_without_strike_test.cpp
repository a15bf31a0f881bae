// An opponent whose strike the motion set has no clip for takes no part (World::stands_aside): daz43
// records kicks and jumps but no punch, and a user sent to fight such an opponent circled it for good.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <random>
#include <string>

#include "engine/world/clearance.h"
#include "engine/world/world.h"
#include "tests/support/paths.h"

using namespace prep;

TEST_CASE("an opponent the set has no strike for stands where it is, and the user passes it to the goal") {
  Scenario probe;
  probe.motions = test::repo() + "/assets/manifests/daz43.json";
  probe.params_file = test::repo() + "/assets/scenarios/controller_daz43.json";
  const std::shared_ptr<const WorldAssets> assets =
      prepare_world_assets(probe, load_scenario_params(probe), test::tmp_dir() + "/policy-cache");
  REQUIRE(assets->target(TargetAction::PunchLeft).clip < 0);
  REQUIRE(assets->target(TargetAction::PunchRight).clip < 0);
  std::mt19937 rng(43);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (int k = 0; k < 4; ++k) {
    // An opponent 4-8 m ahead, up to 1 m aside; the goal 3-5 m beyond it.
    const float ahead = 4.0f + 4.0f * u(rng), aside = (u(rng) - 0.5f) * 2.0f;
    const float goal_x = (u(rng) - 0.5f) * 2.0f, goal_z = ahead + 3.0f + 2.0f * u(rng);
    char text[768];
    std::snprintf(text, sizeof text,
                  "{\"auto\": true, \"characters\": [{\"position\": [0, 0], \"control\": \"user\"}], "
                  "\"objects\": [{\"type\": \"opponent\", \"action\": \"%s\", \"position\": [%.3f, %.3f], \"heading\": 180}], "
                  "\"goal\": [%.3f, %.3f]}",
                  k % 2 ? "punch_left" : "punch_right", aside, ahead, goal_x, goal_z);
    CAPTURE(text);
    Scenario scenario = parse_scenario(text, "opponent-without-strike");
    scenario.motions = probe.motions;
    scenario.params_file = probe.params_file;
    World world(scenario, assets);
    ClearanceLog log(world);
    const int opponent = world.user() == 0 ? 1 : 0;
    const glm::vec2 start = world.characters()[static_cast<size_t>(opponent)].position;
    float farthest = 0.0f;  // the opponent from where it started
    world.run_until_done(60.0f, 1.0f, [&](const World& w) {
      log.observe(w);
      farthest = std::max(farthest, glm::length(w.characters()[static_cast<size_t>(opponent)].position - start));
    });
    CHECK(world.goal_reached());
    CHECK(world.launches().empty());
    CHECK_FALSE(world.characters()[static_cast<size_t>(world.user())].has_source);
    // It stands: what moves it is the user passing it (kept a person's space apart).
    CHECK(farthest < kPersonalSpace);
    CHECK(log.summary.character_frames == 0);
  }
}
