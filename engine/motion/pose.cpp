#include "engine/motion/pose.h"

#include <cmath>

#include "engine/motion/slerp.h"

namespace prep {

void interpolate(const Pose& a, const Pose& b, float t, Pose& out) {
  out.root_position = a.root_position + (b.root_position - a.root_position) * t;
  out.rotations.resize(a.rotations.size());
  slerp_shorter(a.rotations.data(), b.rotations.data(), t, out.rotations.data(), a.rotations.size());
}

glm::quat without_negligible_components(const glm::dquat& unit) {
  const auto keep = [](double c) { return static_cast<float>(std::abs(c) < kNegligibleComponent ? 0.0 : c); };
  return glm::quat(keep(unit.w), keep(unit.x), keep(unit.y), keep(unit.z));
}

float heading_of(const glm::quat& root_rotation) {
  const glm::vec3 forward = root_rotation * glm::vec3(0.0f, 0.0f, 1.0f);
  return std::atan2(forward.x, forward.z);
}

}  // namespace prep
