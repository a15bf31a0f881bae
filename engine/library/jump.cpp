// jump: walk in, gather both feet, counter-movement crouch, two-footed jump over a 0.4 m hurdle with the
// knees tucked, landing on both feet, absorb, walk on. Flight is ballistic (g = 9.81 m/s^2).
#include "engine/library/action.h"
#include "engine/library/angles.h"
#include "engine/library/rig.h"

#include <array>
#include <cmath>

#include "engine/motion/kinematics.h"

namespace prep::library {
namespace {
void set_arms(DofPose& d, float flex, float elbow, float abduct = 10.0f) {
  for (int side = 0; side < 2; ++side) {
    d.at(side, kShoulderFlex) = flex * kDeg;
    d.at(side, kElbowFlex) = elbow * kDeg;
    d.at(side, kShoulderAbduct) = abduct * kDeg;
  }
}
void set_legs(DofPose& d, float hip, float knee, float ankle) {
  for (int side = 0; side < 2; ++side) {
    d.at(side, kHipFlex) = hip * kDeg;
    d.at(side, kKneeFlex) = knee * kDeg;
    d.at(side, kAnkleDorsi) = ankle * kDeg;
  }
}
}  // namespace

GeneratedClip make_jump(const std::string& name, Obstacle* hurdle) {
  ActionSpec spec;
  spec.name = name;
  spec.role = Role::Jump;
  spec.gait = plan_gait(1.4f, 1.0f, 60.0f);
  const float T = spec.gait.cycle_s;
  const float step = 0.5f * spec.gait.stride_m;
  const Walker in = walk_in(spec);
  const float feet_z = in.supports(1, 0.0f, 0.0f, 0.0f).back().anchor_xz.y;  // right heel strike at the join
  const float takeoff = 1.0f, landing = 1.45f, resume = 2.45f;
  const float land_z = feet_z + 1.05f;
  spec.walk_in_s = T;
  spec.resume_time = resume;
  spec.resume_phase = 0.0f;
  // The first step out of the landing is a little shorter than a walking step.
  spec.resume_origin = {0.0f, land_z + step - 0.06f - in.supports(1, 0.0f, 0.0f, 0.0f).back().anchor_xz.y};
  spec.walk_out_s = T;
  spec.target_time = 0.5f;  // the counter-movement crouch begins once both feet are down

  auto key = [&](float t, float z, float y, auto&& edit) {
    DofPose d = standing_pose({0.0f, z}, y);
    edit(d);
    spec.keys.push_back({t, d, false, {}});
  };
  // Gather: the left foot comes alongside, the body slows over the feet.
  key(0.5f, feet_z + 0.02f, 0.86f, [](DofPose& d) {
    set_legs(d, 25, 35, 5);
    set_arms(d, -10, 25);
    d[kSpineFlex] = 8 * kDeg;
  });
  // Counter-movement: hips back and down, trunk forward, arms swung back.
  key(0.8f, feet_z - 0.04f, 0.66f, [](DofPose& d) {
    set_legs(d, 80, 105, 25);
    set_arms(d, -45, 20, 12);
    d[kSpineFlex] = 28 * kDeg;
    d[kNeckFlex] = -18 * kDeg;
  });
  // Take-off: legs extended, body leaning forward, arms driven forward and up.
  key(takeoff, feet_z + 0.12f, 0.98f, [](DofPose& d) {
    set_legs(d, 10, 8, -25);
    set_arms(d, 95, 30, 15);
    d[kSpineFlex] = 12 * kDeg;
    d[kNeckFlex] = -8 * kDeg;
  });
  // Tuck over the hurdle.
  key(1.2f, feet_z + 0.55f, 1.2f, [](DofPose& d) {
    set_legs(d, 85, 115, 5);
    set_arms(d, 60, 45, 15);
    d[kSpineFlex] = 20 * kDeg;
    d[kNeckFlex] = -10 * kDeg;
  });
  // Landing: feet reach forward for the floor.
  key(landing, land_z - 0.02f, 0.90f, [](DofPose& d) {
    set_legs(d, 35, 35, 0);
    set_arms(d, 45, 35, 15);
    d[kSpineFlex] = 15 * kDeg;
  });
  // Absorb.
  key(1.7f, land_z - 0.08f, 0.77f, [](DofPose& d) {
    set_legs(d, 70, 90, 22);
    set_arms(d, 30, 30, 12);
    d[kSpineFlex] = 25 * kDeg;
    d[kNeckFlex] = -15 * kDeg;
  });
  // Rise and lean into the first step.
  key(2.05f, land_z + 0.05f, 0.88f, [](DofPose& d) {
    set_legs(d, 10, 12, 0);
    set_arms(d, 5, 20);
    d[kSpineFlex] = 4 * kDeg;
  });
  spec.flight_from = takeoff;
  spec.flight_to = landing;

  // Supports. Right: from the join until take-off, from landing until it steps off into the walk.
  spec.feet[1] = {{0.0f, takeoff, Hold::RollingFoot, false, {}, 0.0f, 0.0f},
                  {landing, 2.05f, Hold::RollingFoot, true, {-0.10f, land_z}, -0.05f, 0.0f}};
  // Left: beside the right for the take-off, then landing and holding until the walk's toe-off.
  spec.feet[0] = {{0.50f, takeoff, Hold::RollingFoot, true, {0.12f, feet_z}, 0.08f, 0.06f},
                  {landing, resume + (kStanceFraction - 0.5f) * T, Hold::RollingFoot, true, {0.10f, land_z}, 0.05f, 0.0f}};
  GeneratedClip g = compose_action(spec);
  if (hurdle) {
    // The hurdle (10 cm deep) goes where the feet pass highest: for each candidate position between the
    // take-off toes and the landing heels, the lowest foot point that passes over it; the best one wins.
    const float toes = feet_z + anthropometry::kAnkleToBall + anthropometry::kBallToToeTip;
    const float heels = land_z - 0.25f * anthropometry::kFootLength;
    std::vector<std::array<glm::vec3, 6>> feet_points;
    std::vector<glm::vec3> pos;
    std::vector<glm::quat> rot;
    for (const Pose& p : g.clip.frames) {
      forward_kinematics(*g.clip.skeleton, p, pos, &rot);
      std::array<glm::vec3, 6> pts;
      for (int side = 0; side < 2; ++side) {
        const size_t a = static_cast<size_t>(foot(side));
        pts[static_cast<size_t>(3 * side)] = pos[a];
        pts[static_cast<size_t>(3 * side + 1)] = end_site_position(*g.clip.skeleton, toe(side), pos, rot);
        pts[static_cast<size_t>(3 * side + 2)] = pos[a] + rot[a] * glm::vec3(0, -anthropometry::kAnkleHeight, -0.25f * anthropometry::kFootLength);
      }
      feet_points.push_back(pts);
    }
    float best_z = 0.5f * (toes + heels), best_low = -1.0f;
    for (float z = toes + 0.05f; z <= heels - 0.05f; z += 0.01f) {
      float low = 1e9f;
      for (const auto& pts : feet_points)
        for (const glm::vec3& p : pts)
          if (std::fabs(p.z - z) <= 0.05f) low = std::min(low, p.y);
      if (low > best_low) {
        best_low = low;
        best_z = z;
      }
    }
    *hurdle = {best_z - 0.05f, best_z + 0.05f, 0.40f, 0.45f, true};
  }
  return g;
}

}  // namespace prep::library
