// The solid parts of a scenario object: the boxes of a bar's or beam's rail and posts, of a hurdle's
// board, legs and feet, and a ball's sphere, in the object's own frame. The renderer draws these boxes and
// the clearance measure (clearance.h) tests bodies against them: one geometry for both.
//
// Object frame: origin on the floor at the object's position, +Y up, X along its width, Z its crossing
// direction (scenario.h: at heading 0 an obstacle spans the X axis and is crossed walking along +Z).
#pragma once

#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "engine/world/scenario.h"

namespace prep {

enum class SolidPart { Rail, Post, Board, Leg, Foot, Ball };
const char* solid_part_name(SolidPart part);  // "rail", "post", ...

struct ObjectSolid {
  SolidPart part = SolidPart::Rail;
  bool sphere = false;       // a ball: centre and radius = extents.x / 2
  glm::vec3 centre{0.0f};    // in the object's frame
  glm::vec3 extents{0.0f};   // full sizes along X, Y, Z
};

// Sizes of the parts the scenario does not give (m).
constexpr float kPostWidth = 0.07f;        // a bar's or beam's posts, square
constexpr float kDefaultRail = 0.08f;      // a bar's or beam's rail, when the size gives no depth
constexpr float kHurdleBoard = 0.12f;      // a hurdle's board, top down
constexpr float kHurdleLeg = 0.04f;
constexpr float kHurdleFootLength = 0.5f;  // along the crossing direction, on the floor
constexpr float kHurdleFootHeight = 0.03f;

// An opponent object has no solids (it is a character).
std::vector<ObjectSolid> object_solids(ObjectType type, glm::vec3 size);

// A point of the world in an object's frame (position on the floor (x, z), heading radians).
glm::vec3 to_object_frame(glm::vec3 world, glm::vec2 position, float heading);
// The same with the heading's cosine and sine taken once, for many points in one object's frame.
struct ObjectFrame {
  ObjectFrame(glm::vec2 position, float heading);
  glm::vec3 to_local(glm::vec3 world) const;
  glm::vec2 position;
  float cos_heading, sin_heading;
};

}  // namespace prep
