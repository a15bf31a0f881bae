#include "engine/library/draft.h"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>

#include "engine/library/builtin.h"
#include "engine/library/rig.h"
#include "engine/library/spline.h"
#include "engine/library/two_bone_ik.h"
#include "engine/motion/kinematics.h"

namespace prep::library {
namespace {

constexpr float kHalfPi = 1.5707963f;
constexpr float kWristAboveFloor = 0.03f;  // wrist joint centre above the floor with the palm flat on it

glm::quat yaw_rotation(float yaw) { return glm::angleAxis(yaw, glm::vec3(0, 1, 0)); }
glm::quat pitch_rotation(float toe_up) { return glm::angleAxis(-toe_up, glm::vec3(1, 0, 0)); }

struct LimbFrame {
  glm::vec3 end{0.0f};          // ankle or wrist
  glm::quat end_rotation{1, 0, 0, 0};
  bool has_toe = false;
  glm::quat toe_world{1, 0, 0, 0};  // feet: world rotation of the toes
};

// The heading and the toe-up pitch of a foot's world rotation.
void yaw_pitch(const glm::quat& q, float& yaw, float& pitch) {
  const glm::vec3 f = q * glm::vec3(0, 0, 1);
  yaw = std::atan2(f.x, f.z);
  pitch = std::asin(std::clamp(f.y, -1.0f, 1.0f));
}

struct Limb {
  bool is_leg;
  int side;
  int upper, middle, end, end_child;  // joints: hip/knee/ankle/toe or shoulder/elbow/wrist/-1
};

}  // namespace

FootHold roll_foot(glm::vec3 flat_ankle, float yaw, float roll, bool before_mid) {
  constexpr float kMaxToeExtension = 0.70f;  // rad (40 degrees) of toe extension at the ball before the ball rises
  const auto skeleton = builtin_skeleton();
  const glm::vec3 ball_offset = skeleton->joints[kLeftToeBase].offset;
  const glm::vec3 tip_offset = skeleton->joints[kLeftToeBase].end_site;
  const glm::quat heading = yaw_rotation(yaw);
  FootHold h;
  if (before_mid) {
    h.foot = heading * pitch_rotation(std::max(roll, 0.0f));
    h.toes = h.foot;
    h.ankle = flat_ankle;
    return h;
  }
  const float pitch = std::min(roll, 0.0f);
  const float extension = std::min(-pitch, kMaxToeExtension);
  h.foot = heading * pitch_rotation(pitch);
  h.toes = heading * pitch_rotation(pitch + extension);
  const glm::vec3 tip = flat_ankle + heading * (ball_offset + tip_offset);
  const glm::vec3 ball = tip - h.toes * tip_offset;
  h.ankle = ball - h.foot * ball_offset;
  return h;
}

void merge_supports(std::vector<Support>& supports) {
  std::sort(supports.begin(), supports.end(), [](const Support& a, const Support& b) { return a.first < b.first; });
  std::vector<Support> merged;
  for (const Support& s : supports) {
    if (!merged.empty() && s.first <= merged.back().last + 1)
      merged.back().last = std::max(merged.back().last, s.last);
    else
      merged.push_back(s);
  }
  supports = std::move(merged);
}

Clip realize(const Draft& draft, RealizeReport* report) {
  const auto skeleton = builtin_skeleton();
  Clip clip;
  clip.name = draft.name;
  clip.skeleton = skeleton;
  clip.fps = draft.fps;
  const int n = static_cast<int>(draft.frames.size());
  clip.frames.reserve(static_cast<size_t>(n));
  for (const DofPose& d : draft.frames) clip.frames.push_back(to_pose(d));

  // Forward kinematics of the keyed poses.
  std::vector<std::vector<glm::vec3>> positions(static_cast<size_t>(n));
  std::vector<std::vector<glm::quat>> rotations(static_cast<size_t>(n));
  for (int f = 0; f < n; ++f)
    forward_kinematics(*skeleton, clip.frames[static_cast<size_t>(f)], positions[static_cast<size_t>(f)], &rotations[static_cast<size_t>(f)]);

  const auto offset = [&](int j) { return skeleton->joints[static_cast<size_t>(j)].offset; };
  const glm::vec3 ball_offset = offset(kLeftToeBase);  // ankle -> ball in the foot's frame (same both sides)
  const glm::vec3 toe_tip_offset = skeleton->joints[kLeftToeBase].end_site;

  std::vector<Limb> limbs;
  for (int side = 0; side < 2; ++side) {
    limbs.push_back({true, side, up_leg(side), leg(side), foot(side), toe(side)});
    limbs.push_back({false, side, upper_arm(side), fore_arm(side), hand(side), -1});
  }

  for (const Limb& limb : limbs) {
    const std::vector<Support>& supports = limb.is_leg ? draft.feet[static_cast<size_t>(limb.side)] : draft.hands[static_cast<size_t>(limb.side)];
    if (supports.empty()) continue;
    const auto S = [](int i) { return static_cast<size_t>(i); };
    // Keyed (FK) end-joint transforms.
    std::vector<LimbFrame> keyed(S(n)), held(S(n));
    for (int f = 0; f < n; ++f) {
      keyed[S(f)].end = positions[S(f)][S(limb.end)];
      keyed[S(f)].end_rotation = rotations[S(f)][S(limb.end)];
      if (limb.end_child >= 0) {
        keyed[S(f)].has_toe = true;
        keyed[S(f)].toe_world = rotations[S(f)][S(limb.end_child)];
      }
    }
    // Held transforms inside supports, and the correction (held relative to keyed) at their ends.
    struct Correction {
      glm::vec3 shift;
      glm::quat turn;
    };
    std::vector<Correction> at_first, at_last;
    for (const Support& s : supports) {
      const int first = std::clamp(s.first, 0, n - 1), last = std::clamp(s.last, 0, n - 1);
      const int mid = (first + last) / 2;
      const LimbFrame& m = keyed[S(mid)];
      float yaw, mid_pitch;
      yaw_pitch(m.end_rotation, yaw, mid_pitch);
      if (!limb.is_leg) {  // the hand's "forward" is its fingers' direction
        const glm::vec3 fingers = m.end_rotation * glm::vec3(side_sign(limb.side), 0, 0);
        yaw = std::atan2(fingers.x, fingers.z);
      }
      if (s.explicit_anchor) yaw = s.anchor_yaw;
      glm::vec3 anchor = s.explicit_anchor ? glm::vec3(s.anchor_xz.x, 0.0f, s.anchor_xz.y) : glm::vec3(m.end.x, 0.0f, m.end.z);
      glm::quat rigid_rotation = yaw_rotation(yaw);
      switch (s.hold) {
        case Hold::RollingFoot:
          anchor.y = anthropometry::kAnkleHeight;
          break;
        case Hold::RigidFoot: {
          float keyed_yaw, pitch;
          yaw_pitch(m.end_rotation, keyed_yaw, pitch);
          rigid_rotation = glm::angleAxis(yaw - keyed_yaw, glm::vec3(0, 1, 0)) * m.end_rotation;
          // Put the toe tip (with the keyed toe angle) on the floor.
          const glm::quat toe_local = glm::inverse(m.end_rotation) * m.toe_world;
          const glm::vec3 tip_from_ankle = rigid_rotation * (ball_offset + toe_local * toe_tip_offset);
          anchor.y = -tip_from_ankle.y;
          break;
        }
        case Hold::PalmDown:
          anchor.y = kWristAboveFloor;
          rigid_rotation = yaw_rotation(yaw) * glm::angleAxis(-side_sign(limb.side) * kHalfPi, glm::vec3(0, 1, 0));
          break;
      }
      for (int f = first; f <= last; ++f) {
        const LimbFrame& k = keyed[S(f)];
        LimbFrame& h = held[S(f)];
        h.has_toe = k.has_toe;
        h.toe_world = k.toe_world;
        if (s.hold == Hold::RollingFoot) {
          float keyed_yaw, pitch;
          yaw_pitch(k.end_rotation, keyed_yaw, pitch);
          const FootHold hold = roll_foot(anchor, yaw, pitch - mid_pitch, f < mid);
          h.end = hold.ankle;
          h.end_rotation = hold.foot;
          h.toe_world = hold.toes;
        } else {
          h.end = anchor;
          h.end_rotation = rigid_rotation;
        }
      }
      const LimbFrame &kf = keyed[S(first)], &hf = held[S(first)], &kl = keyed[S(last)], &hl = held[S(last)];
      at_first.push_back({hf.end - kf.end, hf.end_rotation * glm::inverse(kf.end_rotation)});
      at_last.push_back({hl.end - kl.end, hl.end_rotation * glm::inverse(kl.end_rotation)});
    }
    // Between supports: the keyed path, corrected by a smooth blend of the neighbouring corrections, lifted.
    const size_t count = supports.size();
    for (int f = 0; f < n; ++f) {
      size_t next = 0;
      while (next < count && supports[next].first <= f) ++next;
      if (next > 0 && f <= supports[next - 1].last) continue;  // inside a support
      const LimbFrame& k = keyed[S(f)];
      LimbFrame& h = held[S(f)];
      Correction c;
      float lift = 0.0f;
      if (next == 0) {
        c = at_first[0];
      } else if (next == count) {
        c = at_last[count - 1];
      } else {
        const int e = supports[next - 1].last, b = supports[next].first;
        const float tau = static_cast<float>(f - e) / static_cast<float>(b - e);
        const float w = smooth5(tau);
        c.shift = glm::mix(at_last[next - 1].shift, at_first[next].shift, w);
        c.turn = glm::slerp(at_last[next - 1].turn, at_first[next].turn, w);
        lift = supports[next].lift_before * 16.0f * tau * tau * (1 - tau) * (1 - tau);
      }
      h.end = k.end + c.shift + glm::vec3(0, lift, 0);
      h.end_rotation = glm::normalize(c.turn * k.end_rotation);
      h.has_toe = k.has_toe;
      h.toe_world = glm::normalize(c.turn * k.toe_world);
      if (limb.is_leg) {  // never through the floor: raise the foot if its toe tip or heel would go below it
        const glm::vec3 tip = h.end + h.end_rotation * ball_offset + h.toe_world * toe_tip_offset;
        const glm::vec3 heel = h.end + h.end_rotation * glm::vec3(0, -anthropometry::kAnkleHeight, -0.25f * anthropometry::kFootLength);
        const float low = std::min(tip.y, heel.y);
        if (low < 0.0f) h.end.y -= low;
      }
    }
    // Solve the limb at every frame.
    TwoBoneChain chain;
    chain.upper_length = glm::length(offset(limb.middle));
    chain.lower_length = glm::length(offset(limb.end));
    chain.rest_direction = glm::normalize(offset(limb.middle));
    chain.hinge_axis = limb.is_leg ? glm::vec3(1, 0, 0) : glm::vec3(0, -side_sign(limb.side), 0);
    const int parent = skeleton->joints[S(limb.upper)].parent;
    for (int f = 0; f < n; ++f) {
      const auto& pos = positions[S(f)];
      const auto& rot = rotations[S(f)];
      const LimbFrame& h = held[S(f)];
      // Knees bend toward the front of the thigh; elbows toward the back of the upper arm.
      const glm::vec3 hint = rot[S(limb.upper)] * (limb.is_leg ? glm::vec3(0, 0, 1) : glm::vec3(0, 0, -1));
      const TwoBoneSolution sol = solve_two_bone(chain, pos[S(limb.upper)], h.end, hint);
      if (!sol.reached && report) ++report->unreachable_frames;
      Pose& pose = clip.frames[S(f)];
      const glm::quat middle_local = glm::angleAxis(sol.hinge_angle, chain.hinge_axis);
      const glm::quat middle_world = sol.upper_world * middle_local;
      pose.rotations[S(limb.upper)] = glm::normalize(glm::inverse(rot[S(parent)]) * sol.upper_world);
      pose.rotations[S(limb.middle)] = middle_local;
      pose.rotations[S(limb.end)] = glm::normalize(glm::inverse(middle_world) * h.end_rotation);
      if (limb.end_child >= 0) pose.rotations[S(limb.end_child)] = glm::normalize(glm::inverse(h.end_rotation) * h.toe_world);
    }
  }
  make_hemisphere_continuous(clip);
  return clip;
}

}  // namespace prep::library
