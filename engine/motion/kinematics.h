// Forward kinematics: local pose -> world-space joint positions and rotations.
#pragma once

#include <glm/gtc/quaternion.hpp>
#include <glm/vec3.hpp>
#include <vector>

#include "engine/motion/pose.h"
#include "engine/motion/skeleton.h"

namespace prep {

// World position of every joint. If world_rotations is given it receives every joint's world rotation.
// Output vectors are resized to the joint count (no allocation once they have the size).
void forward_kinematics(const Skeleton& skeleton, const Pose& pose, std::vector<glm::vec3>& world_positions,
                        std::vector<glm::quat>* world_rotations = nullptr);

// World position of joint j's End Site, given the world positions and rotations from forward_kinematics.
glm::vec3 end_site_position(const Skeleton& skeleton, int joint, const std::vector<glm::vec3>& world_positions,
                            const std::vector<glm::quat>& world_rotations);

}  // namespace prep
