// The crowd: lanes that never meet, stepped on two threads exactly as on one, every character preparing,
// and lanes that start over when their run is done.
#include "engine/world/crowd.h"

#include <doctest/doctest.h>

#include <algorithm>
#include <vector>

#include <glm/geometric.hpp>

#include "engine/util/error.h"
#include "engine/world/policy_cache.h"
#include "tests/support/paths.h"

using namespace prep;

namespace {

struct Stadium {
  Scenario lane = load_scenario(test::repo() + "/assets/scenarios/stadium.json");
  std::shared_ptr<const WorldAssets> assets =
      prepare_world_assets(lane, load_scenario_params(lane), test::tmp_dir() + "/policy-cache");
};

CrowdOptions options_with(int lanes, int threads) {
  CrowdOptions o;
  o.lanes = lanes;
  o.threads = threads;
  o.seed = 5;
  return o;
}

}  // namespace

TEST_CASE("crowd: each lane's contents stay in its own cell, the cells tile the crowd's rectangle") {
  const Stadium s;
  const Crowd crowd(s.lane, s.assets, options_with(13, 1));
  REQUIRE(crowd.lanes() == 13);
  std::vector<glm::vec4> boxes;  // per lane: min x, min z, max x, max z of its characters, objects and goal
  for (int i = 0; i < crowd.lanes(); ++i) {
    const World& w = crowd.lane(i);
    glm::vec2 low(1e9f), high(-1e9f);
    auto add = [&](glm::vec2 p, float r) {
      low = glm::min(low, p - glm::vec2(r));
      high = glm::max(high, p + glm::vec2(r));
    };
    for (const WorldCharacter& c : w.characters()) add(c.position, 0.3f);
    for (const WorldObject& o : w.objects()) add({o.position.x, o.position.z}, 0.5f * std::max(o.spec.size.x, o.spec.size.z));
    for (const glm::vec2& g : w.scenario().goal) add(g, 0.0f);
    CHECK(low.x >= crowd.low().x);
    CHECK(low.y >= crowd.low().y);
    CHECK(high.x <= crowd.high().x);
    CHECK(high.y <= crowd.high().y);
    boxes.push_back({low.x, low.y, high.x, high.y});
  }
  for (size_t a = 0; a < boxes.size(); ++a) {
    for (size_t b = a + 1; b < boxes.size(); ++b) {
      const bool apart = boxes[a].z + 0.5f <= boxes[b].x || boxes[b].z + 0.5f <= boxes[a].x ||
                         boxes[a].w + 0.5f <= boxes[b].y || boxes[b].w + 0.5f <= boxes[a].y;
      CAPTURE(a);
      CAPTURE(b);
      CHECK(apart);  // at least half a metre between any two lanes' contents
    }
  }
}

TEST_CASE("crowd: two threads step the lanes exactly as one does") {
  const Stadium s;
  Crowd one(s.lane, s.assets, options_with(5, 1));
  Crowd two(s.lane, s.assets, options_with(5, 2));
  for (int tick = 0; tick < 240; ++tick) {
    one.step();
    two.step();
  }
  for (int i = 0; i < 5; ++i) {
    const WorldCharacter& a = one.lane(i).characters().front();
    const WorldCharacter& b = two.lane(i).characters().front();
    CHECK(a.pose.root_position == b.pose.root_position);
    CHECK(a.alpha == b.alpha);
    CHECK(a.pose.rotations == b.pose.rotations);
  }
}

