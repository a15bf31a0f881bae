// Floor-plane helpers shared by the world's files (headings in radians about +Y: a character at heading h
// faces (sin h, 0, cos h)). Internal to engine/world.
#pragma once

#include <cmath>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "engine/world/scenario.h"

namespace prep::floor_plane {

constexpr float kPi = 3.14159265358979f;

inline glm::vec2 forward_of(float heading) { return {std::sin(heading), std::cos(heading)}; }
inline glm::vec2 left_of(float heading) { return {std::cos(heading), -std::sin(heading)}; }
inline glm::vec2 floor_xz(const glm::vec3& p) { return {p.x, p.z}; }
// Bars, beams and hurdles are crossed (along their normal); balls and opponents are met.
inline bool is_across(ObjectType t) { return t == ObjectType::Bar || t == ObjectType::Beam || t == ObjectType::Hurdle; }

}  // namespace prep::floor_plane
