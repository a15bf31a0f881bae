// A player at the steering keys, for headless runs (prep run --keys): someone finding their way round a
// course with the demo's W A S D. It holds one of the eight directions the keys give, or none, for 0.7 to
// 3.7 s at a time: mostly the one nearest the bearing to the course's goal, now and then any other, now and
// then none. Before each tick the user's goal is placed kSteerLead ahead in the held direction, as the
// demo's steering does (WorldSession::steer). Obstacles are then met from every side, along their spans and
// again after they were crossed, which a scenario's goal points alone never do. A seed gives the same hands
// on every machine.
#pragma once

#include <cstdint>

#include <glm/vec2.hpp>

#include "engine/control/random.h"

namespace prep {

class World;

// m the steered goal leads the character: beyond the goal radius and the stopping distance of a walk, so the
// controller keeps walking, and short enough that letting go stops the character soon.
constexpr float kSteerLead = 1.8f;

class KeyPlayer {
 public:
  static constexpr float kShortestHold = 0.7f;  // s
  static constexpr float kLongestHold = 3.7f;   // s
  static constexpr float kTowardGoal = 0.55f;   // the share of holds toward the goal
  static constexpr float kLetGo = 0.1f;         // ... and of keys let go; the rest any of the eight

  // `destination`: where the player is making for (a course's last goal point).
  KeyPlayer(std::uint64_t seed, glm::vec2 destination);

  // The direction held this tick (a new one once the last hold is over, dt seconds a tick), and the user's
  // goal placed ahead in it while one is held.
  void before_tick(World& world, float dt);

  glm::vec2 held() const { return held_; }  // a unit key direction on the floor (x, z), or zero: let go

 private:
  Rng rng_;
  glm::vec2 destination_;
  glm::vec2 held_{0.0f};
  float hold_left_ = 0.0f;
};

}  // namespace prep
