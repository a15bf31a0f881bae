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

// A unit rotation read from a file, as floats, with every component of magnitude below
// kNegligibleComponent set to zero. Converters write channels that do not move as rotations of 1e-16
// degrees and the like; their quaternion components come out near 1e-39, subnormal floats. x86 processors
// compute with a subnormal operand or result through a microcode assist of about a hundred cycles, and
// each product with such a component at run time is one: on a 43-joint CMU set whose BVH files are full
// of them, synthesis ran twice as slow. A component of 1e-9 turns the rotation by 2e-9 rad at most.
constexpr double kNegligibleComponent = 1e-9;
glm::quat without_negligible_components(const glm::dquat& unit);

// Heading (yaw about +Y, radians) of a root rotation: the angle of its forward axis (+Z) on the floor.
float heading_of(const glm::quat& root_rotation);

}  // namespace prep
