// Measuring a trained policy (prep evaluate-policy): greedy approaches from random starts where the source
// of influence is the goal (the paper's usual case: approach a ball and prepare to kick it), replayed the
// way the world runs the controller, tick by tick, so that what is measured is what a scenario would show.
//
// Each episode: the goal at a uniformly random distance in [R, 2R], R = d_g_bins x d_step (the far edge of
// the quantized range, so every approach crosses all distance bins), at a uniformly random bearing; the
// character at alpha 0 in its first core motion (walking). Then, every RuntimeParams::fixed_dt:
// - at the end of each action (its duration from the table) the Controller takes the greedy action, with
//   the state's alpha forced to 1 within the source radius, exactly as in a scenario (controller.h);
// - the played alpha passes the Gaussian filter; the character moves at its core motion's speed scaled by
//   (1 - w_r) of the filtered alpha (Eq. 3-4) and turns at the motion's rate (the action table's effect
//   spread evenly over the action's duration);
// - arrival and launch follow arrival.h, with the goal radius as the tolerance of "at the launch point"
//   (the source is a point here; in a scenario the launch point sits on the line from the character to the
//   object, so it is reached exactly).
// An episode ends with the launch or after max_episode_steps decisions.
//
// - goal_reached_ratio: episodes that launched at the goal.
// - median_steps_to_goal: decisions (actions) until then, over the episodes that launched.
// - median_alpha_at_source: the filtered alpha synthesis uses on the tick of the launch (what a scenario
//   reports as alpha_at_launch). Not the forced 1: it is as high as the approach let it become.
// - median_level_at_arrival: the alpha level the policy itself had chosen when the arrival began.
// - alpha_at_1m_ratio: episodes whose alpha is at least 0.5 on the first tick within 1 m of the source:
//   the state's alpha (Eq. 11 and 13: the level the policy plays).
// - played_alpha_at_1m_ratio: the same with the filtered alpha synthesis uses there, which lags the level
//   by the Gaussian filter (a level raised just before 1 m shows less); median_alpha_at_1m is its median.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "engine/control/environment.h"
#include "engine/control/policy.h"

namespace prep {

struct PolicyEvaluation {
  int episodes = 0;
  double goal_reached_ratio = 0;
  double median_steps_to_goal = 0;
  double median_alpha_at_source = 0;
  double median_level_at_arrival = 0;
  double alpha_at_1m_ratio = 0;
  double played_alpha_at_1m_ratio = 0;
  double median_alpha_at_1m = 0;
  double median_seconds_to_goal = 0;
};

// Throws std::invalid_argument for impossible runtime settings (arrival.h).
PolicyEvaluation evaluate_policy(std::shared_ptr<const Policy> policy, const Params& params, int episodes, std::uint64_t seed);

// The alpha-level trajectory of one greedy episode of the training environment (whole actions, no
// filter) from a given situation, for tests.
struct EpisodeTrace {
  std::vector<int> actions;
  std::vector<float> d_i;        // distance to the source after each action
  std::vector<float> alpha;      // alpha of each action (before any forcing)
  bool reached_goal = false;
};
EpisodeTrace greedy_episode(const Environment& env, const std::vector<float>& q, Situation start, int max_steps);

}  // namespace prep
