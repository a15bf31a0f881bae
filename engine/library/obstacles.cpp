// duck (walk through under a beam ~1.2 m high) and crawl (low, on the knees and forearms, under a bar ~0.58 m high).
#include <algorithm>
#include <cmath>

#include "engine/library/action.h"
#include "engine/library/angles.h"
#include "engine/library/builtin.h"
#include "engine/library/rig.h"
#include "engine/library/spline.h"
#include "engine/motion/kinematics.h"

namespace prep::library {
namespace {
// The body's extent along z (joints and end sites) at one frame.
void z_extent(const Clip& clip, int frame, float& z_min, float& z_max) {
  std::vector<glm::vec3> pos;
  std::vector<glm::quat> rot;
  forward_kinematics(*clip.skeleton, clip.frames[static_cast<size_t>(frame)], pos, &rot);
  z_min = 1e9f;
  z_max = -1e9f;
  for (int j = 0; j < clip.skeleton->size(); ++j) {
    std::vector<glm::vec3> points = {pos[static_cast<size_t>(j)]};
    if (clip.skeleton->joints[static_cast<size_t>(j)].has_end_site) points.push_back(end_site_position(*clip.skeleton, j, pos, rot));
    for (const glm::vec3& p : points) {
      z_min = std::min(z_min, p.z);
      z_max = std::max(z_max, p.z);
    }
  }
}

// An obstacle across the path midway between where the body's front is when it has got low and where its
// back is when it starts to rise again, so that the whole body passes under it while low.
Obstacle under_obstacle(const Clip& clip, int low_from, int low_to, float height, float clearance) {
  float front_min, front_max, back_min, back_max;
  z_extent(clip, low_from, front_min, front_max);
  z_extent(clip, low_to, back_min, back_max);
  const float centre = 0.5f * (front_max + back_min);
  const float half_depth = std::min(0.1f, 0.5f * (back_min - front_max));
  return {centre - half_depth, centre + half_depth, height, clearance, false};
}
}  // namespace

GeneratedClip make_duck(const std::string& name, Obstacle* beam) {
  // Walking on at a moderate pace; the walk lowers into a crouch with the trunk bent forward, passes the
  // beam, and rises again, without breaking step (the legs keep the gait and IK bends the knees).
  const GaitStyle style = plan_gait(1.1f, 0.85f, kLibraryFps);
  const Walker walker(style, 0.0f, {0.0f, 0.0f}, 0.0f);
  const float T = style.cycle_s;
  const float down_from = 0.3f * T, down_to = 1.2f * T, up_from = 2.7f * T, up_to = 3.6f * T;
  const float pad = T;  // a cycle of padding at both ends, cropped (supports over the clip's ends roll as in the walk)
  const float t0 = -T - pad, t1 = 4.6f * T + pad;
  const auto depth = [&](float t) { return smooth5((t - down_from) / (down_to - down_from)) - smooth5((t - up_from) / (up_to - up_from)); };
  Draft draft;
  draft.name = name;
  draft.fps = style.fps;
  const int count = static_cast<int>(std::lround((t1 - t0) * style.fps));
  for (int f = 0; f < count; ++f) {
    const float t = t0 + static_cast<float>(f) / style.fps;
    DofPose d = walker.pose(t);
    const float k = depth(t);
    d[kRootY] -= 0.12f * k;
    d[kSpineFlex] += 55 * kDeg * k;
    d[kPelvisTilt] += 32 * kDeg * k;
    d[kNeckFlex] -= 22 * kDeg * k;
    d[kHeadFlex] -= 8 * kDeg * k;
    for (int side = 0; side < 2; ++side) {
      d.at(side, kHipFlex) += 35 * kDeg * k;
      d.at(side, kKneeFlex) += 40 * kDeg * k;
      d.at(side, kAnkleDorsi) += 10 * kDeg * k;
      d.at(side, kShoulderFlex) += 15 * kDeg * k;
      d.at(side, kElbowFlex) += 20 * kDeg * k;
    }
    draft.frames.push_back(d);
  }
  for (int side = 0; side < 2; ++side) draft.feet[static_cast<size_t>(side)] = walker.supports(side, t0, t1, t0);
  GeneratedClip g;
  const int pad_frames = static_cast<int>(std::lround(pad * style.fps));
  g.clip = crop(realize(draft, &g.report), pad_frames, count - 2 * pad_frames);
  g.role = Role::Duck;
  const float clip_t0 = t0 + pad;
  g.target_frame = static_cast<int>(std::lround((down_from - clip_t0) * style.fps));
  if (beam)
    *beam = under_obstacle(g.clip, static_cast<int>(std::lround((down_to - clip_t0) * style.fps)),
                           static_cast<int>(std::lround((up_from - clip_t0) * style.fps)), 1.2f, 1.15f);
  return g;
}

GeneratedClip make_crawl(const std::string& name, Obstacle* bar) {
  ActionSpec spec;
  spec.name = name;
  spec.role = Role::Crawl;
  spec.gait = plan_gait(1.1f, 0.85f, kLibraryFps);
  const float T = spec.gait.cycle_s;
  const float step = 0.5f * spec.gait.stride_m;
  const Walker in = walk_in(spec);
  const float feet_z = in.supports(1, 0.0f, 0.0f, 0.0f).back().anchor_xz.y;
  // Timeline (s from the join): gather the feet, kneel and put the hands down, crawl, squat back onto
  // the feet, stand, walk on.
  const float kneel_from = 0.5f, feet_off = 1.1f, hands_down = 1.5f, knees_down = 1.5f;
  // Five cycles of 0.36 m carry the whole body (hands to toes about 1.3 m on all fours) past a bar 0.2 m
  // deep while it stays low (four leave 3 cm); 0.7 s a cycle is an adult's easy crawl (0.51 m/s), so the
  // crawl takes 3.5 s and the obstacle course stays finishable in 30 s.
  constexpr int kCycles = 5;
  constexpr float kCrawlCycle = 0.7f;   // s per crawl cycle (each limb steps once)
  constexpr float kCrawlStep = 0.36f;   // m per limb step
  const float crawl_from = 1.7f, crawl_to = crawl_from + kCycles * kCrawlCycle;
  const float feet_up = crawl_to + 0.1f, hands_up = crawl_to + 0.3f, feet_land = crawl_to + 0.6f, stand = crawl_to + 1.6f;
  const float resume = stand + 0.5f;
  spec.walk_in_s = T;
  spec.target_time = kneel_from;
  spec.resume_time = resume;
  spec.resume_phase = 0.0f;
  spec.walk_out_s = T;

  // The crawling posture: a low crawl, the trunk horizontal, the thighs leaning back from the knees, shins
  // on the floor, the elbows bent under the shoulders and the forearms and palms on the floor ahead of
  // them, the neck extended to look ahead.
  const float root_crawl_y = 0.43f;
  // The knee is behind the hip by the thigh's lean: the hip joint (behind the root, the pelvis tilted
  // forward) at its crawling height, the knee joint kKneeOnFloor above the floor. The keyed hip and knee
  // angles follow the lean, so that the keyed leg is the one IK puts between the hip and the planted foot.
  constexpr float kKneeOnFloor = 0.05f;
  constexpr float kPelvisCrawlTilt = 84 * kDeg;
  const float hip_y = root_crawl_y - anthropometry::kPelvisAboveHip * std::cos(kPelvisCrawlTilt);
  const float hip_behind_root = anthropometry::kPelvisAboveHip * std::sin(kPelvisCrawlTilt);
  const float thigh_lean = std::acos(std::min(1.0f, (hip_y - kKneeOnFloor) / anthropometry::kThigh));
  const float knee_behind_root = hip_behind_root + anthropometry::kThigh * std::sin(thigh_lean);
  auto crawl_pose = [&](float z) {
    DofPose d = standing_pose({0.0f, z}, root_crawl_y);
    d[kPelvisTilt] = kPelvisCrawlTilt;
    d[kSpineFlex] = 12 * kDeg;
    d[kNeckFlex] = 8 * kDeg;
    d[kHeadFlex] = -4 * kDeg;
    for (int side = 0; side < 2; ++side) {
      d.at(side, kHipFlex) = kPelvisCrawlTilt - thigh_lean;   // the thigh leaning back from the knee
      d.at(side, kKneeFlex) = 92 * kDeg - thigh_lean;        // the shin back along the floor
      d.at(side, kAnkleDorsi) = -25 * kDeg;
      d.at(side, kShoulderFlex) = 92 * kDeg;  // arms vertical at mid-support, sweeping +-15 degrees
      d.at(side, kShoulderAbduct) = 8 * kDeg;
      d.at(side, kShoulderTwist) = 0.0f;
      d.at(side, kElbowFlex) = 60 * kDeg;
      d.at(side, kWristFlex) = -10 * kDeg;
    }
    return d;
  };
  const float root_start = feet_z + 0.25f;  // root z when the crawl starts
  const float crawl_speed = kCrawlStep / kCrawlCycle;
  const float root_end = root_start + crawl_speed * (crawl_to - crawl_from);
  auto key = [&](float t, DofPose d) { spec.keys.push_back({t, d, false, {}}); };
  // Gather the feet and slow down.
  {
    DofPose d = standing_pose({0.0f, feet_z - 0.02f}, 0.88f);
    d[kSpineFlex] = 10 * kDeg;
    key(kneel_from, d);
  }
  {  // Bend down, reaching for the floor.
    DofPose d = standing_pose({0.0f, feet_z + 0.02f}, 0.60f);
    d[kPelvisTilt] = 45 * kDeg;
    d[kSpineFlex] = 20 * kDeg;
    d[kNeckFlex] = -25 * kDeg;
    for (int side = 0; side < 2; ++side) {
      d.at(side, kHipFlex) = 90 * kDeg;
      d.at(side, kKneeFlex) = 100 * kDeg;
      d.at(side, kAnkleDorsi) = 20 * kDeg;
      d.at(side, kShoulderFlex) = 70 * kDeg;
      d.at(side, kElbowFlex) = 20 * kDeg;
    }
    key(feet_off, d);
  }
  key(knees_down, crawl_pose(root_start - 0.05f));
  // Crawl: the trunk rolls and twists a little with the diagonal limb pairs.
  for (int c = 0; c <= 2 * kCycles; ++c) {
    const float t = crawl_from + 0.5f * kCrawlCycle * static_cast<float>(c);
    DofPose d = crawl_pose(root_start + crawl_speed * (t - crawl_from));
    const float s = (c % 2 == 0) ? 1.0f : -1.0f;
    d[kPelvisRoll] = 3 * kDeg * s;
    d[kSpineTwist] = -4 * kDeg * s;
    key(t, d);
  }
  {  // Push back onto the feet: a half squat, the trunk still bent forward.
    DofPose d = standing_pose({0.0f, root_end - 0.10f}, 0.80f);
    d[kPelvisTilt] = 40 * kDeg;
    d[kSpineFlex] = 25 * kDeg;
    d[kNeckFlex] = -30 * kDeg;
    for (int side = 0; side < 2; ++side) {
      d.at(side, kHipFlex) = 85 * kDeg;
      d.at(side, kKneeFlex) = 85 * kDeg;
      d.at(side, kAnkleDorsi) = 25 * kDeg;
      d.at(side, kShoulderFlex) = 75 * kDeg;
      d.at(side, kElbowFlex) = 15 * kDeg;
      d.at(side, kShoulderTwist) = 30 * kDeg;  // the forearms turning as the palms leave the floor
      d.at(side, kWristFlex) = -40 * kDeg;
    }
    key(feet_land + 0.1f, d);
  }
  {  // Stand.
    DofPose d = standing_pose({0.0f, root_end}, 0.90f);
    d[kSpineFlex] = 4 * kDeg;
    key(stand, d);
  }
  const float foot_end_z = root_end - 0.02f;
  spec.resume_origin = {0.0f, foot_end_z + step - (feet_z - 0.0f)};

  // Feet: walk-in stance, standing, then on the toes with the shins down, crawling, squatting, standing.
  const float shin = anthropometry::kShank;
  for (int side = 0; side < 2; ++side) {
    const float x = side_sign(side) * 0.11f;
    auto& feet = spec.feet[static_cast<size_t>(side)];
    if (side == 1) feet.push_back({0.0f, feet_off, Hold::RollingFoot, false, {}, 0.0f, 0.0f});
    else feet.push_back({0.45f, feet_off, Hold::RollingFoot, true, {x, feet_z}, 0.05f, 0.06f});
    // On all fours the ankle is a shin's length behind the knee, the knee behind the hip by the thigh's lean.
    const float knee_lead = side == 0 ? 0.0f : 0.5f;  // the left knee steps with the right hand
    float z = root_start - knee_behind_root - shin;
    float on = knees_down;
    for (int c = 0; c < kCycles; ++c) {
      const float swing_start = crawl_from + (static_cast<float>(c) + knee_lead) * kCrawlCycle;
      feet.push_back({on, swing_start, Hold::RigidFoot, false, {x, z}, 0.0f, c == 0 ? 0.16f : 0.04f});
      on = swing_start + 0.4f * kCrawlCycle;
      z += kCrawlStep;
    }
    feet.push_back({on, feet_up, Hold::RigidFoot, false, {x, z}, 0.0f, 0.04f});
    if (side == 1) feet.push_back({feet_land, resume - 0.35f, Hold::RollingFoot, true, {x, foot_end_z}, 0.0f, 0.12f});
    else feet.push_back({feet_land, resume + (kStanceFraction - 0.5f) * T, Hold::RollingFoot, true, {x, foot_end_z}, 0.0f, 0.12f});
    // Hands: under the shoulders.
    auto& hands = spec.hands[static_cast<size_t>(side)];
    const float hand_lead = side == 1 ? 0.0f : 0.5f;  // the right hand steps first
    float hz = root_start + 0.52f;
    float hon = hands_down;
    for (int c = 0; c < kCycles; ++c) {
      const float swing_start = crawl_from + (static_cast<float>(c) + hand_lead) * kCrawlCycle;
      hands.push_back({hon, swing_start, Hold::PalmDown, false, {side_sign(side) * 0.17f, hz}, 0.0f, 0.05f});
      hon = swing_start + 0.4f * kCrawlCycle;
      hz += kCrawlStep;
    }
    hands.push_back({hon, hands_up, Hold::PalmDown, false, {side_sign(side) * 0.17f, hz}, 0.0f, 0.05f});
  }
  GeneratedClip g = compose_action(spec);
  if (bar) {
    const float fps = spec.gait.fps;
    const auto frame = [&](float t) { return static_cast<int>(std::lround((t + spec.walk_in_s) * fps)); };
    *bar = under_obstacle(g.clip, frame(crawl_from), frame(crawl_to), 0.58f, 0.53f);
  }
  return g;
}

}  // namespace prep::library
