#include "engine/motion/kinematics.h"

#include "engine/motion/quaternion_ops.h"

namespace prep {

void forward_kinematics(const Skeleton& skeleton, const Pose& pose, std::vector<glm::vec3>& world_positions,
                        std::vector<glm::quat>* world_rotations) {
  const size_t n = skeleton.joints.size();
  world_positions.resize(n);
  // Reuse the caller's rotation buffer when given; otherwise a thread-local scratch buffer.
  thread_local std::vector<glm::quat> scratch;
  std::vector<glm::quat>& rot = world_rotations ? *world_rotations : scratch;
  rot.resize(n);
  if (n == 0) return;
  rot[0] = pose.rotations[0];
  world_positions[0] = pose.root_position;
  for (size_t i = 1; i < n; ++i) {
    const Joint& j = skeleton.joints[i];
    const size_t p = static_cast<size_t>(j.parent);
    place_joint(world_positions[p], rot[p], j.offset, pose.rotations[i], world_positions[i], rot[i]);
  }
}

glm::vec3 end_site_position(const Skeleton& skeleton, int joint, const std::vector<glm::vec3>& world_positions,
                            const std::vector<glm::quat>& world_rotations) {
  const size_t j = static_cast<size_t>(joint);
  return world_positions[j] + quat::rotate(world_rotations[j], skeleton.joints[j].end_site);
}

}  // namespace prep
