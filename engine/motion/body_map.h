// What each joint of a skeleton is, anatomically: legs, arms, spine, head; which joints belong to the
// upper body (adapted first, Sec. 5.1; optimized for balance, Sec. 5.3) and which to the lower body.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "engine/motion/skeleton.h"

namespace prep {

enum Side { kLeft = 0, kRight = 1 };

struct LegChain {
  int hip = -1;    // thigh joint (rotates the thigh)
  int knee = -1;   // shin joint
  int ankle = -1;  // foot joint; its world position is the heel/ankle point
  int toe = -1;    // toe joint if the skeleton has one, else -1
  // The toe tip: the End Site of `toe` if present, else the End Site of `ankle`.
  int toe_tip_joint = -1;  // joint whose End Site is the toe tip
};

struct ArmChain {
  int collar = -1;    // clavicle, -1 if none
  int shoulder = -1;  // upper arm
  int elbow = -1;     // forearm
  int wrist = -1;     // hand
};

struct BodyMap {
  int root = 0;                    // pelvis / hips
  std::vector<int> spine;          // from the pelvis up to (not including) the neck
  int neck = -1;
  int head = -1;
  std::array<LegChain, 2> legs;    // [kLeft], [kRight]
  std::array<ArmChain, 2> arms;
  std::vector<bool> upper_body;    // per joint: spine, neck, head, arms, hands, fingers
  std::vector<bool> lower_body;    // per joint: root, hips, legs, feet, toes (root included, Sec. 5.1)

  // Recognises our skeleton, the daz43 and cmu31 CMU conversions and Mixamo-style names by joint names
  // (case-insensitive: hip/thigh/upleg, knee/shin/leg, ankle/foot, toe; shoulder/arm, elbow/forearm,
  // wrist/hand; l/left and r/right prefixes). Throws std::invalid_argument naming what is missing.
  static BodyMap detect(const Skeleton& skeleton);
};

}  // namespace prep
