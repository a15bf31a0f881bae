#include "engine/world/object_solids.h"

#include <algorithm>
#include <cmath>

namespace prep {

const char* solid_part_name(SolidPart part) {
  switch (part) {
    case SolidPart::Rail: return "rail";
    case SolidPart::Post: return "post";
    case SolidPart::Board: return "board";
    case SolidPart::Leg: return "leg";
    case SolidPart::Foot: return "foot";
    case SolidPart::Ball: return "ball";
  }
  return "?";
}

std::vector<ObjectSolid> object_solids(ObjectType type, glm::vec3 size) {
  std::vector<ObjectSolid> solids;
  const float width = std::max(size.x, 0.05f);
  switch (type) {
    case ObjectType::Ball: {
      const float d = std::max(size.x, 0.02f);
      solids.push_back({SolidPart::Ball, true, {0.0f, 0.5f * d, 0.0f}, glm::vec3(d)});
      break;
    }
    case ObjectType::Bar:
    case ObjectType::Beam: {
      // size.y is the rail's underside; the posts reach its top, just outside the width.
      const float clearance = std::max(size.y, 0.0f);
      const float rail = size.z > 0.0f ? size.z : kDefaultRail;
      for (float side : {-1.0f, 1.0f})
        solids.push_back({SolidPart::Post, false, {side * 0.5f * (width + kPostWidth), 0.5f * (clearance + rail), 0.0f},
                          {kPostWidth, clearance + rail, kPostWidth}});
      solids.push_back({SolidPart::Rail, false, {0.0f, clearance + 0.5f * rail, 0.0f}, {width, rail, rail}});
      break;
    }
    case ObjectType::Hurdle: {
      // size.y is the board's top.
      const float top = std::max(size.y, 0.05f);
      const float board = std::min(kHurdleBoard, top);
      const float depth = size.z > 0.0f ? size.z : 0.03f;
      solids.push_back({SolidPart::Board, false, {0.0f, top - 0.5f * board, 0.0f}, {width, board, depth}});
      for (float side : {-1.0f, 1.0f}) {
        solids.push_back({SolidPart::Leg, false, {side * 0.5f * width, 0.5f * top, 0.0f}, {kHurdleLeg, top, kHurdleLeg}});
        solids.push_back({SolidPart::Foot, false, {side * 0.5f * width, 0.5f * kHurdleFootHeight, 0.0f},
                          {0.05f, kHurdleFootHeight, kHurdleFootLength}});
      }
      break;
    }
    case ObjectType::Opponent:
      break;
  }
  return solids;
}

ObjectFrame::ObjectFrame(glm::vec2 at, float heading)
    : position(at), cos_heading(std::cos(heading)), sin_heading(std::sin(heading)) {}

glm::vec3 ObjectFrame::to_local(glm::vec3 world) const {
  // The object's X axis is (cos h, -sin h) on the floor, its Z axis (sin h, cos h): the inverse rotation.
  const float dx = world.x - position.x, dz = world.z - position.y;
  const float c = cos_heading, s = sin_heading;
  return {c * dx - s * dz, world.y, s * dx + c * dz};
}

glm::vec3 to_object_frame(glm::vec3 world, glm::vec2 position, float heading) {
  return ObjectFrame(position, heading).to_local(world);
}

}  // namespace prep
