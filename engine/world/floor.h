// Floor-plane helpers shared by the world's files (headings in radians about +Y: a character at heading h
// faces (sin h, 0, cos h)). Internal to engine/world (and the demo, which steers the same headings). Defined
// here once, not per file, so that the module's .cpp files can share a translation unit (unity build).
#pragma once

#include <cmath>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "engine/world/scenario.h"

namespace prep::floor_plane {

constexpr float kPi = 3.14159265358979f;
constexpr float kDegrees = kPi / 180.0f;  // degrees to radians

inline glm::vec2 forward_of(float heading) { return {std::sin(heading), std::cos(heading)}; }
inline glm::vec2 left_of(float heading) { return {std::cos(heading), -std::sin(heading)}; }
inline glm::vec2 floor_xz(const glm::vec3& p) { return {p.x, p.z}; }
inline float wrap_angle(float a) {  // to (-pi, pi]
  a = std::fmod(a + kPi, 2.0f * kPi);
  if (a < 0.0f) a += 2.0f * kPi;
  return a - kPi;
}
// The way across an obstacle standing at `at`, turned `heading`, for one coming from `from`: its normal,
// pointing from `from`'s side to the other.
inline glm::vec2 crossing_direction(float heading, glm::vec2 at, glm::vec2 from) {
  const glm::vec2 n = forward_of(heading);
  return glm::dot(at - from, n) < 0.0f ? -n : n;
}
// Bars, beams and hurdles are crossed (along their normal); balls and opponents are met.
inline bool is_across(ObjectType t) { return t == ObjectType::Bar || t == ObjectType::Beam || t == ObjectType::Hurdle; }

}  // namespace prep::floor_plane
