// A small hand-made humanoid (metres, Y up, facing +Z, daz-style joint names) for the synthesis unit tests,
// so that each test can compute its expected numbers by hand.
#pragma once

#include <memory>

#include "engine/motion/body_map.h"
#include "engine/motion/center_of_mass.h"
#include "engine/motion/skeleton.h"

namespace prep::test {

// With fingers, each hand gets a middle finger of two joints (lMid1, lMid2) ending in an End Site.
inline std::shared_ptr<const Skeleton> make_test_skeleton(bool fingers = false) {
  auto s = std::make_shared<Skeleton>();
  auto add = [&](const char* name, int parent, glm::vec3 offset) {
    Joint j;
    j.name = name;
    j.parent = parent;
    j.offset = offset;
    s->joints.push_back(j);
    return s->size() - 1;
  };
  auto end_site = [&](int j, glm::vec3 e) {
    s->joints[static_cast<size_t>(j)].has_end_site = true;
    s->joints[static_cast<size_t>(j)].end_site = e;
  };
  const int hip = add("hip", -1, {0.0f, 0.95f, 0.0f});
  const int abdomen = add("abdomen", hip, {0.0f, 0.10f, 0.0f});
  const int chest = add("chest", abdomen, {0.0f, 0.20f, 0.0f});
  const int neck = add("neck", chest, {0.0f, 0.25f, 0.0f});
  const int head = add("head", neck, {0.0f, 0.10f, 0.0f});
  end_site(head, {0.0f, 0.20f, 0.0f});
  for (float side : {1.0f, -1.0f}) {
    const bool left = side > 0.0f;
    const int collar = add(left ? "lCollar" : "rCollar", chest, {side * 0.05f, 0.20f, 0.0f});
    const int shoulder = add(left ? "lShldr" : "rShldr", collar, {side * 0.12f, 0.0f, 0.0f});
    const int elbow = add(left ? "lForeArm" : "rForeArm", shoulder, {side * 0.28f, 0.0f, 0.0f});
    const int hand = add(left ? "lHand" : "rHand", elbow, {side * 0.25f, 0.0f, 0.0f});
    if (fingers) {
      const int mid1 = add(left ? "lMid1" : "rMid1", hand, {side * 0.09f, 0.0f, 0.0f});
      const int mid2 = add(left ? "lMid2" : "rMid2", mid1, {side * 0.05f, 0.0f, 0.0f});
      end_site(mid2, {side * 0.04f, 0.0f, 0.0f});
    } else {
      end_site(hand, {side * 0.18f, 0.0f, 0.0f});
    }
  }
  for (float side : {1.0f, -1.0f}) {
    const bool left = side > 0.0f;
    const int thigh = add(left ? "lThigh" : "rThigh", hip, {side * 0.09f, -0.05f, 0.0f});
    const int shin = add(left ? "lShin" : "rShin", thigh, {0.0f, -0.42f, 0.0f});
    const int foot = add(left ? "lFoot" : "rFoot", shin, {0.0f, -0.43f, 0.0f});
    end_site(foot, {0.0f, -0.05f, 0.17f});
  }
  s->validate();
  return s;
}

}  // namespace prep::test
