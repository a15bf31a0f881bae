#include "engine/world/key_player.h"

#include <cmath>

#include "engine/world/world.h"

namespace prep {
namespace {

constexpr float kEighth = 0.25f * 3.14159265f;  // rad between neighbouring key directions

glm::vec2 key_direction(int k) { return {std::cos(kEighth * static_cast<float>(k)), std::sin(kEighth * static_cast<float>(k))}; }

}  // namespace

KeyPlayer::KeyPlayer(std::uint64_t seed, glm::vec2 destination) : rng_(seed), destination_(destination) {}

void KeyPlayer::before_tick(World& world, float dt) {
  const WorldCharacter& user = world.characters()[static_cast<size_t>(world.user())];
  if (hold_left_ <= 0.0f) {
    const float pick = rng_.uniform();
    if (pick < kTowardGoal) {
      const glm::vec2 to = destination_ - user.position;
      // The key direction nearest the bearing (W and D together for a diagonal, as a player presses them).
      held_ = key_direction(static_cast<int>(std::lround(std::atan2(to.y, to.x) / kEighth)));
    } else if (pick < kTowardGoal + kLetGo) {
      held_ = glm::vec2(0.0f);
    } else {
      held_ = key_direction(rng_.below(8));
    }
    hold_left_ = rng_.uniform(kShortestHold, kLongestHold);
  }
  hold_left_ -= dt;
  if (held_ != glm::vec2(0.0f)) world.set_goal(user.position + kSteerLead * held_);
}

}  // namespace prep
