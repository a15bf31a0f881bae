// The player at the steering keys of headless runs (engine/world/key_player.h).
#include <doctest/doctest.h>

#include <cmath>
#include <vector>

#include "engine/world/key_player.h"
#include "engine/world/world.h"
#include "tests/world/builtin_assets.h"

using namespace prep;

namespace {

const char* kCourse =
    "{\"auto\": true, \"characters\": [{\"position\": [0, 0], \"heading\": 0, \"control\": \"user\"}], "
    "\"objects\": [{\"type\": \"bar\", \"position\": [0.0, 5.0], \"heading\": 20, \"size\": [3.0, 0.72, 0.08]}], "
    "\"goal\": [0.5, 9.0]}";

// The held directions, tick by tick, and the user's last position.
struct Hands {
  std::vector<glm::vec2> held;
  glm::vec2 end{0.0f};
};

Hands play(std::uint64_t seed, float seconds, bool check_goal) {
  World world(parse_scenario(kCourse, "keys"), test::builtin_assets());
  const float dt = world.params().runtime.fixed_dt;
  KeyPlayer keys(seed, {0.5f, 9.0f});
  Hands hands;
  for (int t = 0; t < static_cast<int>(seconds / dt); ++t) {
    const glm::vec2 from = world.characters()[0].position;
    keys.before_tick(world, dt);
    hands.held.push_back(keys.held());
    if (check_goal && keys.held() != glm::vec2(0.0f)) {
      // The goal kSteerLead ahead of the user in the held direction, as the demo's steering places it.
      REQUIRE(!world.characters()[0].goal.empty());
      CHECK(glm::length(world.characters()[0].goal.front() - (from + kSteerLead * keys.held())) < 1e-5f);
    }
    world.step();
  }
  hands.end = world.characters()[0].position;
  return hands;
}

}  // namespace

TEST_CASE("the key player holds one of the eight key directions, or none, for a while, mostly toward the goal") {
  const Hands hands = play(7, 20.0f, true);
  // Over many holds (no world needed): the shares of each kind of hold.
  World world(parse_scenario(kCourse, "keys"), test::builtin_assets());
  KeyPlayer keys(11, {0.5f, 9.0f});
  const float dt = world.params().runtime.fixed_dt;
  int holds = 0, toward = 0, let_go = 0;
  glm::vec2 last(-9.0f);
  float held_for = 0.0f, shortest = 1e9f, longest = 0.0f;
  for (int t = 0; t < 60 * 600; ++t) {
    keys.before_tick(world, dt);
    const glm::vec2 h = keys.held();
    const float length = glm::length(h);
    CHECK((length == 0.0f || std::fabs(length - 1.0f) < 1e-6f));
    if (length > 0.0f) {
      // One of the eight: a multiple of 45 degrees.
      const float eighths = std::atan2(h.y, h.x) / (0.25f * 3.14159265f);
      CHECK(std::fabs(eighths - std::round(eighths)) < 1e-4f);
    }
    if (h != last) {
      if (holds > 0) {
        shortest = std::min(shortest, held_for);
        longest = std::max(longest, held_for);
      }
      ++holds;
      // The user stays at its start here: toward the goal is the key direction nearest (0.5, 9), +z.
      toward += glm::length(h - glm::vec2(0.0f, 1.0f)) < 1e-4f;
      let_go += length == 0.0f;
      held_for = 0.0f;
      last = h;
    }
    held_for += dt;
  }
  // Holds of one direction after another of the same direction run together, so the shares are of changes.
  CHECK(holds > 150);
  CHECK(toward > holds / 4);
  CHECK(let_go > 0);
  CHECK(let_go < holds / 4);
  CHECK(shortest >= KeyPlayer::kShortestHold - 1.5f * dt);
  CHECK(longest >= KeyPlayer::kShortestHold);
  CHECK(hands.held.size() == static_cast<size_t>(20.0f / dt));
}

TEST_CASE("the key player's seed gives the same hands and the same run, and another seed other ones") {
  const Hands a = play(3, 15.0f, false), b = play(3, 15.0f, false), c = play(4, 15.0f, false);
  CHECK(a.held == b.held);
  CHECK(a.end == b.end);
  CHECK(a.held != c.held);
  // It walks: the user has left its start.
  CHECK(glm::length(a.end) > 1.0f);
}
