#include "engine/library/draft.h"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>

#include "engine/library/angles.h"
#include "engine/library/builtin.h"
#include "engine/library/rig.h"
#include "engine/library/spline.h"
#include "engine/library/two_bone_ik.h"
#include "engine/motion/kinematics.h"

namespace prep::library {
namespace {

constexpr float kWristAboveFloor = 0.03f;
constexpr float kRelease = 0.4f;  // s over which a limb returns to its keyed path after its last support  // wrist joint centre above the floor with the palm flat on it

glm::quat yaw_rotation(float yaw) { return glm::angleAxis(yaw, glm::vec3(0, 1, 0)); }
glm::quat pitch_rotation(float toe_up) { return glm::angleAxis(-toe_up, glm::vec3(1, 0, 0)); }

struct LimbFrame {
  glm::vec3 end{0.0f};          // ankle or wrist
  glm::quat end_rotation{1, 0, 0, 0};
  bool has_toe = false;
  glm::quat toe_world{1, 0, 0, 0};  // feet: world rotation of the toes
  // A rolling foot: how it is held, so that the heel can rise (further) if the ankle would otherwise
  // dorsiflex beyond kMaxLoadedDorsiflexion.
  bool heel_can_rise = false;
  glm::vec3 flat_anchor{0.0f};
  float yaw = 0.0f, roll = 0.0f;
};

constexpr float kMaxLoadedDorsiflexion = 0.70f;  // rad (40 degrees)
constexpr float kMaxSwingPlantarflexion = 0.82f; // rad (47 degrees, inside the documented 50)

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
    // Heel rocker: the ankle stays above the same floor point and rises just enough that the heel's
    // underside (a quarter foot length behind the ankle) does not go through the floor.
    const float toe_up = std::max(roll, 0.0f);
    h.foot = heading * pitch_rotation(toe_up);
    h.toes = h.foot;
    h.ankle = flat_ankle;
    const float heel_back = 0.25f * anthropometry::kFootLength, height = anthropometry::kAnkleHeight;
    h.ankle.y += std::max(0.0f, heel_back * std::sin(toe_up) - height * (1.0f - std::cos(toe_up)));
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
          h.heel_can_rise = true;  // whenever the ankle would dorsiflex too far, the heel comes up
          h.flat_anchor = anchor;
          h.yaw = yaw;
          h.roll = f >= mid ? std::min(pitch - mid_pitch, 0.0f) : std::max(pitch - mid_pitch, 0.0f);
        } else {
          h.end = anchor;
          h.end_rotation = rigid_rotation;
          if (limb.is_leg) h.toe_world = rigid_rotation * glm::inverse(m.end_rotation) * m.toe_world;  // toes as at mid-support
        }
      }
      const LimbFrame &kf = keyed[S(first)], &hf = held[S(first)], &kl = keyed[S(last)], &hl = held[S(last)];
      at_first.push_back({hf.end - kf.end, hf.end_rotation * glm::inverse(kf.end_rotation)});
      at_last.push_back({hl.end - kl.end, hl.end_rotation * glm::inverse(kl.end_rotation)});
    }
    // Between supports: leave the last held transform and arrive at the next one with zero velocity
    // (a minimum-jerk transfer), carrying the keyed path's own shape (its deviation from its straight
    // transfer: the clearance, the knee's swing) windowed by sin(pi tau) so both ends stay at rest. Before
    // the first and after the last support the keyed path is shifted by that support's correction.
    const size_t count = supports.size();
    for (int f = 0; f < n; ++f) {
      size_t next = 0;
      while (next < count && supports[next].first <= f) ++next;
      if (next > 0 && f <= supports[next - 1].last) continue;  // inside a support
      const LimbFrame& k = keyed[S(f)];
      LimbFrame& h = held[S(f)];
      h.has_toe = k.has_toe;
      if (next == 0 || next == count) {
        // Before the first / after the last support the limb returns to its keyed path within kRelease.
        const int edge = next == 0 ? std::clamp(supports[0].first, 0, n - 1) : std::clamp(supports[count - 1].last, 0, n - 1);
        const float away = static_cast<float>(std::abs(f - edge)) / draft.fps;
        const float keep = 1.0f - smooth5(away / kRelease);
        const Correction c = next == 0 ? at_first[0] : at_last[count - 1];
        h.end = k.end + keep * c.shift;
        const glm::quat turn = glm::slerp(glm::quat(1, 0, 0, 0), c.turn, keep);
        h.end_rotation = glm::normalize(turn * k.end_rotation);
        h.toe_world = glm::normalize(turn * k.toe_world);
      } else {
        const int e = std::clamp(supports[next - 1].last, 0, n - 1), b = std::clamp(supports[next].first, 0, n - 1);
        const float tau = static_cast<float>(f - e) / static_cast<float>(b - e);
        // The transfer along the floor starts after 5% of the swing: a foot leaves the floor vertically
        // and lands with the minimum-jerk profile (no velocity left at touch-down).
        const float w = smooth5((tau - 0.05f) / 0.95f);
        // The vertical shape starts at once, the horizontal one more gently: a foot lifts before it moves on.
        const float tau_flat = std::clamp((tau - 0.05f) / 0.95f, 0.0f, 1.0f);
        const float window = std::sin(3.14159265f * tau), window_flat = std::pow(std::sin(3.14159265f * tau_flat), 2.0f);
        const LimbFrame &he = held[S(e)], &hb = held[S(b)], &ke = keyed[S(e)], &kb = keyed[S(b)];
        const glm::vec3 keyed_shape = k.end - glm::mix(ke.end, kb.end, w);
        const float lift = supports[next].lift_before * window;
        h.end = glm::mix(he.end, hb.end, w) + glm::vec3(window_flat * keyed_shape.x, window * keyed_shape.y, window_flat * keyed_shape.z) +
                glm::vec3(0, lift, 0);
        const glm::quat keyed_turn = glm::normalize(k.end_rotation * glm::inverse(glm::slerp(ke.end_rotation, kb.end_rotation, w)));
        const glm::quat shape_turn = glm::slerp(glm::quat(1, 0, 0, 0), keyed_turn, window_flat);
        h.end_rotation = glm::normalize(shape_turn * glm::slerp(he.end_rotation, hb.end_rotation, w));
        if (k.has_toe) {  // the toes relative to the foot, blended likewise
          const glm::quat toe_e = glm::inverse(he.end_rotation) * he.toe_world, toe_b = glm::inverse(hb.end_rotation) * hb.toe_world;
          const glm::quat toe_k = glm::inverse(k.end_rotation) * k.toe_world;
          const glm::quat toe_line = glm::slerp(toe_e, toe_b, w);
          h.toe_world = glm::normalize(h.end_rotation * glm::slerp(toe_line, toe_k, window_flat));
        }
      }
      if (limb.is_leg) {  // never through the floor: raise the foot if its toe tip or heel would go below it
        const glm::vec3 tip = h.end + h.end_rotation * ball_offset + h.toe_world * toe_tip_offset;
        const glm::vec3 heel = h.end + h.end_rotation * glm::vec3(0, -anthropometry::kAnkleHeight, -0.25f * anthropometry::kFootLength);
        const float low = std::min(tip.y, heel.y);
        if (low < 0.0f) h.end.y -= low;
      }
    }
    std::vector<bool> in_support(S(n), false);
    for (const Support& s : supports)
      for (int f = std::max(s.first, 0); f <= std::min(s.last, n - 1); ++f) in_support[S(f)] = true;
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
      LimbFrame h = held[S(f)];
      // Knees bend toward the front of the thigh; elbows toward the back of the upper arm.
      const glm::vec3 hint = rot[S(limb.upper)] * (limb.is_leg ? glm::vec3(0, 0, 1) : glm::vec3(0, 0, -1));
      TwoBoneSolution sol = solve_two_bone(chain, pos[S(limb.upper)], h.end, hint);
      for (int pass = 0; pass < 4 && h.heel_can_rise; ++pass) {
        const glm::quat shin = sol.upper_world * glm::angleAxis(sol.hinge_angle, chain.hinge_axis);
        const glm::vec3 forward = glm::inverse(shin) * h.end_rotation * glm::vec3(0, 0, 1);
        const float dorsiflexion = std::asin(std::clamp(forward.y, -1.0f, 1.0f));
        if (dorsiflexion <= kMaxLoadedDorsiflexion) break;
        h.roll -= dorsiflexion - kMaxLoadedDorsiflexion;  // raise the heel by the excess, about the ball
        const FootHold hold = roll_foot(h.flat_anchor, h.yaw, h.roll, false);
        h.end = hold.ankle;
        h.end_rotation = hold.foot;
        h.toe_world = hold.toes;
        sol = solve_two_bone(chain, pos[S(limb.upper)], h.end, hint);
      }
      if (!sol.reached && report) {
        ++report->unreachable_frames;
        const float over = glm::length(h.end - pos[S(limb.upper)]) - chain.upper_length - chain.lower_length;
        report->worst_overreach = std::max(report->worst_overreach, over);
      }
      Pose& pose = clip.frames[S(f)];
      const glm::quat middle_local = glm::angleAxis(sol.hinge_angle, chain.hinge_axis);
      const glm::quat middle_world = sol.upper_world * middle_local;
      pose.rotations[S(limb.upper)] = glm::normalize(glm::inverse(rot[S(parent)]) * sol.upper_world);
      pose.rotations[S(limb.middle)] = middle_local;
      pose.rotations[S(limb.end)] = glm::normalize(glm::inverse(middle_world) * h.end_rotation);
      if (limb.is_leg && !in_support[S(f)]) {
        // A swinging foot keeps within the ankle's range: turn it about the ankle if the blend of the keyed
        // and held orientations would dorsiflex or plantarflex it too far (a kneeling foot lifting off).
        const glm::vec3 forward = pose.rotations[S(limb.end)] * glm::vec3(0, 0, 1);
        const float dorsiflexion = std::asin(std::clamp(forward.y, -1.0f, 1.0f));
        const float within = std::clamp(dorsiflexion, -kMaxSwingPlantarflexion, kMaxLoadedDorsiflexion);
        if (dorsiflexion != within) {
          const glm::quat fix = glm::angleAxis(dorsiflexion - within, glm::vec3(1, 0, 0));
          pose.rotations[S(limb.end)] = glm::normalize(pose.rotations[S(limb.end)] * fix);
          h.end_rotation = glm::normalize(h.end_rotation * fix);
          h.toe_world = glm::normalize(h.toe_world * fix);
        }
      }
      if (limb.end_child >= 0) pose.rotations[S(limb.end_child)] = glm::normalize(glm::inverse(h.end_rotation) * h.toe_world);
    }
  }
  make_hemisphere_continuous(clip);
  return clip;
}

}  // namespace prep::library
