#include "engine/library/joint_ranges.h"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>

#include "engine/library/rig.h"

namespace prep::library {
namespace {
constexpr float kRadToDeg = 57.2957795f;
float rotation_angle_deg(const glm::quat& q) {
  return 2.0f * std::acos(std::clamp(std::fabs(q.w), 0.0f, 1.0f)) * kRadToDeg;
}
}  // namespace

const std::vector<JointRange>& joint_ranges() {
  static const std::vector<JointRange> ranges = {
      {"UpLeg", "hip flexion", -30, 125},      {"UpLeg", "hip abduction", -30, 45},
      {"Leg", "knee flexion", -5, 150},        {"Foot", "ankle dorsiflexion", -50, 45},
      {"ToeBase", "toe extension", -40, 70},   {"ForeArm", "elbow flexion", 0, 150},
      {"Hand", "wrist rotation", 0, 95},       {"Shoulder", "clavicle rotation", 0, 30},
      {"Spine", "lumbar rotation", 0, 40},     {"Spine1", "thoracic rotation", 0, 40},
      {"Spine2", "thoracic rotation", 0, 40},  {"Neck", "neck rotation", 0, 60},
      {"Head", "head rotation", 0, 45},
  };
  return ranges;
}

std::vector<JointAngle> measure_joint_angles(const Pose& pose) {
  std::vector<JointAngle> out;
  const auto& ranges = joint_ranges();
  auto add = [&](const std::string& joint, size_t range, float degrees) {
    out.push_back({joint, ranges[range].measure, degrees, ranges[range].min_deg, ranges[range].max_deg});
  };
  const auto q = [&](int j) { return pose.rotations[static_cast<size_t>(j)]; };
  for (int side = 0; side < 2; ++side) {
    const std::string prefix = side == 0 ? "Left" : "Right";
    const float s = side_sign(side);
    const glm::vec3 thigh = q(up_leg(side)) * glm::vec3(0, -1, 0);  // thigh direction in the pelvis frame
    add(prefix + "UpLeg", 0, std::atan2(thigh.z, -thigh.y) * kRadToDeg);
    add(prefix + "UpLeg", 1, std::asin(std::clamp(s * thigh.x, -1.0f, 1.0f)) * kRadToDeg);
    const glm::vec3 shin = q(leg(side)) * glm::vec3(0, -1, 0);
    add(prefix + "Leg", 2, std::atan2(-shin.z, -shin.y) * kRadToDeg);
    const glm::vec3 foot_forward = q(foot(side)) * glm::vec3(0, 0, 1);
    add(prefix + "Foot", 3, std::asin(std::clamp(foot_forward.y, -1.0f, 1.0f)) * kRadToDeg);
    const glm::vec3 toes = q(toe(side)) * glm::vec3(0, 0, 1);
    add(prefix + "ToeBase", 4, std::asin(std::clamp(toes.y, -1.0f, 1.0f)) * kRadToDeg);
    const glm::vec3 forearm = q(fore_arm(side)) * glm::vec3(s, 0, 0);
    add(prefix + "ForeArm", 5, std::acos(std::clamp(glm::dot(forearm, glm::vec3(s, 0, 0)), -1.0f, 1.0f)) * kRadToDeg);
    add(prefix + "Hand", 6, rotation_angle_deg(q(hand(side))));
    add(prefix + "Shoulder", 7, rotation_angle_deg(q(clavicle(side))));
  }
  add("Spine", 8, rotation_angle_deg(q(kSpine)));
  add("Spine1", 9, rotation_angle_deg(q(kSpine1)));
  add("Spine2", 10, rotation_angle_deg(q(kSpine2)));
  add("Neck", 11, rotation_angle_deg(q(kNeck)));
  add("Head", 12, rotation_angle_deg(q(kHead)));
  return out;
}

}  // namespace prep::library
