// A small standing humanoid built in the test (no dependency on any motion library), for screenshots.
#pragma once

#include <memory>

#include "engine/motion/clip.h"
#include "engine/motion/skeleton.h"

namespace prep::test {

inline std::shared_ptr<const Skeleton> stick_skeleton() {
  auto s = std::make_shared<Skeleton>();
  auto add = [&](const char* name, int parent, glm::vec3 offset) {
    Joint j;
    j.name = name;
    j.parent = parent;
    j.offset = offset;
    s->joints.push_back(j);
    return s->size() - 1;
  };
  const int hips = add("hips", -1, {0, 0, 0});
  const int spine = add("spine", hips, {0, 0.12f, 0});
  const int chest = add("chest", spine, {0, 0.22f, 0});
  const int neck = add("neck", chest, {0, 0.20f, 0});
  const int head = add("head", neck, {0, 0.10f, 0});
  s->joints[head].has_end_site = true;
  s->joints[head].end_site = {0, 0.2f, 0};
  for (float side : {1.0f, -1.0f}) {
    const bool left = side > 0;
    const int thigh = add(left ? "lThigh" : "rThigh", hips, {side * 0.1f, -0.05f, 0});
    const int shin = add(left ? "lShin" : "rShin", thigh, {0, -0.43f, 0});
    const int foot = add(left ? "lFoot" : "rFoot", shin, {0, -0.42f, 0});
    s->joints[foot].has_end_site = true;
    s->joints[foot].end_site = {0, -0.05f, 0.15f};
    const int shoulder = add(left ? "lShldr" : "rShldr", chest, {side * 0.18f, 0.17f, 0});
    const int forearm = add(left ? "lForeArm" : "rForeArm", shoulder, {0, -0.29f, 0});
    const int hand = add(left ? "lHand" : "rHand", forearm, {0, -0.26f, 0});
    s->joints[hand].has_end_site = true;
    s->joints[hand].end_site = {0, -0.15f, 0};
  }
  s->validate();
  return s;
}

// A two-frame clip of that skeleton standing with its feet on the floor at `at`, facing +Z.
inline Clip standing_clip(const glm::vec3& at) {
  Clip clip;
  clip.name = "stand";
  clip.skeleton = stick_skeleton();
  clip.fps = 30.0f;
  Pose pose(clip.skeleton->size());
  pose.root_position = at + glm::vec3(0, 0.05f + 0.43f + 0.42f + 0.05f, 0);  // hip drop + thigh + shin + heel
  clip.frames = {pose, pose};
  return clip;
}

}  // namespace prep::test
