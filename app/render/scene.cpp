#include "app/render/scene.h"

#include <algorithm>
#include <cctype>

#include "engine/motion/kinematics.h"

namespace prep::render {

SceneCharacter make_scene_character(std::shared_ptr<const Skeleton> skeleton, const Pose& pose, const glm::vec3& colour) {
  SceneCharacter c;
  forward_kinematics(*skeleton, pose, c.joint_positions, &c.joint_rotations);
  c.skeleton = std::move(skeleton);
  c.colour = colour;
  return c;
}

const char* object_type_name(ObjectType type) {
  switch (type) {
    case ObjectType::Ball: return "ball";
    case ObjectType::Bar: return "bar";
    case ObjectType::Beam: return "beam";
    case ObjectType::Hurdle: return "hurdle";
    case ObjectType::Box: return "box";
  }
  return "box";
}

int head_joint(const Skeleton& skeleton) {
  int highest = 0;
  float highest_y = -1e9f;
  std::vector<float> rest_y(skeleton.joints.size(), 0.0f);
  for (int j = 0; j < skeleton.size(); ++j) {
    const Joint& joint = skeleton.joints[j];
    std::string lower = joint.name;
    std::transform(lower.begin(), lower.end(), lower.begin(), [](unsigned char ch) { return std::tolower(ch); });
    if (lower == "head") return j;
    rest_y[j] = joint.offset.y + (joint.parent >= 0 ? rest_y[joint.parent] : 0.0f);
    if (rest_y[j] > highest_y) highest_y = rest_y[j], highest = j;
  }
  return highest;
}

}  // namespace prep::render
