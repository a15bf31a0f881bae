#include "engine/library/dof_pose.h"

#include <cmath>
#include <glm/gtc/quaternion.hpp>

#include "engine/library/angles.h"
#include "engine/library/rig.h"
#include "engine/library/spline.h"

namespace prep::library {
namespace {
glm::quat rx(float a) { return glm::angleAxis(a, glm::vec3(1, 0, 0)); }
glm::quat ry(float a) { return glm::angleAxis(a, glm::vec3(0, 1, 0)); }
glm::quat rz(float a) { return glm::angleAxis(a, glm::vec3(0, 0, 1)); }
// How the spine's flexion, bend and twist divide among the lumbar and the two thoracic joints (the lumbar
// spine flexes most, the thoracic spine twists most).
constexpr float kFlexShare[3] = {0.40f, 0.32f, 0.28f};
constexpr float kTwistShare[3] = {0.20f, 0.38f, 0.42f};
}  // namespace

Pose to_pose(const DofPose& d) {
  Pose p(kJointCount);
  auto set = [&](int j, glm::quat q) { p.rotations[static_cast<size_t>(j)] = glm::normalize(q); };
  p.root_position = {d[kRootX], d[kRootY], d[kRootZ]};
  set(kHips, ry(d[kYaw]) * rx(d[kPelvisTilt]) * rz(d[kPelvisRoll]));
  const int spine[3] = {kSpine, kSpine1, kSpine2};
  for (int k = 0; k < 3; ++k)
    set(spine[k], ry(kTwistShare[k] * d[kSpineTwist]) * rx(kFlexShare[k] * d[kSpineFlex]) * rz(-d[kSpineBend] / 3.0f));
  set(kNeck, ry(d[kNeckTwist]) * rx(d[kNeckFlex]));
  set(kHead, ry(d[kHeadTwist]) * rx(d[kHeadFlex]) * rz(-d[kHeadBend]));
  for (int side = 0; side < 2; ++side) {
    const float s = side_sign(side);
    set(clavicle(side), ry(-s * d.at(side, kClavicleProtraction)) * rz(s * d.at(side, kClavicleElevation)));
    // The T-pose arm is brought down by -90 degrees of abduction, then flexed forward in the trunk's frame;
    // the twist turns it about its own long axis (internal rotation turns the elbow crease inward).
    set(upper_arm(side), rx(-d.at(side, kShoulderFlex)) * rz(s * (d.at(side, kShoulderAbduct) - kHalfPi)) *
                             rx(d.at(side, kShoulderTwist)));
    set(fore_arm(side), ry(-s * d.at(side, kElbowFlex)));
    set(hand(side), rz(-s * d.at(side, kWristFlex)));
    set(up_leg(side), rx(-d.at(side, kHipFlex)) * rz(s * d.at(side, kHipAbduct)) * ry(-s * d.at(side, kHipRotation)));
    set(leg(side), rx(d.at(side, kKneeFlex)));
    set(foot(side), rx(-d.at(side, kAnkleDorsi)));
    set(toe(side), rx(-d.at(side, kToeExtension)));
  }
  return p;
}

DofPose sample_keys(const std::vector<PoseKey>& keys, float t) {
  if (keys.empty()) return {};
  if (t <= keys.front().t) return keys.front().pose;
  if (t >= keys.back().t) return keys.back().pose;
  size_t i = 0;
  while (i + 1 < keys.size() && keys[i + 1].t <= t) ++i;
  const PoseKey& a = keys[i];
  const PoseKey& b = keys[i + 1];
  auto slope = [&](size_t k) -> DofPose {
    const PoseKey& key = keys[k];
    if (key.has_velocity) return key.velocity;
    if (k == 0 || k + 1 == keys.size()) return DofPose{};
    return (keys[k + 1].pose - keys[k - 1].pose) * (1.0f / (keys[k + 1].t - keys[k - 1].t));
  };
  const float dt = b.t - a.t;
  const float s = (t - a.t) / dt;
  const DofPose ma = slope(i) * dt, mb = slope(i + 1) * dt;
  DofPose out;
  for (int j = 0; j < kDofCount; ++j) out[j] = hermite(a.pose[j], ma[j], b.pose[j], mb[j], s);
  return out;
}

}  // namespace prep::library
