// builtin_skeleton(): our 22-joint humanoid, in metres, Y up, facing +Z, +X its left, rest pose a T-pose
// (arms out along X, legs straight, feet flat on the floor, toe tips at y = 0).
#include <memory>

#include "engine/library/builtin.h"
#include "engine/library/rig.h"

namespace prep {

std::shared_ptr<const Skeleton> builtin_skeleton() {
  using namespace library;
  using namespace library::anthropometry;
  static const std::shared_ptr<const Skeleton> skeleton = [] {
    auto s = std::make_shared<Skeleton>();
    s->joints.resize(kJointCount);
    auto set = [&](int j, const char* name, int parent, glm::vec3 offset) {
      Joint& joint = s->joints[static_cast<size_t>(j)];
      joint.name = name;
      joint.parent = parent;
      joint.offset = offset;
    };
    auto end_site = [&](int j, glm::vec3 offset) {
      s->joints[static_cast<size_t>(j)].has_end_site = true;
      s->joints[static_cast<size_t>(j)].end_site = offset;
    };
    // Trunk: root at mid-pelvis; the lumbar, lower and upper thoracic joints divide the trunk from the pelvis
    // to the base of the neck (C7, ~0.85 H) with a slight S of the spine (lordosis, kyphosis) in z.
    const float neck_base = 0.852f * kHeight;
    const float trunk = neck_base - kRootHeight;
    set(kHips, "Hips", -1, {0.0f, kRootHeight, 0.0f});
    set(kSpine, "Spine", kHips, {0.0f, 0.16f * trunk, -0.01f});
    set(kSpine1, "Spine1", kSpine, {0.0f, 0.27f * trunk, -0.005f});
    set(kSpine2, "Spine2", kSpine1, {0.0f, 0.27f * trunk, 0.005f});
    set(kNeck, "Neck", kSpine2, {0.0f, 0.30f * trunk, -0.02f});
    set(kHead, "Head", kNeck, {0.0f, kChinHeight + 0.02f * kHeight - neck_base, 0.02f});  // atlanto-occipital joint
    end_site(kHead, {0.0f, kHeight - (kChinHeight + 0.02f * kHeight), 0.01f});          // top of the head at H
    // Arms: the clavicle from the sternoclavicular joint to the glenohumeral joint at shoulder height.
    const float spine2_y = kRootHeight + 0.70f * trunk;
    const float sc_y = kShoulderHeight + 0.006f;
    for (int side = 0; side < 2; ++side) {
      const float x = side_sign(side);
      const bool left = side == 0;
      set(clavicle(side), left ? "LeftShoulder" : "RightShoulder", kSpine2, {x * 0.025f, sc_y - spine2_y, 0.01f});
      set(upper_arm(side), left ? "LeftArm" : "RightArm", clavicle(side),
          {x * (kShoulderHalfWidth - 0.025f), kShoulderHeight - sc_y, -0.01f});
      set(fore_arm(side), left ? "LeftForeArm" : "RightForeArm", upper_arm(side), {x * kUpperArm, 0.0f, 0.0f});
      set(hand(side), left ? "LeftHand" : "RightHand", fore_arm(side), {x * kForeArm, 0.0f, 0.0f});
      end_site(hand(side), {x * kHand, 0.0f, 0.0f});  // fingertips
    }
    // Legs: hip joint centres below and beside the root; knee, ankle straight below; the foot to the ball,
    // the toes to the tip resting on the floor.
    for (int side = 0; side < 2; ++side) {
      const float x = side_sign(side);
      const bool left = side == 0;
      set(up_leg(side), left ? "LeftUpLeg" : "RightUpLeg", kHips, {x * kHipHalfWidth, -kPelvisAboveHip, 0.0f});
      set(leg(side), left ? "LeftLeg" : "RightLeg", up_leg(side), {0.0f, -kThigh, 0.0f});
      set(foot(side), left ? "LeftFoot" : "RightFoot", leg(side), {0.0f, -kShank, 0.0f});
      set(toe(side), left ? "LeftToeBase" : "RightToeBase", foot(side), {0.0f, kBallHeight - kAnkleHeight, kAnkleToBall});
      end_site(toe(side), {0.0f, -kBallHeight, kBallToToeTip});  // toe tip on the floor
    }
    s->validate();
    return s;
  }();
  return skeleton;
}

}  // namespace prep
