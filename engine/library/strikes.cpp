// punch_left, punch_right and kick: walk in, set up (guard stance / plant foot), strike, recover, walk on.
#include "engine/library/action.h"
#include "engine/library/angles.h"
#include "engine/library/rig.h"

namespace prep::library {
namespace {
// Boxing guard (orthodox: left foot forward): knees soft, chest turned a little to the right, both fists
// at chin height, elbows down.
void guard(DofPose& d) {
  for (int side = 0; side < 2; ++side) {
    d.at(side, kShoulderFlex) = 40 * kDeg;
    d.at(side, kShoulderAbduct) = 18 * kDeg;
    d.at(side, kShoulderTwist) = 35 * kDeg;
    d.at(side, kElbowFlex) = 118 * kDeg;
    d.at(side, kWristFlex) = 0.0f;
    d.at(side, kHipFlex) = 10 * kDeg;
    d.at(side, kKneeFlex) = 12 * kDeg;
    d.at(side, kAnkleDorsi) = 6 * kDeg;
  }
  d[kYaw] = -12 * kDeg;
  d[kSpineTwist] = -6 * kDeg;
  d[kSpineFlex] = 4 * kDeg;
  d[kNeckFlex] = 6 * kDeg;
  d[kNeckTwist] = 9 * kDeg;
  d[kHeadTwist] = 9 * kDeg;
}
}  // namespace

GeneratedClip make_punch(const std::string& name, bool left) {
  ActionSpec spec;
  spec.name = name;
  spec.role = left ? Role::PunchLeft : Role::PunchRight;
  spec.gait = plan_gait(1.4f, 1.0f, 60.0f);
  const float T = spec.gait.cycle_s;
  const float step = 0.5f * spec.gait.stride_m;
  const Walker in = walk_in(spec);
  const Support right_down = in.supports(1, 0.0f, 0.0f, 0.0f).back();
  const float right_z = right_down.anchor_xz.y;
  const float left_z = right_z + 0.38f;  // the lead foot steps into the stance
  const float strike = 1.0f, resume = 2.4f;
  spec.walk_in_s = T;
  spec.resume_time = resume;
  spec.resume_phase = 0.0f;  // the right foot (rear) steps through into the walk
  spec.resume_origin = {0.0f, left_z + step - right_z};
  spec.walk_out_s = T;
  spec.target_time = strike;
  const float stance_z = 0.5f * (right_z + left_z) + 0.03f;  // root over the middle of the feet
  auto key = [&](float t, float z, float y, auto&& edit) {
    DofPose d = standing_pose({0.0f, z}, y);
    guard(d);
    edit(d);
    spec.keys.push_back({t, d, false, {}});
  };
  // Raising the guard while stepping into the stance.
  key(0.5f, stance_z + 0.05f, 0.92f, [](DofPose& d) { d.at(0, kHipFlex) = 22 * kDeg; });
  key(0.8f, stance_z, 0.92f, [](DofPose&) {});
  key(strike, stance_z, 0.92f, [](DofPose&) {});
  const int s = left ? 0 : 1;
  // The strike: shoulder forward to horizontal, elbow straight; the body turns into it.
  key(strike + 0.14f, stance_z + (left ? 0.04f : 0.06f), 0.91f, [&](DofPose& d) {
    d.at(s, kShoulderFlex) = 85 * kDeg;
    d.at(s, kShoulderAbduct) = 8 * kDeg;
    d.at(s, kShoulderTwist) = 10 * kDeg;
    d.at(s, kElbowFlex) = 6 * kDeg;
    d[kYaw] = (left ? -22 : 14) * kDeg;
    d[kSpineTwist] = (left ? -10 : 22) * kDeg;
    d[kNeckTwist] = d[kHeadTwist] = -0.5f * (d[kYaw] + d[kSpineTwist]);
  });
  key(strike + 0.36f, stance_z, 0.92f, [](DofPose&) {});
  key(1.9f, stance_z + 0.02f, 0.92f, [](DofPose&) {});
  spec.feet[1] = {{0.0f, 2.0f, Hold::RollingFoot, false, {}, 0.0f, 0.0f}};
  spec.feet[0] = {{0.55f, resume + (kStanceFraction - 0.5f) * T, Hold::RollingFoot, true, {0.12f, left_z}, 0.0f, 0.06f}};
  return compose_action(spec);
}

GeneratedClip make_kick(const std::string& name) {
  ActionSpec spec;
  spec.name = name;
  spec.role = Role::Kick;
  spec.gait = plan_gait(1.4f, 1.0f, 60.0f);
  const float T = spec.gait.cycle_s;
  const float step = 0.5f * spec.gait.stride_m;
  const Walker in = walk_in(spec);
  const float right_z = in.supports(1, 0.0f, 0.0f, 0.0f).back().anchor_xz.y;
  const float plant_z = right_z + 0.55f;  // the left (support) foot plants beside the ball
  const float resume = 2.1f;
  spec.walk_in_s = T;
  spec.resume_time = resume;
  spec.resume_phase = 0.5f;  // the walk goes on with a left heel strike
  spec.walk_out_s = T;
  spec.target_time = 0.55f;   // the kicking leg's back-swing starts
  const float land_z = plant_z + 0.05f;  // the kicking foot comes down just ahead of the plant foot
  spec.resume_origin = {0.0f, land_z + step - right_z};
  auto key = [&](float t, float z, float y, auto&& edit) {
    DofPose d = standing_pose({0.0f, z}, y);
    edit(d);
    spec.keys.push_back({t, d, false, {}});
  };
  // Plant: the left foot lands beside the ball, the body over it, arms out for balance.
  key(0.55f, plant_z - 0.2f, 0.88f, [](DofPose& d) {
    d.at(0, kHipFlex) = 25 * kDeg;
    d.at(0, kKneeFlex) = 20 * kDeg;
    d.at(1, kHipFlex) = -15 * kDeg;
    d.at(1, kKneeFlex) = 40 * kDeg;
    d.at(0, kShoulderAbduct) = d.at(1, kShoulderAbduct) = 30 * kDeg;
  });
  // Back-swing of the right leg.
  key(0.75f, plant_z - 0.08f, 0.86f, [](DofPose& d) {
    d.at(0, kKneeFlex) = 20 * kDeg;
    d.at(0, kHipFlex) = 15 * kDeg;
    d.at(1, kHipFlex) = -25 * kDeg;
    d.at(1, kKneeFlex) = 95 * kDeg;
    d.at(1, kAnkleDorsi) = -30 * kDeg;
    d.at(0, kShoulderAbduct) = 40 * kDeg;
    d.at(1, kShoulderAbduct) = 30 * kDeg;
    d.at(0, kShoulderFlex) = 20 * kDeg;
    d.at(1, kShoulderFlex) = -20 * kDeg;
    d[kSpineFlex] = -2 * kDeg;
    d[kNeckFlex] = 20 * kDeg;
  });
  // Contact: the leg swings through, knee extending, the instep meets the ball.
  key(0.92f, plant_z - 0.04f, 0.87f, [](DofPose& d) {
    d.at(0, kKneeFlex) = 22 * kDeg;
    d.at(0, kHipFlex) = 20 * kDeg;
    d.at(1, kHipFlex) = 45 * kDeg;
    d.at(1, kKneeFlex) = 25 * kDeg;
    d.at(1, kAnkleDorsi) = -35 * kDeg;
    d.at(0, kShoulderAbduct) = 35 * kDeg;
    d.at(1, kShoulderAbduct) = 25 * kDeg;
    d.at(0, kShoulderFlex) = -15 * kDeg;
    d.at(1, kShoulderFlex) = 25 * kDeg;
    d[kSpineFlex] = 6 * kDeg;
    d[kNeckFlex] = 25 * kDeg;
  });
  // Follow-through.
  key(1.08f, plant_z, 0.88f, [](DofPose& d) {
    d.at(0, kKneeFlex) = 15 * kDeg;
    d.at(0, kHipFlex) = 12 * kDeg;
    d.at(1, kHipFlex) = 62 * kDeg;
    d.at(1, kKneeFlex) = 15 * kDeg;
    d.at(1, kAnkleDorsi) = -20 * kDeg;
    d.at(0, kShoulderAbduct) = d.at(1, kShoulderAbduct) = 25 * kDeg;
    d[kSpineFlex] = 10 * kDeg;
  });
  // The kicking foot comes down; weight onto it.
  key(1.45f, plant_z + 0.1f, 0.9f, [](DofPose& d) {
    d.at(1, kHipFlex) = 15 * kDeg;
    d.at(1, kKneeFlex) = 10 * kDeg;
  });
  // Right: walk-in stance, then down after the kick until the walk's right toe-off.
  spec.feet[1] = {{0.0f, 0.55f, Hold::RollingFoot, false, {}, 0.0f, 0.0f},
                  {1.40f, resume + (kStanceFraction - 0.5f) * T, Hold::RollingFoot, true, {-0.10f, land_z}, -0.05f, 0.10f}};
  spec.feet[0] = {{0.50f, resume - 0.5f * T + (kStanceFraction - 0.5f) * T, Hold::RollingFoot, true, {0.16f, plant_z}, 0.08f, 0.06f}};
  return compose_action(spec);
}

}  // namespace prep::library
