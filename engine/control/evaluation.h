// Measuring a trained policy (prep evaluate-policy): greedy episodes from random starts where the source
// of influence is the goal (the paper's usual case: approach a ball and prepare to kick it).
//
// Each episode: the goal at a uniformly random distance in [R, 2R], R = d_g_bins x d_step (the far edge of
// the quantized range, so every approach crosses all distance bins), at a uniformly random bearing; the
// character standing (its "idle" core motion if it has one, else the first) at alpha 0. The greedy
// action is played until the goal is reached or max_episode_steps pass.
//
// - goal_reached_ratio: episodes that reached the goal.
// - median_steps_to_goal: over the episodes that reached it.
// - median_alpha_at_source: the alpha of the action with which the character arrives at the source (the
//   goal, within RewardParams::goal_radius: where the target motion is launched), over the episodes that
//   arrive. The played level, not the training's forcing to 1 (which happens earlier, on entering
//   source_radius). At alpha = 1 the root weight is 1 and Eq. 3-4 leave no stride, so with alpha levels
//   0.2 apart the highest level a character can arrive with is 0.8.
// - alpha_at_1m_ratio: episodes whose alpha, when the character first comes within 1 m of the source, is
//   at least 0.5 (the alpha of the action that brought it within 1 m).
#pragma once

#include <cstdint>
#include <vector>

#include "engine/control/environment.h"

namespace prep {

struct PolicyEvaluation {
  int episodes = 0;
  double goal_reached_ratio = 0;
  double median_steps_to_goal = 0;
  double median_alpha_at_source = 0;
  double alpha_at_1m_ratio = 0;
  double mean_return = 0;  // Eq. 18 from the start, over all episodes
};

PolicyEvaluation evaluate_policy(const Environment& env, const std::vector<float>& q, int episodes, std::uint64_t seed,
                                 int max_episode_steps, float discount);

// The alpha-level trajectory of one greedy episode from a given situation (for tests and the demo).
struct EpisodeTrace {
  std::vector<int> actions;
  std::vector<float> d_i;        // distance to the source after each action
  std::vector<float> alpha;      // alpha of each action (before any forcing)
  bool reached_goal = false;
};
EpisodeTrace greedy_episode(const Environment& env, const std::vector<float>& q, Situation start, int max_steps);

}  // namespace prep
