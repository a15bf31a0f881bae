// A pose described by anatomical angles (flexion, abduction, rotation per joint, in radians) plus the root
// position: the space in which the library's motions are keyed and interpolated. Every entry is a plain
// number, so cubic Hermite interpolation of key poses is smooth in every joint; to_pose() turns it into
// the engine's quaternions.
#pragma once

#include <array>
#include <vector>

#include "engine/motion/pose.h"

namespace prep::library {

// Entries of a DofPose. Per-side entries are at kLeftBase + index (left) and kRightBase + index (right).
enum Dof : int {
  kRootX,
  kRootY,
  kRootZ,
  kYaw,            // heading of the pelvis, + turns left (toward +X)
  kPelvisTilt,     // anterior tilt +
  kPelvisRoll,     // obliquity: + raises the left side
  kSpineFlex,      // forward bend of the whole spine (shared by Spine, Spine1, Spine2)
  kSpineBend,      // lateral bend, + toward the left
  kSpineTwist,     // axial rotation, + turns the chest left
  kNeckFlex,
  kNeckTwist,
  kHeadFlex,
  kHeadTwist,
  kHeadBend,
  kSideBase,
};
enum SideDof : int {
  kClavicleElevation,  // shrug +
  kClavicleProtraction,// forward +
  kShoulderFlex,       // arm forward +, measured from hanging down
  kShoulderAbduct,     // arm out sideways +, from hanging down
  kShoulderTwist,      // internal rotation +
  kElbowFlex,
  kWristFlex,          // palm-ward +
  kHipFlex,            // thigh forward +
  kHipAbduct,          // thigh outward +
  kHipRotation,        // internal rotation +
  kKneeFlex,
  kAnkleDorsi,         // toes up +
  kToeExtension,       // toes up relative to the foot +
  kSideDofCount
};
constexpr int kLeftBase = kSideBase;
constexpr int kRightBase = kSideBase + kSideDofCount;
constexpr int kDofCount = kSideBase + 2 * kSideDofCount;

inline int side_dof(int side, SideDof d) { return (side == 0 ? kLeftBase : kRightBase) + d; }

struct DofPose {
  std::array<float, kDofCount> v{};

  float& operator[](int i) { return v[static_cast<size_t>(i)]; }
  float operator[](int i) const { return v[static_cast<size_t>(i)]; }
  float& at(int side, SideDof d) { return v[static_cast<size_t>(side_dof(side, d))]; }
  float at(int side, SideDof d) const { return v[static_cast<size_t>(side_dof(side, d))]; }

  DofPose& operator+=(const DofPose& o) {
    for (size_t i = 0; i < v.size(); ++i) v[i] += o.v[i];
    return *this;
  }
  friend DofPose operator+(DofPose a, const DofPose& b) { return a += b; }
  friend DofPose operator-(DofPose a, const DofPose& b) {
    for (size_t i = 0; i < a.v.size(); ++i) a.v[i] -= b.v[i];
    return a;
  }
  friend DofPose operator*(DofPose a, float s) {
    for (float& x : a.v) x *= s;
    return a;
  }
};

// The quaternion pose of builtin_skeleton() for these angles.
Pose to_pose(const DofPose& d);

// A key of a keyed motion: the pose at time t (s) and, optionally, its time derivative there.
struct PoseKey {
  float t = 0.0f;
  DofPose pose;
  bool has_velocity = false;
  DofPose velocity;
};

// Cubic Hermite interpolation through the keys (Catmull-Rom tangents on non-uniform times where no
// velocity is given, zero velocity at the first and last key unless given). Clamped outside the keys.
DofPose sample_keys(const std::vector<PoseKey>& keys, float t);

}  // namespace prep::library
