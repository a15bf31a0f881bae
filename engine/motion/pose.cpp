#include "engine/motion/pose.h"

#include <cmath>

namespace prep {

void interpolate(const Pose& a, const Pose& b, float t, Pose& out) {
  out.root_position = a.root_position + (b.root_position - a.root_position) * t;
  out.rotations.resize(a.rotations.size());
  for (size_t i = 0; i < a.rotations.size(); ++i) {
    glm::quat qb = b.rotations[i];
    if (glm::dot(a.rotations[i], qb) < 0.0f) qb = -qb;  // shorter arc
    out.rotations[i] = glm::normalize(glm::slerp(a.rotations[i], qb, t));
  }
}

float heading_of(const glm::quat& root_rotation) {
  const glm::vec3 forward = root_rotation * glm::vec3(0.0f, 0.0f, 1.0f);
  return std::atan2(forward.x, forward.z);
}

}  // namespace prep
