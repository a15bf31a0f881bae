// Skeletons built by hand for the motion tests: our built-in naming (optionally with Mixamo's
// "mixamorig:" prefix), in metres, standing on y = 0 in the rest pose, facing +Z, left = +X.
#pragma once

#include <memory>
#include <string>

#include "engine/motion/clip.h"
#include "engine/motion/skeleton.h"

namespace prep::test {

inline int add_joint(Skeleton& sk, const std::string& name, const std::string& parent, glm::vec3 offset) {
  Joint j;
  j.name = name;
  j.parent = parent.empty() ? -1 : sk.find(parent);
  j.offset = offset;
  sk.joints.push_back(j);
  return sk.size() - 1;
}

inline void add_end_site(Skeleton& sk, const std::string& joint, glm::vec3 offset) {
  Joint& j = sk.joints[static_cast<size_t>(sk.find(joint))];
  j.has_end_site = true;
  j.end_site = offset;
}

// A symmetric T-pose: arms straight out sideways. Root (Hips) 0.95 m high; ankles 0.08 m above the floor;
// toe tips on the floor 0.18 m ahead of the ankles; top of the head 1.75 m.
inline std::shared_ptr<Skeleton> t_pose_skeleton(const std::string& prefix = "") {
  auto sk = std::make_shared<Skeleton>();
  const auto n = [&](const char* s) { return s[0] ? prefix + s : std::string(); };
  add_joint(*sk, n("Hips"), "", {0, 0.95f, 0});
  add_joint(*sk, n("Spine"), n("Hips"), {0, 0.10f, 0});
  add_joint(*sk, n("Spine1"), n("Spine"), {0, 0.15f, 0});
  add_joint(*sk, n("Spine2"), n("Spine1"), {0, 0.15f, 0});
  add_joint(*sk, n("Neck"), n("Spine2"), {0, 0.12f, 0});
  add_joint(*sk, n("Head"), n("Neck"), {0, 0.10f, 0});
  add_end_site(*sk, n("Head"), {0, 0.18f, 0});
  for (int side = 0; side < 2; ++side) {
    const std::string s = side == 0 ? "Left" : "Right";
    const float x = side == 0 ? 1.0f : -1.0f;
    add_joint(*sk, n((s + "Shoulder").c_str()), n("Spine2"), {x * 0.04f, 0.10f, 0});
    add_joint(*sk, n((s + "Arm").c_str()), n((s + "Shoulder").c_str()), {x * 0.14f, 0, 0});
    add_joint(*sk, n((s + "ForeArm").c_str()), n((s + "Arm").c_str()), {x * 0.28f, 0, 0});
    add_joint(*sk, n((s + "Hand").c_str()), n((s + "ForeArm").c_str()), {x * 0.25f, 0, 0});
    add_end_site(*sk, n((s + "Hand").c_str()), {x * 0.18f, 0, 0});
    add_joint(*sk, n((s + "UpLeg").c_str()), n("Hips"), {x * 0.10f, -0.05f, 0});
    add_joint(*sk, n((s + "Leg").c_str()), n((s + "UpLeg").c_str()), {0, -0.42f, 0});
    add_joint(*sk, n((s + "Foot").c_str()), n((s + "Leg").c_str()), {0, -0.40f, 0});
    add_joint(*sk, n((s + "ToeBase").c_str()), n((s + "Foot").c_str()), {0, -0.06f, 0.13f});
    add_end_site(*sk, n((s + "ToeBase").c_str()), {0, -0.02f, 0.05f});
  }
  sk->validate();
  return sk;
}

// A clip of `frames` rest poses at `fps`, root at its rest height.
inline Clip still_clip(std::shared_ptr<const Skeleton> sk, int frames, float fps) {
  Clip clip;
  clip.skeleton = sk;
  clip.fps = fps;
  Pose pose(sk->size());
  pose.root_position = sk->joints[0].offset;
  clip.frames.assign(static_cast<size_t>(frames), pose);
  return clip;
}

}  // namespace prep::test
