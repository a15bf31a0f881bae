// Sec. 6.2, Eq. 13-17: the reward of an action, and what happens at the source of influence and the goal.
//
// r = w_theta f_theta + w_d f_d + w_alpha f_alpha                              (Eq. 17)
// f_theta = 1 - |theta_g'| / theta_norm                                        (Eq. 14)
// f_d     = (d_norm + d_g - d_g') / (2 d_norm)                                 (Eq. 15)
// f_alpha = 1 - |alpha' - alpha|^C_alpha                                       (Eq. 16)
// where ' marks the state after the action, and alpha' = the action's alpha (Eq. 13).
//
// Our reading of "when a character reaches the source of influence, alpha is forced to be 1.0" (the
// choices are explained in the README and tested):
// - "Reaches" = the action ends within RewardParams::source_radius of the source; the next state's alpha
//   is then 1 (the override of Eq. 13), after every such action. With the paper's discount of 0.3 the
//   learner sees about one action (one gait cycle, action_effects.h) ahead, so a forcing only where the
//   target motion starts would teach a last-moment jump of alpha. The radius is 1 m, chosen by training
//   the paper's configuration and measuring (prep evaluate-policy over 1,000 approaches, README): at
//   0.8 m the character comes within 1 m of the source below alpha 0.5 in 21-27% of the approaches (it
//   raises alpha only on the cycle before the forcing; seeds 1-3); at 1.2 m it is prepared at 1 m in
//   96-100% but approaches take a quarter longer (median 9.3-11 s against 7.5), and in the obstacle course
//   its policy stops for good 0.7 m short of the beam's launch point and misses the hurdle; at 1 m every
//   seed tried reached the goal in every approach, prepared at 1 m in 95-99%. At run time the controller's
//   state is forced the same way (controller.h); where the character actually stops, with its played
//   alpha forced to 1, is arrival.h's.
// - Inside the radius moving on costs Eq. 16 twice per action (below), 2 x 0.6 x 0.2^2 = 0.048 at the top
//   moving level 0.8, against Eq. 15's 0.15 per metre of approach: an action at 0.8 must travel at least
//   0.32 m or the character stays where it is. The built-in walk's cycle at 0.8 travels 0.39 m; a slower
//   core walk, or a lower-body curve that shortens the stride more (BlendParams::C_lower), needs a smaller
//   source radius.
// - In that step the played alpha changes twice: from the state's alpha to the action's (Eq. 13) and then
//   from the action's alpha to 1 at the source. Eq. 16's penalty is applied to each change:
//   f_alpha = 1 - |a.alpha - alpha|^C - |1 - a.alpha|^C. Penalising only the state-to-state change
//   |1 - alpha|^C (the literal reading) leaves the arriving action's own alpha free, and the learned policy
//   then "dashes" the last footstep at alpha = 0 (the longest stride) after preparing the one before; with
//   C >= 1 and an action alpha between the state's and 1 our sum never exceeds the literal penalty, so a
//   character that keeps raising alpha into the source is not punished more than the paper would.
// - The goal ends the episode, and the character then stays there, ready. With the paper's rewards (all
//   positive) and Q(terminal) = 0, ending an episode forfeits gamma * Q of the future, so the learner avoids
//   the goal it should reach. We make the goal absorbing: the value after reaching it is
//   r_max / (1 - gamma) with r_max = w_theta + w_d + w_alpha, the largest reward Eq. 17 gives for a step of
//   at most d_norm, so reaching the goal is never worse than wandering (Eq. 18 continued past arrival).
#pragma once

#include <vector>

#include "engine/params/params.h"

namespace prep {

float reward_facing(float theta_g_next, const RewardParams& p);                  // Eq. 14
float reward_approach(float d_g, float d_g_next, const RewardParams& p);        // Eq. 15
float reward_steadiness(float alpha, float alpha_next, const RewardParams& p);   // Eq. 16
// Eq. 16 at the source of influence: the played alpha goes alpha -> action_alpha -> 1 (see above).
float reward_steadiness_at_source(float alpha, float action_alpha, const RewardParams& p);

struct RewardTerms {
  float facing = 0, approach = 0, steadiness = 0, total = 0;
};
// Eq. 17 for one transition. at_source: the action ended within the source radius (alpha forced to 1).
RewardTerms reward_terms(float theta_g_next, float d_g, float d_g_next, float alpha, float action_alpha,
                         bool at_source, const RewardParams& p);

// The value of the absorbing goal state, r_max / (1 - gamma), see above.
float goal_value(const RewardParams& reward, float discount);

// The reward with Eq. 16's part precomputed per pair of alpha levels (the power is the slow part), for the
// training loop. Levels are alpha = l * alpha_step.
class RewardModel {
 public:
  RewardModel(const RewardParams& p, int alpha_levels, float alpha_step);

  float operator()(float theta_g_next_abs, float d_g, float d_g_next, int alpha_level, int action_level,
                   bool at_source) const {
    // One table, the source's half second: an index, not a branch (at_source is hard to predict).
    const float steady = steadiness_[static_cast<size_t>(((at_source ? levels_ : 0) + alpha_level) * levels_ + action_level)];
    return facing_bias_ - facing_slope_ * theta_g_next_abs +  // w_theta * Eq. 14
           approach_bias_ + approach_slope_ * (d_g - d_g_next) +  // w_d * Eq. 15
           steady;                                               // w_alpha * Eq. 16
  }
  float max_reward() const { return max_reward_; }  // w_theta + w_d + w_alpha (see goal_value)
  float goal_radius() const { return goal_radius_; }
  float source_radius() const { return source_radius_; }

 private:
  int levels_;
  float facing_bias_, facing_slope_, approach_bias_, approach_slope_;
  float goal_radius_, source_radius_, max_reward_;
  // w_alpha * f_alpha(from level, to level) at [from * levels + to], then the same with the jump to 1 at the
  // source at [(levels + from) * levels + to].
  std::vector<float> steadiness_;
};

}  // namespace prep
