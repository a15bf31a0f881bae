#include "engine/motion/body_volumes.h"

#include <algorithm>
#include <cctype>
#include <limits>
#include <stdexcept>

#include "engine/motion/quaternion_ops.h"

namespace prep {

namespace {

constexpr float kHeadRadius = 0.10f;
constexpr float kHeadCentreAbove = 0.11f;  // m from the head joint (base of the skull) to the head's centre
constexpr float kHeadHalfLength = 0.02f;   // the head capsule is a sphere drawn out this much each way

std::string lowercase(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

bool has(const std::string& s, const char* word) { return s.find(word) != std::string::npos; }

// The highest joint of the rest pose, or the one named "head".
int head_by_name_or_height(const Skeleton& skeleton) {
  int highest = 0;
  float highest_y = -1e9f;
  std::vector<float> rest_y(skeleton.joints.size(), 0.0f);
  for (int j = 0; j < skeleton.size(); ++j) {
    const Joint& joint = skeleton.joints[static_cast<size_t>(j)];
    if (lowercase(joint.name) == "head") return j;
    rest_y[static_cast<size_t>(j)] = joint.offset.y + (joint.parent >= 0 ? rest_y[static_cast<size_t>(joint.parent)] : 0.0f);
    if (rest_y[static_cast<size_t>(j)] > highest_y) highest_y = rest_y[static_cast<size_t>(j)], highest = j;
  }
  return highest;
}

bool is_at_or_below(const Skeleton& skeleton, int joint, int ancestor) {
  for (int j = joint; j >= 0; j = skeleton.joints[static_cast<size_t>(j)].parent)
    if (j == ancestor) return true;
  return false;
}

// The part of the body a bone starting at `joint` belongs to, from the body map's chains.
BodyPart part_of(const Skeleton& skeleton, const BodyMap* body, int joint) {
  if (!body) return BodyPart::Trunk;
  for (int side : {kLeft, kRight}) {
    const ArmChain& arm = body->arms[static_cast<size_t>(side)];
    const LegChain& leg = body->legs[static_cast<size_t>(side)];
    if (is_at_or_below(skeleton, joint, arm.wrist)) return side == kLeft ? BodyPart::LeftHand : BodyPart::RightHand;
    if (is_at_or_below(skeleton, joint, arm.shoulder)) return side == kLeft ? BodyPart::LeftArm : BodyPart::RightArm;
    if (is_at_or_below(skeleton, joint, leg.ankle)) return side == kLeft ? BodyPart::LeftFoot : BodyPart::RightFoot;
    if (is_at_or_below(skeleton, joint, leg.hip)) return side == kLeft ? BodyPart::LeftLeg : BodyPart::RightLeg;
  }
  return is_at_or_below(skeleton, joint, body->head) ? BodyPart::Head : BodyPart::Trunk;
}

}  // namespace

const char* body_part_name(BodyPart part) {
  switch (part) {
    case BodyPart::Head: return "head";
    case BodyPart::Trunk: return "trunk";
    case BodyPart::LeftArm: return "left arm";
    case BodyPart::RightArm: return "right arm";
    case BodyPart::LeftHand: return "left hand";
    case BodyPart::RightHand: return "right hand";
    case BodyPart::LeftLeg: return "left leg";
    case BodyPart::RightLeg: return "right leg";
    case BodyPart::LeftFoot: return "left foot";
    case BodyPart::RightFoot: return "right foot";
  }
  return "?";
}

// Order matters: "forearm" before "arm", "upleg" before "leg".
float bone_radius(const std::string& joint_name) {
  const std::string n = lowercase(joint_name);
  if (has(n, "eye") || has(n, "jaw")) return 0.0f;
  if (has(n, "thumb") || has(n, "index") || has(n, "mid") || has(n, "ring") || has(n, "pinky") || has(n, "finger"))
    return 0.011f;
  if (has(n, "hand") || has(n, "wrist")) return 0.032f;
  if (has(n, "forearm") || has(n, "elbow") || has(n, "lowerarm")) return 0.040f;
  if (has(n, "collar") || has(n, "clavicle")) return 0.045f;
  if (has(n, "shldr") || has(n, "shoulder") || has(n, "arm")) return 0.048f;
  if (has(n, "toe")) return 0.030f;
  if (has(n, "foot") || has(n, "ankle")) return 0.042f;
  if (has(n, "thigh") || has(n, "upleg") || has(n, "upperleg") || has(n, "buttock")) return 0.068f;
  if (has(n, "shin") || has(n, "knee") || has(n, "calf") || has(n, "lowerleg") || has(n, "leg")) return 0.052f;
  if (has(n, "neck")) return 0.050f;
  if (has(n, "chest") || has(n, "spine") || has(n, "abdomen") || has(n, "torso") || has(n, "back")) return 0.100f;
  if (has(n, "hip") || has(n, "pelvis") || has(n, "root")) return 0.085f;
  return 0.045f;
}

BodyVolumes::BodyVolumes(const Skeleton& skeleton) {
  BodyMap map;
  const BodyMap* body = nullptr;
  try {
    map = BodyMap::detect(skeleton);
    body = &map;
  } catch (const std::invalid_argument&) {
    // Not a humanoid the body map knows: capsules by name, all trunk.
  }
  head_ = body ? body->head : head_by_name_or_height(skeleton);
  for (int j = 0; j < skeleton.size(); ++j) {
    const Joint& joint = skeleton.joints[static_cast<size_t>(j)];
    if (joint.parent == head_) continue;  // eyes, jaw, head-top joints: the head is one volume
    auto add = [&](int from, int to, glm::vec3 local_end) {
      const float r = bone_radius(skeleton.joints[static_cast<size_t>(from)].name);
      if (r > 0.0f)
        capsules_.push_back({from, to, local_end, r, part_of(skeleton, body, from), skeleton.joints[static_cast<size_t>(from)].name});
    };
    if (joint.parent >= 0) add(joint.parent, j, glm::vec3(0.0f));
    if (joint.has_end_site && j != head_) add(j, -1, joint.end_site);
  }
  const Joint& head = skeleton.joints[static_cast<size_t>(head_)];
  const glm::vec3 up = head.has_end_site && glm::length(head.end_site) > 1e-4f ? glm::normalize(head.end_site) : glm::vec3(0, 1, 0);
  capsules_.push_back({head_, -1, up, kHeadRadius, BodyPart::Head, head.name});

  std::vector<float> reach(static_cast<size_t>(skeleton.size()), -1.0f);
  const auto reaches = [&](int joint, float r) { reach[static_cast<size_t>(joint)] = std::max(reach[static_cast<size_t>(joint)], r); };
  for (const BodyCapsule& c : capsules_) {
    const float end = glm::length(c.local_end);
    if (c.end_joint >= 0) {
      reaches(c.joint, c.radius);
      reaches(c.end_joint, c.radius);
    } else if (c.part != BodyPart::Head || c.joint != head_) {
      reaches(c.joint, end + c.radius);
    } else {
      reaches(c.joint, end * (kHeadCentreAbove + kHeadHalfLength) + c.radius);
    }
  }
  for (int j = 0; j < skeleton.size(); ++j)
    if (reach[static_cast<size_t>(j)] >= 0.0f) bound_points_.push_back({j, reach[static_cast<size_t>(j)]});
}

void BodyVolumes::floor_box_bound(const std::vector<glm::vec3>& p, glm::vec2& low, glm::vec2& high) const {
  glm::vec2 lo(std::numeric_limits<float>::infinity()), hi(-std::numeric_limits<float>::infinity());
  for (const BoundPoint& b : bound_points_) {
    const glm::vec3& x = p[static_cast<size_t>(b.joint)];
    lo = glm::min(lo, glm::vec2(x.x - b.reach, x.z - b.reach));
    hi = glm::max(hi, glm::vec2(x.x + b.reach, x.z + b.reach));
  }
  // Grown by a millimetre and a millionth of the coordinates besides: more than the rounding of a placed
  // capsule's end (a unit quaternion's rotation of the End Site, added to the joint) anywhere a body can be.
  const glm::vec2 far = glm::max(glm::abs(lo), glm::abs(hi));
  const float margin = 1e-3f + 1e-6f * std::max(far.x, far.y);
  low = lo - margin;
  high = hi + margin;
}

void BodyVolumes::place(const std::vector<glm::vec3>& p, const std::vector<glm::quat>& q, std::vector<PlacedCapsule>& out) const {
  out.resize(capsules_.size());
  for (size_t k = 0; k < capsules_.size(); ++k) {
    const BodyCapsule& c = capsules_[k];
    const size_t j = static_cast<size_t>(c.joint);
    if (c.end_joint >= 0) {
      out[k] = {p[j], p[static_cast<size_t>(c.end_joint)], c.radius};
    } else if (c.part != BodyPart::Head || c.joint != head_) {
      out[k] = {p[j], p[j] + quat::rotate(q[j], c.local_end), c.radius};
    } else {
      // The head: centred above the head joint along its up axis (towards its End Site when it has one).
      const glm::vec3 up = quat::rotate(q[j], c.local_end);
      const glm::vec3 centre = p[j] + up * kHeadCentreAbove;
      out[k] = {centre - up * kHeadHalfLength, centre + up * kHeadHalfLength, c.radius};
    }
  }
}

}  // namespace prep
