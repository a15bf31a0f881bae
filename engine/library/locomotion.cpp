// Locomotion clips of the built-in library: walks, walking turns, side-steps, idle.
#include <cmath>

#include "engine/library/angles.h"
#include "engine/library/gait.h"
#include "engine/library/generated.h"
#include "engine/library/rig.h"
#include "engine/library/spline.h"
#include "engine/library/action.h"

namespace prep::library {
namespace {
// A cyclic clip of `cycles` gait cycles from a walker, generated with a cycle of padding on each side so
// that the supports around the loop seam are the same as anywhere else.
GeneratedClip walk_clip(const std::string& name, const Walker& walker, int cycles, Role role) {
  const GaitStyle& g = walker.style();
  const int per_cycle = static_cast<int>(std::lround(g.cycle_s * g.fps));
  const int pad = per_cycle;
  const int count = cycles * per_cycle;
  Draft draft;
  draft.name = name;
  draft.fps = g.fps;
  const float t0 = -static_cast<float>(pad) / g.fps;
  for (int f = 0; f < count + 2 * pad; ++f) draft.frames.push_back(walker.pose(t0 + static_cast<float>(f) / g.fps));
  const float t1 = t0 + static_cast<float>(count + 2 * pad) / g.fps;
  for (int side = 0; side < 2; ++side) draft.feet[static_cast<size_t>(side)] = walker.supports(side, t0, t1, t0);
  GeneratedClip out;
  out.clip = crop(realize(draft, &out.report), pad, count);
  out.role = role;
  out.cyclic = true;
  out.loop_first = 0;
  out.loop_last = count - 1;
  return out;
}
}  // namespace

Clip crop(const Clip& clip, int first, int count) {
  Clip out = clip;
  out.frames.assign(clip.frames.begin() + first, clip.frames.begin() + first + count);
  return out;
}

GeneratedClip make_walk(const std::string& name, float speed, float amplitude) {
  const Walker walker(plan_gait(speed, amplitude, kLibraryFps), 0.0f, {0.0f, 0.0f}, 0.0f);
  return walk_clip(name, walker, 2, Role::Walk);
}

GeneratedClip make_turn(const std::string& name, bool left) {
  // A 90 degree walking turn over two cycles at a moderate pace; the heading changes with a minimum-jerk
  // profile, so the clip starts and ends walking straight and chains with itself and with the walk.
  const GaitStyle style = plan_gait(1.1f, 0.85f, kLibraryFps);
  const float span = 2.0f * style.cycle_s;
  const float total = (left ? 1.0f : -1.0f) * 0.5f * kPi;
  const Walker walker(style, 0.0f, {0.0f, 0.0f}, 0.0f, [span, total](float t) { return total * smooth5(t / span); });
  return walk_clip(name, walker, 2, left ? Role::TurnLeft : Role::TurnRight);
}

}  // namespace prep::library

