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

JointPass::JointPass(const Skeleton& skeleton, const std::vector<int>& joints) {
  for (int j : joints) {
    const Joint& joint = skeleton.joints[static_cast<size_t>(j)];
    if (joint.parent < 0) {
      roots_.push_back(static_cast<std::uint32_t>(j));
    } else {
      steps_.push_back({static_cast<std::uint32_t>(j), static_cast<std::uint32_t>(joint.parent), joint.offset});
    }
  }
}

void JointPass::run(const Pose& pose, std::vector<glm::vec3>& positions, std::vector<glm::quat>& rotations) const {
  for (std::uint32_t r : roots_) {
    rotations[r] = pose.rotations[r];
    positions[r] = pose.root_position;
  }
  for (const Step& s : steps_) {
    place_joint(positions[s.parent], rotations[s.parent], s.offset, pose.rotations[s.joint], positions[s.joint],
                rotations[s.joint]);
  }
}

void JointPass::run_two(const Pose& pose_a, std::vector<glm::vec3>& positions_a, std::vector<glm::quat>& rotations_a,
                        const Pose& pose_b, std::vector<glm::vec3>& positions_b,
                        std::vector<glm::quat>& rotations_b) const {
  for (std::uint32_t r : roots_) {
    rotations_a[r] = pose_a.rotations[r];
    positions_a[r] = pose_a.root_position;
    rotations_b[r] = pose_b.rotations[r];
    positions_b[r] = pose_b.root_position;
  }
  for (const Step& s : steps_) {
    place_joint(positions_a[s.parent], rotations_a[s.parent], s.offset, pose_a.rotations[s.joint], positions_a[s.joint],
                rotations_a[s.joint]);
    place_joint(positions_b[s.parent], rotations_b[s.parent], s.offset, pose_b.rotations[s.joint], positions_b[s.joint],
                rotations_b[s.joint]);
  }
}

glm::vec3 end_site_position(const Skeleton& skeleton, int joint, const std::vector<glm::vec3>& world_positions,
                            const std::vector<glm::quat>& world_rotations) {
  const size_t j = static_cast<size_t>(joint);
  return world_positions[j] + quat::rotate(world_rotations[j], skeleton.joints[j].end_site);
}

}  // namespace prep
