// Our humanoid's joints and proportions, shared by every generator of the built-in library.
//
// Proportions: D. A. Winter, "Biomechanics and Motor Control of Human Movement" (4th ed., 2009), Fig. 4.1,
// segment lengths as fractions of body height H. We take H = 1.75 m (an adult male). Where Winter gives a
// surface landmark (the greater trochanter, the acromion), the joint centre is placed a little inside it.
#pragma once

#include <glm/vec3.hpp>

namespace prep::library {

// Joint indices of builtin_skeleton(), parents first.
enum JointId : int {
  kHips,
  kSpine,
  kSpine1,
  kSpine2,
  kNeck,
  kHead,
  kLeftShoulder,
  kLeftArm,
  kLeftForeArm,
  kLeftHand,
  kRightShoulder,
  kRightArm,
  kRightForeArm,
  kRightHand,
  kLeftUpLeg,
  kLeftLeg,
  kLeftFoot,
  kLeftToeBase,
  kRightUpLeg,
  kRightLeg,
  kRightFoot,
  kRightToeBase,
  kJointCount
};

// Per side: +1 for the left (the character's left is +X), -1 for the right.
inline float side_sign(int side) { return side == 0 ? 1.0f : -1.0f; }
inline int up_leg(int side) { return side == 0 ? kLeftUpLeg : kRightUpLeg; }
inline int leg(int side) { return side == 0 ? kLeftLeg : kRightLeg; }
inline int foot(int side) { return side == 0 ? kLeftFoot : kRightFoot; }
inline int toe(int side) { return side == 0 ? kLeftToeBase : kRightToeBase; }
inline int clavicle(int side) { return side == 0 ? kLeftShoulder : kRightShoulder; }
inline int upper_arm(int side) { return side == 0 ? kLeftArm : kRightArm; }
inline int fore_arm(int side) { return side == 0 ? kLeftForeArm : kRightForeArm; }
inline int hand(int side) { return side == 0 ? kLeftHand : kRightHand; }

namespace anthropometry {
constexpr float kHeight = 1.75f;                       // H
constexpr float kAnkleHeight = 0.039f * kHeight;       // Winter: floor to lateral malleolus
constexpr float kKneeHeight = 0.285f * kHeight;        // floor to knee joint
constexpr float kHipHeight = 0.530f * kHeight;         // floor to greater trochanter ~ hip joint centre
constexpr float kShoulderHeight = 0.818f * kHeight;    // floor to acromion
constexpr float kChinHeight = 0.870f * kHeight;
constexpr float kHipHalfWidth = 0.05f * kHeight;       // hip joint centres ~0.10 H apart (inside Winter's 0.191 H trochanter width)
constexpr float kShoulderHalfWidth = 0.11f * kHeight;  // glenohumeral centres, inside the 0.259 H biacromial width
constexpr float kUpperArm = 0.186f * kHeight;          // shoulder -> elbow
constexpr float kForeArm = 0.146f * kHeight;           // elbow -> wrist
constexpr float kHand = 0.108f * kHeight;              // wrist -> fingertip
constexpr float kFootLength = 0.152f * kHeight;        // heel -> toe tip
constexpr float kThigh = kHipHeight - kKneeHeight;     // 0.245 H
constexpr float kShank = kKneeHeight - kAnkleHeight;   // 0.246 H
constexpr float kPelvisAboveHip = 0.04f;               // the root (mid-pelvis) above the hip joint centres
constexpr float kRootHeight = kHipHeight + kPelvisAboveHip;
// Foot geometry (ankle joint -> ball of the foot -> toe tip): the toe tip rests on the floor; the ankle sits
// a quarter of the foot length in front of the heel.
constexpr float kAnkleToBall = 0.55f * kFootLength;    // along the foot, ahead of the ankle
constexpr float kBallToToeTip = 0.20f * kFootLength;
constexpr float kBallHeight = 0.012f;                  // the metatarsal heads' joint centre above the floor
}  // namespace anthropometry

}  // namespace prep::library
