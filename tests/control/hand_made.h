// Hand-made core motions for the controller's tests: a one-joint skeleton whose root walks, turns or
// stands at known speeds, so that every number an action table holds can be computed by hand.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <glm/gtc/quaternion.hpp>

#include "engine/control/action_effects.h"
#include "engine/control/actions.h"
#include "engine/control/environment.h"
#include "engine/control/policy.h"
#include "engine/control/state.h"
#include "engine/motion/motion_set.h"
#include "engine/params/params.h"

namespace prep::test {

// A root moving at `speed` m/s along its facing while turning at `turn_rate` rad/s, `frames` frames at
// `fps`, looping over all of them.
inline MotionClip hand_made_clip(const std::string& name, Role role, float speed, float turn_rate, float fps = 30.0f,
                                 int frames = 31, float heading0 = 0.3f) {
  auto skeleton = std::make_shared<Skeleton>();
  skeleton->joints.push_back(Joint{"hips", -1, glm::vec3(0.0f), false, glm::vec3(0.0f)});
  MotionClip m;
  m.clip.name = name;
  m.clip.skeleton = skeleton;
  m.clip.fps = fps;
  m.role = role;
  m.cyclic = true;
  m.loop_first = 0;
  m.loop_last = frames - 1;
  glm::vec3 p(2.0f, 0.9f, -1.0f);
  float h = heading0;
  for (int k = 0; k < frames; ++k) {
    Pose pose(1);
    pose.root_position = p;
    pose.rotations[0] = glm::angleAxis(h, glm::vec3(0.0f, 1.0f, 0.0f));
    m.clip.frames.push_back(pose);
    // Advance with the heading of the frame's midpoint so the path is an exact circular arc per frame.
    const float dt = 1.0f / fps, mid = h + 0.5f * turn_rate * dt;
    p += speed * dt * glm::vec3(std::sin(mid), 0.0f, std::cos(mid));
    h += turn_rate * dt;
  }
  return m;
}

struct HandMadeWorld {
  std::vector<MotionClip> clips;
  ActionTable table;
};

// walk 1.5 m/s, turn_left 1.2 m/s at +1 rad/s, turn_right mirrored, walk_slow 0.6 m/s: the order of a
// set's own core motions (default_core_clips). The clips carry no contacts, so a loop counts as one gait cycle (two footsteps) and,
// with the default footsteps_per_action of 2, one action plays the whole 1 s loop.
inline HandMadeWorld hand_made_world(const Params& params, const RootCurve& curve = RootCurve{0.5f, 1.0f, false}) {
  HandMadeWorld w;
  w.clips.push_back(hand_made_clip("walk", Role::Walk, 1.5f, 0.0f));
  w.clips.push_back(hand_made_clip("turn_left", Role::TurnLeft, 1.2f, 1.0f));
  w.clips.push_back(hand_made_clip("turn_right", Role::TurnRight, 1.2f, -1.0f));
  w.clips.push_back(hand_made_clip("walk_slow", Role::Walk, 0.6f, 0.0f));
  std::vector<const MotionClip*> core;
  for (const auto& c : w.clips) core.push_back(&c);
  w.table = tabulate_action_effects(core, curve, params.quantization.alpha_levels, params.quantization.alpha_step,
                                    params.quantization.footsteps_per_action, "hand-made");
  return w;
}

// A small configuration that trains in about a second: coarse distance and bearing bins, the paper's
// alpha levels, rewards and SARSA constants (discount 0.3). (Alpha levels 0.5 apart would pin the
// character inside the source radius: moving on there would cost 2 x 0.6 x 0.5^2, reward.h.)
inline Params small_params() {
  Params p;
  QuantizationParams& q = p.quantization;
  q.d_step = 0.8f;
  q.d_g_bins = 3;
  q.d_i_bins = 2;
  q.theta_g_step_deg = 45.0f;
  q.theta_g_bins = 8;
  q.theta_i_step_deg = 180.0f;
  q.theta_i_bins = 2;
  p.reward.goal_radius = 0.6f;
  p.sarsa.convergence_episodes = 1000;
  p.sarsa.max_steps = 20000000;
  return p;
}

// A policy over the hand-made world with the given Q table (all actions allowed after every motion).
inline std::shared_ptr<const Policy> hand_made_policy(const Params& params, const HandMadeWorld& world, std::vector<float> q) {
  const StateSpace states(params.quantization, world.table.motions);
  TrainingResult r;
  r.q = std::move(q);
  return std::make_shared<const Policy>(
      make_policy(params, world.table, ActionSpace(states.motions(), states.alpha_levels(), action_levels(params.quantization)), r, "kick"));
}

inline Environment make_environment(const Params& params, const ActionTable& table) {
  const StateSpace states(params.quantization, table.motions);
  return Environment(states, ActionSpace(states.motions(), states.alpha_levels(), action_levels(params.quantization)), table, params.reward);
}

}  // namespace prep::test
