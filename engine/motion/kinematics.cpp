#include "engine/motion/kinematics.h"

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
  // The addresses held in locals: place_joint's SSE2 stores may alias anything, and would have them read
  // again for every joint.
  const Joint* const joints = skeleton.joints.data();
  const glm::quat* const local = pose.rotations.data();
  glm::vec3* const x = world_positions.data();
  glm::quat* const r = rot.data();
  r[0] = local[0];
  x[0] = pose.root_position;
  for (size_t i = 1; i < n; ++i) {
    const Joint& j = joints[i];
    const size_t p = static_cast<size_t>(j.parent);
    place_joint(x[p], r[p], j.offset, local[i], x[i], r[i]);
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
  // The buffers' addresses held in locals: place_joint's SSE2 stores may alias anything, and would have
  // them read again for every joint.
  glm::vec3* const p = positions.data();
  glm::quat* const r = rotations.data();
  const glm::quat* const local = pose.rotations.data();
  for (std::uint32_t root : roots_) {
    r[root] = local[root];
    p[root] = pose.root_position;
  }
  for (const Step& s : steps_) place_joint(p[s.parent], r[s.parent], s.offset, local[s.joint], p[s.joint], r[s.joint]);
}

void JointPass::run_two(const Pose& pose_a, std::vector<glm::vec3>& positions_a, std::vector<glm::quat>& rotations_a,
                        const Pose& pose_b, std::vector<glm::vec3>& positions_b,
                        std::vector<glm::quat>& rotations_b) const {
  glm::vec3* const pa = positions_a.data();
  glm::quat* const ra = rotations_a.data();
  const glm::quat* const la = pose_a.rotations.data();
  glm::vec3* const pb = positions_b.data();
  glm::quat* const rb = rotations_b.data();
  const glm::quat* const lb = pose_b.rotations.data();
  for (std::uint32_t root : roots_) {
    ra[root] = la[root];
    pa[root] = pose_a.root_position;
    rb[root] = lb[root];
    pb[root] = pose_b.root_position;
  }
  for (const Step& s : steps_) {
    place_joint(pa[s.parent], ra[s.parent], s.offset, la[s.joint], pa[s.joint], ra[s.joint]);
    place_joint(pb[s.parent], rb[s.parent], s.offset, lb[s.joint], pb[s.joint], rb[s.joint]);
  }
}

}  // namespace prep
