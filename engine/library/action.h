// Target motions from keyed poses, joined to the walk on both sides (Fig. 4): the clip walks in (part i),
// reaches the join at a right heel strike (t = 0), plays the keyed action (part ii) and hands over to the
// walk again at a chosen gait phase (part iii). Keys and supports are given in times from the join and in
// the walk-in path's coordinates (the path runs along +Z through the origin at t = 0).
#pragma once

#include <array>
#include <string>
#include <vector>

#include "engine/library/gait.h"
#include "engine/library/generated.h"

namespace prep::library {

struct SupportSpec {
  float on = 0, off = 0;          // s from the join
  Hold hold = Hold::RollingFoot;
  bool explicit_anchor = false;
  glm::vec2 anchor_xz{0.0f};
  float anchor_yaw = 0.0f;
  float lift_before = 0.06f;
};

struct ActionSpec {
  std::string name;
  Role role = Role::Walk;
  GaitStyle gait;
  float walk_in_s = 1.0f;             // walking before the join
  std::vector<PoseKey> keys;          // action keys at t > 0 (the join pose is added as the first key)
  float resume_time = 2.0f;           // s from the join: the walk takes over here ...
  float resume_phase = 0.0f;          // ... at this gait phase ...
  glm::vec2 resume_origin{0.0f};      // ... with its path through this point
  float walk_out_s = 1.0f;
  std::array<std::vector<SupportSpec>, 2> feet, hands;
  float target_time = 0.0f;           // T_t, s from the join
  // Optional ballistic flight: between these times the root follows a parabola under gravity that
  // joins its keyed positions at both ends (keys must exist at both times).
  float flight_from = -1.0f, flight_to = -1.0f;
};

GeneratedClip compose_action(const ActionSpec& spec);

// Walkers of a spec: the walk-in (phase 0 at the join) and the walk-out (phase resume_phase at resume_time).
Walker walk_in(const ActionSpec& spec);
Walker walk_out(const ActionSpec& spec);

// A relaxed standing pose (the base that action keys modify): root at `xz`, upright, arms hanging.
DofPose standing_pose(glm::vec2 xz, float root_height);

}  // namespace prep::library