namespace prep::library {

GeneratedClip make_idle(const std::string& name) {
  // Quiet standing: breathing (~15 breaths a minute: chest and shoulders rise, the spine extends a
  // little) and a slow weight shift from foot to foot (~8 s), as in quiet stance sway. One 8 s loop.
  constexpr float kDuration = 8.0f, kBreath = 4.0f;
  const int count = static_cast<int>(kDuration * kLibraryFps);
  Draft draft;
  draft.name = name;
  draft.fps = kLibraryFps;
  constexpr float kHalfStance = 0.10f;
  for (int f = 0; f < count; ++f) {
    const float t = static_cast<float>(f) / kLibraryFps;
    const float breath = 0.5f - 0.5f * std::cos(2 * kPi * t / kBreath);      // 0 exhaled .. 1 inhaled
    const float shift = std::sin(2 * kPi * t / kDuration);                   // -1 right .. +1 left
    DofPose d = [&] {
      DofPose s;
      s[kRootY] = anthropometry::kRootHeight - 0.012f - 0.004f * std::fabs(shift);
      s[kRootX] = 0.025f * shift;
      s[kRootZ] = 0.0f;
      s[kPelvisTilt] = 6 * kDeg;
      s[kPelvisRoll] = -2.0f * kDeg * shift;  // the unloaded side's hip drops a little
      s[kSpineFlex] = (-5.0f - 1.2f * breath) * kDeg;
      s[kSpineBend] = 1.6f * kDeg * shift;
      s[kNeckFlex] = 1.0f * breath * kDeg;
      s[kHeadFlex] = 3 * kDeg;
      s[kHeadTwist] = 4 * kDeg * std::sin(2 * kPi * t / kDuration * 2.0f);
      for (int side = 0; side < 2; ++side) {
        s.at(side, kClavicleElevation) = 1.5f * kDeg * breath;
        s.at(side, kShoulderAbduct) = (7 + 1.0f * breath) * kDeg;
        s.at(side, kShoulderFlex) = 3 * kDeg;
        s.at(side, kShoulderTwist) = 10 * kDeg;
        s.at(side, kElbowFlex) = 14 * kDeg;
        s.at(side, kWristFlex) = 5 * kDeg;
        s.at(side, kHipFlex) = 3 * kDeg;
        s.at(side, kKneeFlex) = 5 * kDeg;
        s.at(side, kHipRotation) = 2 * kDeg;
      }
      return s;
    }();
    draft.frames.push_back(d);
  }
  for (int side = 0; side < 2; ++side)
    draft.feet[static_cast<size_t>(side)] = {{-1, count, Hold::RollingFoot, true, {side_sign(side) * kHalfStance, 0.0f}, side_sign(side) * 0.12f, 0.0f}};
  GeneratedClip out;
  out.clip = realize(draft, &out.report);
  out.role = Role::Idle;
  out.cyclic = true;
  out.loop_first = 0;
  out.loop_last = count - 1;
  return out;
}

GeneratedClip make_side_step(const std::string& name, bool left) {
  // Side-stepping (facing +Z, moving along +X for step_left): the leading foot steps out 0.30 m, the
  // weight moves across in double support, the trailing foot closes in. 1.1 s per cycle, ~0.27 m/s.
  constexpr float kCycle = 1.1f, kStep = 0.30f, kNarrow = 0.10f;
  const float dir = left ? 1.0f : -1.0f;
  const int lead = left ? 0 : 1, trail = 1 - lead;
  // Phases (of the cycle): lead foot off 0.05 .. on 0.30; trail foot off 0.55 .. on 0.80.
  constexpr float kLeadOff = 0.05f, kLeadOn = 0.30f, kTrailOff = 0.55f, kTrailOn = 0.80f;
  // Root lateral position over a cycle (relative to the cycle's start), held over the supporting foot
  // in single support and moved across in double support.
  const float lead0 = dir * kNarrow, trail0 = -dir * kNarrow;
  const std::vector<float> root_keys_t = {0.0f, kLeadOff, kLeadOn, kTrailOff, kTrailOn, 1.0f};
  const float w = 0.05f;  // how far inside the supporting foot the pelvis stays
  const std::vector<float> root_keys_x = {0.0f, trail0 + dir * w, trail0 + dir * w, lead0 + dir * kStep - dir * w,
                                          lead0 + dir * kStep - dir * w, dir * kStep};
  const auto root_x = [&](float phase) {
    const float k = std::floor(phase);
    const float p = phase - k;
    size_t i = 0;
    while (i + 2 < root_keys_t.size() && root_keys_t[i + 1] <= p) ++i;
    const float s = smooth5((p - root_keys_t[i]) / (root_keys_t[i + 1] - root_keys_t[i]));
    return dir * kStep * k + root_keys_x[i] + (root_keys_x[i + 1] - root_keys_x[i]) * s;
  };
  const int per_cycle = static_cast<int>(std::lround(kCycle * kLibraryFps));
  constexpr int kCycles = 2;
  const int pad = per_cycle, count = kCycles * per_cycle;
  Draft draft;
  draft.name = name;
  draft.fps = kLibraryFps;
  for (int f = -pad; f < count + pad; ++f) {
    const float phase = static_cast<float>(f) / static_cast<float>(per_cycle);
    DofPose d = standing_pose({root_x(phase), 0.0f}, anthropometry::kRootHeight - 0.07f);
    const float p = phase - std::floor(phase);
    // Lift of each foot's swing drives a little hip and knee flexion (the IK holds the rest).
    const auto swing = [](float p, float off, float on) {
      return p > off && p < on ? std::sin(kPi * (p - off) / (on - off)) : 0.0f;
    };
    const float lead_swing = swing(p, kLeadOff, kLeadOn), trail_swing = swing(p, kTrailOff, kTrailOn);
    d.at(lead, kHipFlex) += 15 * kDeg * lead_swing;
    d.at(lead, kKneeFlex) += 25 * kDeg * lead_swing;
    d.at(trail, kHipFlex) += 15 * kDeg * trail_swing;
    d.at(trail, kKneeFlex) += 25 * kDeg * trail_swing;
    d[kPelvisRoll] = dir * 2.5f * kDeg * (lead_swing - trail_swing);
    d[kSpineBend] = -d[kPelvisRoll];
    for (int side = 0; side < 2; ++side) {
      d.at(side, kHipFlex) += 8 * kDeg;
      d.at(side, kKneeFlex) += 12 * kDeg;
      d.at(side, kShoulderAbduct) += 6 * kDeg * (side == lead ? lead_swing : trail_swing);
    }
    draft.frames.push_back(d);
  }
  for (int c = -2; c <= kCycles + 1; ++c) {
    const float base = dir * kStep * static_cast<float>(c);
    auto frame = [&](float phase) { return pad + static_cast<int>(std::lround((static_cast<float>(c) + phase) * per_cycle)); };
    draft.feet[static_cast<size_t>(lead)].push_back(
        {frame(kLeadOn - 1.0f), frame(kLeadOff) - 1, Hold::RollingFoot, true, {base + lead0, 0.0f}, side_sign(lead) * 0.08f, 0.07f});
    draft.feet[static_cast<size_t>(trail)].push_back(
        {frame(kTrailOn - 1.0f), frame(kTrailOff) - 1, Hold::RollingFoot, true, {base + trail0, 0.0f}, side_sign(trail) * 0.08f, 0.07f});
  }
  GeneratedClip out;
  out.clip = crop(realize(draft, &out.report), pad, count);
  out.role = left ? Role::StepLeft : Role::StepRight;
  out.cyclic = true;
  out.loop_first = 0;
  out.loop_last = count - 1;
  return out;
}

}  // namespace prep::library
