// Where the characters of a world make for, and the tight turns on top of their clips (steering.h): the
// steering goal of a user or an opponent, a beaten opponent turning before it steps aside, squaring up to
// what is arrived at, and turning about the stance foot toward a goal the walking turns would circle.
#include <cmath>
#include <optional>
#include <vector>

#include <glm/geometric.hpp>

#include "engine/motion/kinematics.h"
#include "engine/world/floor.h"
#include "engine/world/motion_stream.h"
#include "engine/world/steering.h"
#include "engine/world/world.h"
#include "engine/world/world_runtime.h"

namespace prep {

namespace {
using floor_plane::floor_xz;
using floor_plane::forward_of;
using floor_plane::is_across;
using floor_plane::kPi;
using floor_plane::wrap_angle;
}  // namespace

// A defeated opponent with its way aside still more than kStepAsideTurn off its facing: it turns on the
// spot first. Walked off at once, the walking turn would carry it a stride into the one who hit it.
bool World::turning_to_step_aside(const WorldCharacter& c) {
  if (c.control != Control::Opponent || !c.defeated || c.goal.empty()) return false;
  const glm::vec2 d = c.goal.front() - c.position;
  return std::fabs(wrap_angle(std::atan2(d.x, d.y) - c.heading)) > kStepAsideTurn;
}

// Where the character makes for (none: it stays): the controller's goal, and the tight turns' (steer_tightly).
std::optional<glm::vec2> World::steering_goal(const WorldCharacter& c) const {
  // An opponent makes for the user, or steps aside once defeated (defeat); it stays where it is while an
  // obstacle between them is still to be crossed, or a ball kicked, and it is as near as leaves the user
  // room (waits_its_turn).
  if (c.control == Control::Opponent && c.has_source) {
    if (waits_its_turn(c)) return std::nullopt;
    return character_goal(c);
  }
  if (stands_aside(c)) return std::nullopt;
  // Unattended (auto), the user meets the opponent that is its source, as a player steering with the
  // keys would, until it is defeated (world.h); then the scenario's goal again.
  if (c.control == Control::User && auto_launch_ && c.source_character >= 0) return character_goal(c);
  if (c.goal.empty()) return std::nullopt;
  // Unattended, it makes for a ball in range that is its source and nearer than the waypoint or goal it
  // makes for, too (RuntimeParams::make_for_ball_source); a ball beyond the waypoint is met after it, and a
  // ball that is the goal (Sec. 7.2's kick) is made for as the goal.
  if (params_.runtime.make_for_ball_source && c.control == Control::User && auto_launch_ && c.source_in_range && c.source_object >= 0 &&
      objects_[static_cast<size_t>(c.source_object)].spec.type == ObjectType::Ball &&
      glm::length(c.source_object_position - c.position) < glm::length(c.goal.front() - c.position))
    return character_goal(c);
  return c.goal.front();
}

// Tight turns toward a goal the walking turns cannot reach without circling it (steering.h): the stream
// is turned about the stance foot and its stride shortened, on top of the clip just advanced.
void World::steer_tightly(int index) {
  const WorldCharacter& c = characters_[static_cast<size_t>(index)];
  Runtime& rt = *runtime_[static_cast<size_t>(index)];
  const float dt = params_.runtime.fixed_dt;
  const float max_rate = params_.runtime.tight_turn_deg_per_s * kPi / 180.0f;
  TightTurn turn;
  // Squaring up to the obstacle arrived at comes first (steering.h).
  const bool stepping_aside = max_rate > 0.0f && turning_to_step_aside(c);
  if (stepping_aside) {  // a defeated opponent turns where it stands before it walks off (defeat)
    const glm::vec2 d = c.goal.front() - c.position;
    turn.rate = squaring_rate(c.heading, std::atan2(d.x, d.y), max_rate);
  }
  if (max_rate > 0.0f && c.has_source && c.source_character >= 0 && rt.controller->arrived()) {
    // Two characters arrived at striking distance turn to keep facing each other, once more than
    // kFacingSlack off (the other sways and steps; the punch is turned to it at its launch, start_target).
    const glm::vec2 d = c.source_object_position - c.position;
    if (glm::length(d) > 1e-3f && std::fabs(wrap_angle(std::atan2(d.x, d.y) - c.heading)) > kFacingSlack)
      turn.rate = squaring_rate(c.heading, std::atan2(d.x, d.y), max_rate);
  }
  // A ball within kSquareAhead is faced however it was approached: its kick is aimed along the facing, and
  // a character walking by one off to the side would pass it by (steering.h).
  const bool ball_near = c.source_object >= 0 && c.to_launch < kSquareAhead &&
                         objects_[static_cast<size_t>(c.source_object)].spec.type == ObjectType::Ball;
  if (max_rate > 0.0f && c.control == Control::User && c.has_source && c.source_object >= 0 &&
      (rt.controller->arrived() || ball_near ||
       (c.source_ahead && !rt.beside && !rt.approach_from_far && c.to_launch < kSquareAhead))) {
    const WorldObject& o = objects_[static_cast<size_t>(c.source_object)];
    if (is_across(o.spec.type)) {
      glm::vec2 n = forward_of(o.spec.heading);
      if (glm::dot(c.source_object_position - c.position, n) < 0.0f) n = -n;
      turn.rate = squaring_rate(c.heading, std::atan2(n.x, n.y), max_rate);
    } else if (o.spec.type == ObjectType::Ball) {  // the kick is aimed along the facing: face the ball
      const glm::vec2 d = c.source_object_position - c.position;
      if (glm::length(d) > 1e-3f) turn.rate = squaring_rate(c.heading, std::atan2(d.x, d.y), max_rate);
    }
  }
  const std::optional<glm::vec2> goal = steering_goal(c);
  const bool steering = turn.rate == 0.0f && max_rate > 0.0f && goal && !c.reached_goal && !rt.controller->arrived() &&
                        !(c.source_in_range && c.source_ahead);  // a source's approach is the policy's
  // Beside the part of an obstacle's span a launch may start from (near its end, or past it): the character
  // turns to the launch point and walks along to it (then squares up on arrival), rather than into the end.
  const bool to_span = turn.rate == 0.0f && max_rate > 0.0f && c.control == Control::User && c.has_source && rt.beside &&
                       !rt.controller->arrived();
  if (steering || to_span) {
    const float radius = walking_turn_rate_ > 0.0f ? rt.speed / walking_turn_rate_ : 0.0f;
    // A goal behind is turned to only with no source in range (steering.h).
    turn = tight_turn(c.position, c.heading, to_span ? c.source : *goal, radius, max_rate, !c.source_in_range);
    // Walking along an obstacle to a launch place chosen for its room (launch_lateral), the character turns
    // to it however far it is, at its full stride unless the place is inside the turning circle: the policy
    // sees the source, not the way along the obstacle, and would walk into it.
    if (to_span && rt.room_moved && turn.rate == 0.0f) turn.rate = squaring_rate(c.heading, std::atan2(c.source.x - c.position.x, c.source.y - c.position.y), max_rate);
  }
  rt.stride_scale += dt / (dt + kStrideTime) * (turn.stride - rt.stride_scale);
  if (rt.reseed) return;  // the stream was just restarted: it has no step of its own yet
  const glm::vec3 root = rt.stream.pose().root_position;
  FloorTransform move;
  // The stride: the clip's step this tick, shortened (the root is moved back by the part not taken).
  const glm::vec2 step = floor_xz(root) - floor_xz(rt.synthesis_previous_root);
  move.offset = -(1.0f - rt.stride_scale) * step;
  if (turn.rate != 0.0f) {
    const FrameContacts contacts = rt.stream.contacts();
    const bool left = contacts[kLeft].any(), right = contacts[kRight].any();
    // Single support: pivot on the stance foot. Otherwise, arrived (standing, squaring
    // up): turn on the spot about the root, at a third of the rate, a shuffle of the feet; otherwise a
    // character standing a little off square would never turn and never launch.
    if (left != right || rt.controller->arrived() || stepping_aside) {
      const MotionSet& set = *assets_->set;
      glm::vec2 pivot = floor_xz(root) + move.offset;
      if (left != right) {
        std::vector<glm::vec3>& positions = call_scratch().positions;
        forward_kinematics(*set.skeleton, rt.stream.pose(), positions);
        const glm::vec3 ankle = positions[static_cast<size_t>(set.body.legs[left ? kLeft : kRight].ankle)];
        pivot = floor_xz(ankle) + move.offset;
      } else {
        turn.rate /= 3.0f;
      }
      FloorTransform pivoting;
      pivoting.angle = turn.rate * dt;
      const glm::vec3 turned = pivoting.apply(glm::vec3(pivot.x, 0.0f, pivot.y));
      pivoting.offset = pivot - floor_xz(turned);
      move = move.then(pivoting);
    }
  }
  if (move.angle != 0.0f || glm::length(move.offset) > 0.0f) rt.stream.move(move);
}

}  // namespace prep
