// Analytic two-bone inverse kinematics (thigh-shin, upper arm-forearm) with a hinge middle joint.
#pragma once

#include <glm/gtc/quaternion.hpp>
#include <glm/vec3.hpp>

namespace prep::library {

struct TwoBoneChain {
  float upper_length = 0;  // root joint -> middle joint
  float lower_length = 0;  // middle joint -> end joint
  glm::vec3 rest_direction{0, -1, 0};  // the upper bone's direction in its own frame (the child's offset, normalized)
  glm::vec3 hinge_axis{1, 0, 0};       // the middle joint's hinge in its frame: + rotation flexes it
};

struct TwoBoneSolution {
  glm::quat upper_world{1, 0, 0, 0};  // world rotation of the upper bone's joint
  float hinge_angle = 0;              // flexion of the middle joint (>= 0)
  bool reached = true;                // false when the target was out of reach (the limb ends straight toward it)
};

// Places the end joint at `target` from the root joint at `root`. The middle joint bends toward
// `bend_hint` (a world direction, e.g. the front of the thigh for a knee); the hinge stays perpendicular
// to the plane of the limb, so the middle joint is a pure hinge.
TwoBoneSolution solve_two_bone(const TwoBoneChain& chain, glm::vec3 root, glm::vec3 target, glm::vec3 bend_hint);

}  // namespace prep::library
