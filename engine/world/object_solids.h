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

#include "engine/motion/vector_ops.h"
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
  // The same in a register, lane by lane the same operations: the same floats.
  V3 to_local(V3 world) const;
  glm::vec2 position;
  float cos_heading, sin_heading;
};

inline V3 ObjectFrame::to_local(V3 world) const {
#if defined(__SSE2__)
  const float c = cos_heading, s = sin_heading;
  // (dx, y, dz): y less zero is y, its sign included.
  const __m128 d = _mm_sub_ps(world.r, _mm_set_ps(0.0f, position.y, 0.0f, position.x));
  // (c dx, y, c dz) + (-s dz, 0 y, s dx): a - b is a + (-b), a sum is the same either way round, and a
  // zero of y's own sign leaves y as it is.
  const __m128 straight = _mm_mul_ps(d, _mm_set_ps(0.0f, c, 1.0f, c));
  const __m128 crossed = _mm_mul_ps(_mm_shuffle_ps(d, d, _MM_SHUFFLE(3, 0, 1, 2)), _mm_set_ps(0.0f, s, 0.0f, -s));
  return {_mm_add_ps(straight, crossed)};
#else
  return {to_local(world.r)};
#endif
}

}  // namespace prep
