// A pose: the root's translation and one local rotation per joint (quaternions throughout the engine).
#pragma once

#include <glm/gtc/quaternion.hpp>
#include <glm/vec3.hpp>
#include <vector>

namespace prep {

struct Pose {
  glm::vec3 root_position{0.0f};     // world position of joint 0 (metres)
  std::vector<glm::quat> rotations;  // local rotation of each joint relative to its parent; [0] is the root's world rotation

  Pose() = default;
  explicit Pose(int joint_count) : rotations(static_cast<size_t>(joint_count), glm::quat(1, 0, 0, 0)) {}
};

// Interpolates two poses: root position linearly, rotations by slerp on the shorter arc. `out` may be `a` or `b`.
void interpolate(const Pose& a, const Pose& b, float t, Pose& out);

// Heading (yaw about +Y, radians) of a root rotation: the angle of its forward axis (+Z) on the floor.
float heading_of(const glm::quat& root_rotation);

}  // namespace prep
