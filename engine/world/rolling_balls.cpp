// Kicked balls roll: they slow down on the grass and bounce off what they meet (an obstacle's posts, legs,
// feet and low board, a body, another ball) instead of passing through it.
#include <algorithm>
#include <cmath>

#include "engine/world/clearance.h"
#include "engine/world/floor.h"
#include "engine/world/world.h"
#include "engine/world/world_runtime.h"

namespace prep {

using floor_plane::floor_xz;

namespace {

constexpr float kRollingResistance = 1.5f;   // m/s^2: a ball slowing on grass
// The share of the speed into a surface that a ball keeps away from it: off wood or metal (an obstacle's
// parts), off a body (soft, and heavy against a light ball), off another ball (equal masses).
constexpr float kObstacleRestitution = 0.5f;
constexpr float kBodyRestitution = 0.3f;
constexpr float kBallRestitution = 0.8f;
// A ball moves at most this share of its radius between two checks: at a kick's 6-13 m/s it would
// otherwise go 10-22 cm in a tick, through a 3 cm board or a 4 cm hurdle leg.
constexpr float kSubstepOfRadius = 0.5f;
constexpr float kBallSkin = 0.001f;  // m: a ball set out of what it met is left this far clear of it
constexpr float kBodyReach = 1.6f;   // m: no capsule is farther than this from the root on the floor

// Where a ball meets something: how deep it is in it and the way out on the floor (unit; zero when the
// only way out is up or down, which a rolling ball does not take).
struct BallContact {
  float depth = 0.0f;
  glm::vec2 out{0.0f};
};

// The way out on the floor along a 3D direction from the thing met toward the ball's centre.
glm::vec2 out_on_floor(glm::vec3 direction) {
  const glm::vec2 d(direction.x, direction.z);
  const float length = glm::length(d);
  return length > 1e-6f ? d / length : glm::vec2(0.0f);
}

// A ball (centre, radius) against a box solid, both in the box's object frame; the way out in that frame.
BallContact ball_in_box(glm::vec3 centre, float radius, const ObjectSolid& box) {
  const glm::vec3 half = 0.5f * box.extents, from_middle = centre - box.centre;
  const glm::vec3 nearest = glm::clamp(from_middle, -half, half);
  const glm::vec3 gap = from_middle - nearest;
  const float distance = glm::length(gap);
  BallContact contact;
  if (distance >= radius) return contact;
  if (distance > 1e-6f) {
    contact.depth = radius - distance;
    contact.out = out_on_floor(gap);
    return contact;
  }
  // The centre inside the box (only where a ball starts there): out through the nearer side, along the width
  // or the depth.
  const float to_x = half.x - std::abs(from_middle.x), to_z = half.z - std::abs(from_middle.z);
  if (to_x < to_z) {
    contact.depth = to_x + radius;
    contact.out = glm::vec2(from_middle.x >= 0.0f ? 1.0f : -1.0f, 0.0f);
  } else {
    contact.depth = to_z + radius;
    contact.out = glm::vec2(0.0f, from_middle.z >= 0.0f ? 1.0f : -1.0f);
  }
  return contact;
}

// A ball against a sphere (another ball) or a capsule (a body part), in one frame.
BallContact ball_in_capsule(glm::vec3 centre, float radius, glm::vec3 a, glm::vec3 b, float capsule_radius) {
  const glm::vec3 gap = centre - closest_on_segment(centre, a, b);
  const float distance = glm::length(gap);
  BallContact contact;
  if (distance >= radius + capsule_radius) return contact;
  contact.depth = radius + capsule_radius - distance;
  contact.out = out_on_floor(gap);
  return contact;
}

// The velocity after meeting a surface whose way out is `out`: the part into it reversed and scaled by the
// restitution; a ball already leaving keeps its velocity.
glm::vec2 bounced(glm::vec2 velocity, glm::vec2 out, float restitution) {
  const float into = glm::dot(velocity, out);
  return into < 0.0f ? velocity - (1.0f + restitution) * into * out : velocity;
}

// A ball's object frame turned to the world's floor: the object's X axis is (cos h, -sin h), its Z axis
// (sin h, cos h) (ObjectFrame).
glm::vec2 to_world_floor(const ObjectFrame& frame, glm::vec2 local) {
  return {frame.cos_heading * local.x + frame.sin_heading * local.y, -frame.sin_heading * local.x + frame.cos_heading * local.y};
}

}  // namespace

// A rolling ball against the obstacles' solids and the other balls (in each object's frame): the push that
// sets it out of what it has gone into, its velocity bounced off it. A ball no one has kicked yet stays where
// it lies when another meets it (the other bounces off it): the kick it waits for is aimed at where it was
// set, and a ball rolling away from its kicker would be chased. Kicked ones share the blow as equal masses.
glm::vec2 World::ball_meets_objects(size_t k, glm::vec3 centre, float radius) {
  WorldObject& ball = objects_[k];
  glm::vec2 push(0.0f);
  for (size_t j = 0; j < objects_.size(); ++j) {
    if (j == k) continue;
    WorldObject& other = objects_[j];
    const bool other_ball = other.spec.type == ObjectType::Ball;
    if (!(floor_plane::is_across(other.spec.type) || other_ball)) continue;
    const ObjectFrame frame(floor_xz(other.position), other.spec.heading);
    const glm::vec3 local = frame.to_local(centre);
    for (const ObjectSolid& solid : solids_[j]) {
      const BallContact c = solid.sphere ? ball_in_capsule(local, radius, solid.centre, solid.centre, 0.5f * solid.extents.x)
                                         : ball_in_box(local, radius, solid);
      if (c.depth <= 0.0f || c.out == glm::vec2(0.0f)) continue;
      const glm::vec2 out = to_world_floor(frame, c.out);
      push += (c.depth + kBallSkin) * out;
      if (other_ball && other.used) {
        // Equal masses: each keeps (1 - e) / 2 of its own speed along the line between them and takes
        // (1 + e) / 2 of the other's.
        const float mine = glm::dot(ball.velocity, out), theirs = glm::dot(other.velocity, out);
        if (mine < theirs) {
          const float exchange = 0.5f * (1.0f + kBallRestitution) * (theirs - mine);
          ball.velocity += exchange * out;
          other.velocity -= exchange * out;
        }
      } else {
        ball.velocity = bounced(ball.velocity, out, other_ball ? kBallRestitution : kObstacleRestitution);
      }
    }
  }
  return push;
}

// A rolling ball against the bodies as the last tick left them (their capsules placed once per tick, in
// keep_bodies_apart's scratch): the push out of them, its velocity bounced off them.
glm::vec2 World::ball_meets_bodies(size_t k, glm::vec3 centre, float radius) {
  WorldObject& ball = objects_[k];
  const glm::vec2 at(centre.x, centre.z);
  glm::vec2 push(0.0f);
  for (size_t i = 0; i < characters_.size(); ++i) {
    const WorldCharacter& c = characters_[i];
    if (glm::length(c.position - at) > kBodyReach + radius) continue;
    Runtime& rt = *runtime_[i];
    // Its kicker's foot and the ball part at the strike, and the follow-through is slower than the ball:
    // while the ball moves away from its kicker in the kick, the two do not meet (one coming back does).
    if (c.in_target && c.playing == TargetAction::Kick && rt.target_object == static_cast<int>(k) &&
        glm::dot(ball.velocity, at - c.position) > 0.0f)
      continue;
    if (!body_placed_[i]) {
      place_body(static_cast<int>(i), body_low_[i], body_high_[i]);
      body_placed_[i] = 1;
    }
    const glm::vec2 low = body_low_[i], high = body_high_[i];
    if (at.x + radius < low.x || at.x - radius > high.x || at.y + radius < low.y || at.y - radius > high.y) continue;
    for (const PlacedCapsule& capsule : rt.capsules) {
      const BallContact contact = ball_in_capsule(centre, radius, capsule.a, capsule.b, capsule.radius);
      if (contact.depth <= 0.0f || contact.out == glm::vec2(0.0f)) continue;
      push += (contact.depth + kBallSkin) * contact.out;
      ball.velocity = bounced(ball.velocity, contact.out, kBodyRestitution);
    }
  }
  return push;
}

// Each tick a rolling ball slows down, then moves along its velocity in steps of at most half its radius;
// after each step it is set out of whatever it has gone into and bounces off it. The balls move before the
// characters step: a ball struck this tick is still where the foot met it in this tick's frame, and leaves
// on the next.
void World::roll_balls() {
  const float dt = params_.runtime.fixed_dt;
  body_low_.resize(characters_.size());
  body_high_.resize(characters_.size());
  for (size_t k = 0; k < objects_.size(); ++k) {
    WorldObject& ball = objects_[k];
    const float speed = glm::length(ball.velocity);
    if (speed <= 0.0f) continue;
    const float slower = std::max(0.0f, speed - kRollingResistance * dt);
    ball.velocity *= slower / speed;
    if (!params_.runtime.keep_clear) {  // rolls through everything
      ball.position.x += ball.velocity.x * dt;
      ball.position.z += ball.velocity.y * dt;
      continue;
    }
    const float radius = 0.5f * solids_[k].front().extents.x;
    const int steps = std::max(1, static_cast<int>(std::ceil(slower * dt / (kSubstepOfRadius * radius))));
    const glm::vec2 start = floor_xz(ball.position), velocity_at_start = ball.velocity;
    bool met = false;  // once it has met something its path is its own; before, it is the tick's straight line
    glm::vec2 at = start;
    body_placed_.assign(characters_.size(), 0);
    for (int step = 1; step <= steps; ++step) {
      if (met) {
        at += ball.velocity * (dt / static_cast<float>(steps));
      } else if (step < steps) {
        at = start + velocity_at_start * (dt * static_cast<float>(step) / static_cast<float>(steps));
      } else {  // untouched, the tick ends where one whole step of the velocity takes it
        at = glm::vec2(ball.position.x + velocity_at_start.x * dt, ball.position.z + velocity_at_start.y * dt);
      }
      const glm::vec3 centre(at.x, radius, at.y);
      const glm::vec2 push = ball_meets_objects(k, centre, radius) + ball_meets_bodies(k, centre, radius);
      met = met || push != glm::vec2(0.0f);
      at += push;
    }
    ball.position.x = at.x;
    ball.position.z = at.y;
  }
}

}  // namespace prep