TEST_CASE("crowd: every character prepares, jumps its hurdle and kicks its ball, and done lanes start over") {
  const Stadium s;
  Crowd crowd(s.lane, s.assets, options_with(6, 2));
  std::vector<float> highest_alpha(6, 0.0f);
  std::vector<int> jumps(6, 0), kicks(6, 0);
  std::vector<size_t> launches_seen(6, 0);
  std::vector<const World*> world_seen(6, nullptr);
  const int ticks = static_cast<int>(30.0f / s.assets->params.runtime.fixed_dt);
  for (int tick = 0; tick < ticks; ++tick) {
    crowd.step();
    for (int i = 0; i < 6; ++i) {
      const World& w = crowd.lane(i);
      if (&w != world_seen[static_cast<size_t>(i)]) world_seen[static_cast<size_t>(i)] = &w, launches_seen[static_cast<size_t>(i)] = 0;
      const WorldCharacter& c = w.characters()[static_cast<size_t>(w.user())];
      highest_alpha[static_cast<size_t>(i)] = std::max(highest_alpha[static_cast<size_t>(i)], c.alpha);
      for (size_t k = launches_seen[static_cast<size_t>(i)]; k < w.launches().size(); ++k) {
        jumps[static_cast<size_t>(i)] += w.launches()[k].action == TargetAction::Jump;
        kicks[static_cast<size_t>(i)] += w.launches()[k].action == TargetAction::Kick;
      }
      launches_seen[static_cast<size_t>(i)] = w.launches().size();
    }
  }
  for (size_t i = 0; i < 6; ++i) {
    CAPTURE(i);
    CHECK(highest_alpha[i] > 0.8f);
    CHECK(jumps[i] >= 1);
    CHECK(kicks[i] >= 1);
  }
  // A lane's run takes under 30 s: every lane has started over at least once.
  CHECK(crowd.restarts() >= 6);
}

TEST_CASE("crowd: no lanes, or a lane without a user, is refused by name") {
  const Stadium s;
  CHECK_THROWS_AS(Crowd(s.lane, s.assets, options_with(0, 1)), InputError);
  Scenario no_user = s.lane;
  no_user.characters.clear();
  CHECK_THROWS_WITH_AS(Crowd(no_user, s.assets, options_with(3, 1)), doctest::Contains("stadium.json"), InputError);
}

TEST_CASE("crowd: the lanes' first decisions are spread over kDecisionPhases ticks") {
  // A world whose decisions are delayed plays on without one; the crowd's lanes take their first ones on
  // kDecisionPhases different ticks, one after the other.
  const Stadium s;
  Crowd crowd(s.lane, s.assets, options_with(2 * Crowd::kDecisionPhases, 1));
  std::vector<int> first_decision(static_cast<size_t>(crowd.lanes()), -1);
  for (int tick = 0; tick < Crowd::kDecisionPhases + 2; ++tick) {
    crowd.step();
    for (int i = 0; i < crowd.lanes(); ++i) {
      const WorldCharacter& user = crowd.lane(i).characters()[static_cast<size_t>(crowd.lane(i).user())];
      if (first_decision[static_cast<size_t>(i)] < 0 && user.motion >= 0) first_decision[static_cast<size_t>(i)] = tick;
    }
  }
  for (int i = 0; i < crowd.lanes(); ++i) {
    CAPTURE(i);
    CHECK(first_decision[static_cast<size_t>(i)] == i % Crowd::kDecisionPhases);
  }
}

TEST_CASE("crowd: a lane whose first decision is held starts walking where it stands, whatever tick the decision comes") {
  // A lane away from the origin (as every lane but the crowd's first is) whose first decision is held some
  // ticks: in its first two seconds (walking) the character never moves 0.1 m in a tick (6 m/s). The stream's
  // first step was once taken from the origin, and a decision on the second tick (held one tick) carried
  // the character by it: metres in one tick.
  const Stadium s;
  Scenario away = s.lane;
  const glm::vec2 offset(-4.0f, -9.0f);
  for (ScenarioCharacter& c : away.characters) c.position += offset;
  for (ScenarioObject& o : away.objects) o.position += offset;
  for (glm::vec2& g : away.goal) g += offset;
  for (int held = 0; held < 4; ++held) {
    CAPTURE(held);
    World world(away, s.assets);
    world.set_auto(true);
    world.hold_decisions(held);
    glm::vec2 last = world.characters()[static_cast<size_t>(world.user())].position;
    float largest_step = 0.0f;
    for (int tick = 0; tick < 120; ++tick) {
      world.step();
      const glm::vec2 now = world.characters()[static_cast<size_t>(world.user())].position;
      largest_step = std::max(largest_step, glm::length(now - last));
      last = now;
    }
    CHECK(largest_step < 0.1f);
  }
}
