#include "engine/world/steering.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "engine/world/floor.h"

namespace prep {

namespace {
using floor_plane::kPi;
}

float bearing_to(glm::vec2 position, float heading, glm::vec2 target) {
  const glm::vec2 d = target - position;
  float b = std::atan2(d.x, d.y) - heading;
  while (b > kPi) b -= 2.0f * kPi;
  while (b <= -kPi) b += 2.0f * kPi;
  return b;
}

bool inside_turning_circle(glm::vec2 position, float heading, glm::vec2 goal, float turning_radius) {
  const float d = glm::length(goal - position);
  const float b = bearing_to(position, heading, goal);
  if (d < 2.0f * turning_radius * std::fabs(std::sin(b))) return true;  // inside the circle on its side
  return std::fabs(b) > 0.5f * kPi && d < 2.0f * turning_radius;        // behind, within a U-turn's width
}

TightTurn tight_turn(glm::vec2 position, float heading, glm::vec2 goal, float turning_radius, float max_rate,
                     bool turn_back) {
  TightTurn t;
  if (max_rate <= 0.0f) return t;
  const float b = bearing_to(position, heading, goal);
  const bool inside = inside_turning_circle(position, heading, goal, turning_radius);
  const bool near = glm::length(goal - position) < kNearGoal && std::fabs(b) > kNearBearing;
  const bool behind = turn_back && std::fabs(b) > kTurnBack;
  if (!inside && !near && !behind) return t;
  t.rate = std::clamp(b / kTightTurnTime, -max_rate, max_rate);
  if (inside || behind) t.stride = std::max(kTightStride, std::cos(std::min(std::fabs(b), 0.5f * kPi)));
  return t;
}

float squaring_rate(float heading, float crossing_heading, float max_rate) {
  float d = crossing_heading - heading;
  while (d > kPi) d -= 2.0f * kPi;
  while (d <= -kPi) d += 2.0f * kPi;
  if (max_rate <= 0.0f || std::fabs(d) < kSquareTolerance) return 0.0f;
  return std::clamp(d / kTightTurnTime, -max_rate, max_rate);
}

bool passed_waypoint(glm::vec2 position, float heading, glm::vec2 waypoint, float pass_radius) {
  if (glm::length(waypoint - position) > pass_radius) return false;
  return std::fabs(bearing_to(position, heading, waypoint)) >= kPassedBearing;
}

}  // namespace prep
