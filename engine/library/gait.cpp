#include "engine/library/gait.h"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>

#include "engine/library/angles.h"
#include "engine/library/builtin.h"
#include "engine/library/rig.h"
#include "engine/library/spline.h"
#include "engine/motion/kinematics.h"

namespace prep::library {
namespace {

// Sagittal joint angles of normal adult walking at natural cadence, degrees, every 5% of the cycle from
// heel strike (0%) to 95%: our reading of the shapes of Winter's (1991) normative ensemble averages.
//   hip: thigh relative to the pelvis, flexion +: ~30 at heel strike, ~-10 at 50-55%, peak ~32 at 90%.
//   knee: flexion +: loading-response peak ~19 at 15%, ~5 at 40%, ~36 at toe-off, swing peak ~63 at 73%.
//   ankle: dorsiflexion +: ~-5 after heel strike, ~+10 at 40-45%, ~-17 just after toe-off, ~0 in swing.
const std::vector<float> kHipFlexion = {30, 29, 28, 26, 21, 15, 10, 5, 1, -3, -7, -10, -9, -2, 8, 17, 25, 30, 32, 31};
const std::vector<float> kKneeFlexion = {3, 11, 17, 19, 17, 13, 9, 6, 5, 5, 10, 22, 36, 50, 60, 63, 58, 46, 28, 11};
const std::vector<float> kAnkleDorsiflexion = {0, -4, -5, -2, 2, 5, 7, 9, 10, 10, 8, 2, -8, -16, -17, -10, -4, -1, 0, 0};

// Means and amplitudes of the pelvis and trunk (Perry 1992, ch. 10; Winter 1991): the pelvis tilts ~6
// degrees anteriorly on average with a ~3 degree double oscillation, rotates +-4 degrees (the swing-side
// hip forward) and drops +-4 degrees on the swing side in single support; the thorax counter-rotates.
constexpr float kPelvisMeanTilt = 6 * kDeg;
constexpr float kPelvisTiltSwing = 1.5f * kDeg;
constexpr float kPelvisRotation = 4 * kDeg;
constexpr float kPelvisObliquity = 4 * kDeg;
constexpr float kThoraxCounterRotation = 1.6f;  // chest twist relative to the pelvis, times the pelvic rotation
constexpr float kLateralSway = 0.022f;          // m: pelvis toward the stance foot (~4-5 cm peak to peak)
// Arms: shoulder swings about a slightly forward mean, opposite the leg of the same side, lagging ~5%.
constexpr float kShoulderSwing = 15 * kDeg;
constexpr float kShoulderMean = 3 * kDeg;
constexpr float kElbowMean = 20 * kDeg;
constexpr float kElbowSwing = 8 * kDeg;
// Forward speed of the body over the cycle: slowest at mid-stance, fastest at double support (the
// inverted-pendulum exchange of kinetic and potential energy), +-8% (Winter 1991).
constexpr float kSpeedModulation = 0.08f;
// Our sagittal-only leg chain carries the toe too low through swing (real limbs add pelvic hiking and a
// little circumduction); this much is added to the swing foot's height at mid-swing so that the toe
// clears the floor all through the swing.
constexpr float kSwingLift = 0.06f;
// The pelvis stays this much below the height the stance legs allow, so that the sway, the pelvic
// rotation and the turns (which the height plan ignores) never straighten a stance knee completely.
constexpr float kKneeMargin = 0.025f;

float wrap01(float x) { return x - std::floor(x); }

// Leg angles of one leg at its own phase (0 = its heel strike).
void set_leg(DofPose& d, int side, float leg_phase, float amplitude) {
  const float hip = periodic_catmull_rom(kHipFlexion, leg_phase);
  constexpr float hip_mean = 10.0f;  // keep the mean posture when scaling the excursion
  d.at(side, kHipFlex) = (hip_mean + amplitude * (hip - hip_mean)) * kDeg;
  d.at(side, kKneeFlex) = amplitude * periodic_catmull_rom(kKneeFlexion, leg_phase) * kDeg;
  d.at(side, kAnkleDorsi) = amplitude * periodic_catmull_rom(kAnkleDorsiflexion, leg_phase) * kDeg;
  d.at(side, kHipRotation) = 2 * kDeg;
  d.at(side, kHipAbduct) = 0.0f;
}

}  // namespace

DofPose gait_pose(const GaitStyle& style, float phase) {
  DofPose d;
  const float p = wrap01(phase);
  const float two_pi_p = 2 * kPi * p;
  const float a = style.amplitude;
  set_leg(d, 1, p, a);
  set_leg(d, 0, p + 0.5f, a);
  // Pelvis: rotation (right hip forward at right heel strike), obliquity (the swing side drops in single
  // support, peak ~20%), anterior tilt (peaks at each double support), sway toward the stance foot.
  const float rotation = a * kPelvisRotation * std::cos(two_pi_p);
  d[kYaw] = rotation;
  d[kPelvisRoll] = -a * kPelvisObliquity * std::sin(2 * kPi * (p + 0.05f));
  d[kPelvisTilt] = kPelvisMeanTilt + a * kPelvisTiltSwing * std::cos(4 * kPi * (p - 0.05f));
  d[kRootX] = -kLateralSway / std::max(a, 0.6f) * std::sin(2 * kPi * (p - 0.03f));
  d[kRootY] = style.pelvis_height.empty() ? anthropometry::kRootHeight : periodic_catmull_rom(style.pelvis_height, p);
  d[kRootZ] = 0.0f;
  // Trunk: cancel the mean pelvic tilt and the obliquity (the trunk stays upright), lean a little forward,
  // counter-rotate the chest; neck and head keep the gaze level and forward.
  d[kSpineFlex] = style.trunk_lean - d[kPelvisTilt];
  d[kSpineBend] = d[kPelvisRoll] * 0.8f;
  d[kSpineTwist] = -kThoraxCounterRotation * rotation;
  d[kNeckTwist] = -(rotation + d[kSpineTwist]) * 0.5f;
  d[kHeadTwist] = -(rotation + d[kSpineTwist]) * 0.5f;
  d[kNeckFlex] = -style.trunk_lean * 0.5f;
  d[kHeadFlex] = 4 * kDeg - style.trunk_lean * 0.5f;
  d[kHeadBend] = -d[kPelvisRoll] * 0.2f;
  // Arms swing opposite their legs: the right arm is furthest back just after right heel strike.
  for (int side = 0; side < 2; ++side) {
    const float arm_phase = side == 1 ? p : p + 0.5f;
    const float forward = -std::cos(2 * kPi * (arm_phase - 0.05f));  // -1 back .. +1 forward
    d.at(side, kShoulderFlex) = kShoulderMean + style.arm_swing * kShoulderSwing * forward;
    d.at(side, kShoulderAbduct) = 7 * kDeg;
    d.at(side, kShoulderTwist) = 10 * kDeg;
    d.at(side, kElbowFlex) = kElbowMean + style.arm_swing * kElbowSwing * (forward + 1) * 0.5f;
    d.at(side, kWristFlex) = 5 * kDeg;
    d.at(side, kClavicleElevation) = 0.0f;
    d.at(side, kClavicleProtraction) = 0.02f * forward;
  }
  return d;
}

GaitStyle plan_gait(float speed, float amplitude, float fps) {
  GaitStyle style;
  style.amplitude = amplitude;
  style.arm_swing = amplitude;
  style.fps = fps;
  style.trunk_lean = 0.03f + 0.025f * speed;
  const auto skeleton = builtin_skeleton();
  std::vector<glm::vec3> pos;
  std::vector<glm::quat> rot;
  // Root-relative ankle and ball of the right leg over the cycle, with the pelvis at height 0.
  constexpr int kSamples = 120;
  std::vector<glm::vec3> ankle(kSamples), hip(kSamples);
  std::vector<float> pitch(kSamples);
  for (int i = 0; i < kSamples; ++i) {
    DofPose d = gait_pose(style, static_cast<float>(i) / kSamples);
    d[kRootX] = d[kRootY] = d[kRootZ] = 0.0f;
    forward_kinematics(*skeleton, to_pose(d), pos, &rot);
    ankle[static_cast<size_t>(i)] = pos[kRightFoot];
    hip[static_cast<size_t>(i)] = pos[kRightUpLeg];
    const glm::vec3 forward = rot[kRightFoot] * glm::vec3(0, 0, 1);
    pitch[static_cast<size_t>(i)] = std::asin(std::clamp(forward.y, -1.0f, 1.0f));
  }
  // Where a planted foot puts the ankle relative to its flat position at each stance phase (roll_foot).
  const size_t mid = static_cast<size_t>(kSamples * kStanceFraction * 0.5f), off = static_cast<size_t>(kSamples * kStanceFraction);
  std::vector<glm::vec3> held(kSamples, glm::vec3(0.0f));
  for (size_t i = 0; i <= off; ++i)
    held[i] = roll_foot(glm::vec3(0, anthropometry::kAnkleHeight, 0), 0.0f, pitch[i] - pitch[mid], i < mid).ankle;
  // Stride: over a stance the root travels as far as the ankle moves back relative to it, less how far
  // the rolling foot carries the ankle forward (stance is kStanceFraction of the stride).
  const float stance_travel = (ankle[0].z - held[0].z) - (ankle[off].z - held[off].z);
  const float per_phase = stance_travel / kStanceFraction;
  style.stride_m = per_phase;
  const float frames = std::round(per_phase / speed * fps);
  style.cycle_s = frames / fps;
  style.speed = style.stride_m / style.cycle_s;
  // Pelvis height. A stance foot is anchored where the swing brought its heel down (the ankle at heel
  // strike) and then held by roll_foot while the root moves on along the path. The stance leg keeps the
  // table's hip-to-ankle distance (i.e. its knee flexion) and the pelvis is as high as that allows.
  const auto root_travel = [&](float p) {  // root z at phase p (integral of the modulated speed)
    return style.stride_m * (p + kSpeedModulation / (4 * kPi) * std::sin(4 * kPi * (p - 0.05f)));
  };
  std::vector<float> need(kSamples);
  for (int i = 0; i < kSamples; ++i) {
    float lowest = 1e9f;
    for (int side = 0; side < 2; ++side) {
      const float leg_phase = wrap01(static_cast<float>(i) / kSamples + (side == 0 ? 0.5f : 0.0f));
      if (leg_phase >= kStanceFraction) continue;
      const size_t j = static_cast<size_t>(std::lround(leg_phase * kSamples)) % kSamples;  // same leg shape, shifted
      // Held ankle relative to the root (right-leg shapes; the left leg is its mirror half a cycle later).
      glm::vec3 ankle_held = ankle[0] + held[j] - held[0];
      ankle_held.z -= root_travel(leg_phase) - root_travel(0.0f);
      const glm::vec3 reach = ankle[j] - hip[j];  // the table's hip-to-ankle vector
      const float horizontal2 = (ankle_held.x - hip[j].x) * (ankle_held.x - hip[j].x) + (ankle_held.z - hip[j].z) * (ankle_held.z - hip[j].z);
      const float drop = std::sqrt(std::max(glm::dot(reach, reach) - horizontal2, 0.0f));
      // Root height that puts the hip `drop` above the held ankle, with the ankle's held height above the floor.
      const float required = held[j].y + drop - hip[j].y;
      lowest = std::min(lowest, required);
    }
    need[static_cast<size_t>(i)] = lowest;
  }
  // The pelvis cannot drop abruptly when the swing heel comes down: limit the height's slope to
  // kMaxBobSlope (m per cycle) below the need (the lower envelope of cones), then smooth with a periodic
  // Gaussian (sigma 3% of the cycle) into a table of 40 samples.
  constexpr float kMaxBobSlope = 0.35f;
  {
    std::vector<float> envelope(need);
    for (int i = 0; i < kSamples; ++i)
      for (int j = 0; j < kSamples; ++j) {
        float dp = static_cast<float>(i - j) / kSamples;
        dp -= std::round(dp);
        envelope[static_cast<size_t>(i)] = std::min(envelope[static_cast<size_t>(i)], need[static_cast<size_t>(j)] + kMaxBobSlope * std::fabs(dp));
      }
    need = envelope;
  }
  constexpr int kHeightSamples = 40;
  style.pelvis_height.assign(kHeightSamples, 0.0f);
  for (int k = 0; k < kHeightSamples; ++k) {
    float sum = 0, weight = 0;
    for (int i = 0; i < kSamples; ++i) {
      float dp = static_cast<float>(i) / kSamples - static_cast<float>(k) / kHeightSamples;
      dp -= std::round(dp);
      const float w = std::exp(-0.5f * dp * dp / (0.03f * 0.03f));
      sum += w * need[static_cast<size_t>(i)];
      weight += w;
    }
    style.pelvis_height[static_cast<size_t>(k)] = sum / weight;
  }
  // Keep the stance knees a little bent everywhere: a margin under the smooth height.
  float worst = 0.0f;
  for (int i = 0; i < kSamples; ++i)
    worst = std::max(worst, periodic_catmull_rom(style.pelvis_height, static_cast<float>(i) / kSamples) - need[static_cast<size_t>(i)]);
  for (float& y : style.pelvis_height) y -= worst + kKneeMargin;
  return style;
}

Walker::Walker(GaitStyle style, float phase0, glm::vec2 origin, float heading0, std::function<float(float)> heading_change)
    : style_(std::move(style)), phase0_(phase0), heading0_(heading0), origin_(origin), turn_(std::move(heading_change)) {
  // Integrate the path over +-30 s around t = 0 (midpoint rule).
  path_dt_ = 1.0f / (4.0f * style_.fps);
  const int half = static_cast<int>(30.0f / path_dt_);
  path_t0_ = -half * path_dt_;
  path_.assign(static_cast<size_t>(2 * half + 1), origin_);
  // The body moves slowest at mid-stance and fastest at double support (+-kSpeedModulation).
  const auto step = [&](float t) {
    const float h = heading(t);
    const float v = style_.speed * (1.0f + kSpeedModulation * std::cos(4 * kPi * (phase(t) - 0.05f)));
    return v * path_dt_ * glm::vec2(std::sin(h), std::cos(h));
  };
  for (int i = half + 1; i <= 2 * half; ++i)
    path_[static_cast<size_t>(i)] = path_[static_cast<size_t>(i - 1)] + step(path_t0_ + (i - 0.5f) * path_dt_);
  for (int i = half - 1; i >= 0; --i)
    path_[static_cast<size_t>(i)] = path_[static_cast<size_t>(i + 1)] - step(path_t0_ + (i + 0.5f) * path_dt_);
}

glm::vec2 Walker::path(float t) const {
  const float x = std::clamp((t - path_t0_) / path_dt_, 0.0f, static_cast<float>(path_.size() - 1));
  const size_t i = std::min(static_cast<size_t>(x), path_.size() - 2);
  const float f = x - static_cast<float>(i);
  return path_[i] * (1 - f) + path_[i + 1] * f;
}

DofPose Walker::pose(float t) const {
  DofPose d = gait_pose(style_, phase(t));
  const float h = heading(t);
  const glm::vec2 p = path(t);
  const glm::vec2 lateral(std::cos(h), -std::sin(h));  // the character's left for heading h
  const glm::vec2 root = p + lateral * d[kRootX];
  d[kRootX] = root.x;
  d[kRootZ] = root.y;
  d[kYaw] += h;
  // Turning: the head leads the turn by ~0.3 s and the body leans into it a little, its centre of mass
  // shifted toward the inside of the curve (the centripetal lean, ~v * rate * h / g).
  const float rate = (heading(t + 0.01f) - heading(t - 0.01f)) / 0.02f;
  const glm::vec2 inward = lateral * (style_.speed * rate * 0.9f / 9.81f) * 0.5f;
  d[kRootX] += inward.x;
  d[kRootZ] += inward.y;
  d[kNeckTwist] += 0.15f * rate;
  d[kHeadTwist] += 0.15f * rate;
  d[kPelvisRoll] -= 0.03f * rate;
  return d;
}

DofPose Walker::velocity(float t) const {
  const float dt = 0.5f / style_.fps;
  return (pose(t + dt) - pose(t - dt)) * (1.0f / (2 * dt));
}

std::vector<Support> Walker::supports(int side, float t_begin, float t_end, float clip_t0) const {
  std::vector<Support> out;
  const float T = style_.cycle_s;
  const float offset = side == 0 ? 0.5f : 0.0f;  // left heel strikes half a cycle after the right
  // Heel strikes at times where phase(t) - offset is an integer.
  const float k_first = std::floor(phase(t_begin) - offset) - 1.0f;
  const float k_last = std::ceil(phase(t_end) - offset);
  for (float k = k_first; k <= k_last; k += 1.0f) {
    const float on = (k + offset - phase0_) * T;
    const float off = on + kStanceFraction * T;
    if (off < t_begin || on > t_end) continue;
    Support s;
    s.first = static_cast<int>(std::lround((on - clip_t0) * style_.fps));
    s.last = static_cast<int>(std::lround((off - clip_t0) * style_.fps)) - 1;
    const float mid = 0.5f * (on + off);
    const float h = heading(mid);
    const glm::vec2 forward(std::sin(h), std::cos(h)), lateral(std::cos(h), -std::sin(h));
    // Where the swing brings the heel down (the keyed ankle at heel strike) along the path; beside the
    // path by half the step width.
    const auto skeleton = builtin_skeleton();
    std::vector<glm::vec3> pos;
    forward_kinematics(*skeleton, to_pose(pose(on)), pos);
    const glm::vec2 ankle(pos[static_cast<size_t>(foot(side))].x, pos[static_cast<size_t>(foot(side))].z);
    const glm::vec2 centre = path(on);
    s.explicit_anchor = true;
    s.anchor_xz = centre + forward * glm::dot(ankle - centre, forward) + lateral * (side_sign(side) * style_.step_half_width);
    s.anchor_yaw = h + side_sign(side) * style_.toe_out;
    s.lift_before = kSwingLift;
    out.push_back(s);
  }
  return out;
}

}  // namespace prep::library
