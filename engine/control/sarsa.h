// Sec. 6.3-6.4, Eq. 18-19: tabular SARSA over the quantized states and actions.
//
// Q(s_t, a_t) <- Q(s_t, a_t) + lambda (r_{t+1} + gamma Q(s_{t+1}, a_{t+1}) - Q(s_t, a_t))        (Eq. 19)
// with the learning rate lambda = 0.7 and the discount gamma = 0.3 of Eq. 18 (SarsaParams). Reaching the
// goal ends an episode; the goal is absorbing with the value of reward.h's goal_value.
//
// Exploration (Sec. 6.4): episodes begin at exploring starts (Environment::exploring_start); each
// (state, action) pair has a "tried" flag and an untried allowed action is always taken first (uniformly
// among the untried); once all are tried, epsilon-greedy (epsilon = 0.1). Greedy ties go to the lowest
// action index.
//
// Bootstrapping. When the next action is exploratory (an untried action, or the epsilon draw), Eq. 19
// bootstraps on the greedy action's value instead: an untried action's Q is still 0 and a random one is not
// what the policy does there, and with lambda = 0.7 each such sample would drag the estimate far off.
//
// Termination. The paper stops "when the number of state-action values updated per episode drops below 2%
// of the states". Two things make that literal rule unusable: our episodes last a few to a few dozen
// steps, far fewer than 2% of 19,200 states (384), so it would stop at once; and with lambda = 0.7 every
// update moves a Q value by a visible amount forever (within-bin positions and exploration make the
// samples differ), so counting value changes never stops. What the paper wants is a policy that no longer
// improves. So we count policy updates per window: training runs in rounds of
// SarsaParams::convergence_episodes episodes; a state's policy is updated when another allowed action's
// Q exceeds its committed greedy action's Q by more than update_tolerance (the new one becomes committed);
// training has converged when, in one whole round, no untried action was taken anymore (exploring starts
// are done) and fewer than convergence_fraction x states policies were updated. It also stops after
// max_steps steps (checked at the end of a round). A round is 5,000 episodes (about 40,000 actions of a
// gait cycle): rounds of 1,000 such short episodes touch so few states that the count says little, and
// the per-round merge then costs as much as 90 instructions per step.
//
// The discount. The paper's gamma = 0.3 looks about one action ahead, and Eq. 17 pays 0.85 of its 1.0 for
// standing still facing the goal with a steady alpha: r_max / (1 - gamma) = 1.43 for the absorbing goal
// against 0.85 / (1 - gamma) = 1.21 for standing forever. Whatever lets the character stand cheaply then
// wins over paying Eq. 16 on the way in. Hence four choices elsewhere: the core motions all walk (no
// idle, params.h), actions do not choose alpha = 1 (which stands still, Eq. 3-4; the state still reaches
// it by the forcing, params.h forced_top_level), an action is a gait cycle (action_effects.h), and the
// source radius is 1 m (reward.h). With them the paper's constants train a policy that reaches the goal and prepares before it
// (README figures).
//
// Threads, deterministically. Each of SarsaParams::threads workers has its own replica of Q and of the
// tried flags and its own generator (seeded from the seed and the worker's index through splitmix64), and
// runs its share of the round's episodes (E / T each, the first E mod T workers one more). At the end of every round
// the replicas are merged in worker order: each Q value touched by n workers becomes the master value plus
// the mean of their changes; tried flags are OR-ed; every replica restarts from the merged table. So the
// same seed and thread count give the same Q bit for bit, whatever the scheduling.
#pragma once

#include <cstdint>
#include <functional>
#include <limits>
#include <vector>

#include "engine/control/environment.h"
#include "engine/params/params.h"

namespace prep {

struct TrainingPoint {
  std::int64_t steps = 0;
  std::int64_t episodes = 0;
  double average_return = 0;  // mean over all states of max over allowed actions of Q (Fig. 10)
};

struct TrainingProgress {
  std::int64_t steps = 0, max_steps = 0, episodes = 0;
  std::int64_t round_updates = 0;  // policies updated in the last round (see Termination above)
  std::int64_t update_limit = 0;   // the convergence threshold on round_updates
};

struct TrainingResult {
  std::vector<float> q;  // states x actions, row-major by state
  std::int64_t steps = 0;
  std::int64_t episodes = 0;
  std::int64_t rounds = 0;
  bool converged = false;
  double seconds = 0;      // wall-clock time
  double cpu_seconds = 0;  // CPU time of the whole process over the same span (all threads)
  std::vector<TrainingPoint> curve;
};

struct TrainingOptions {
  std::int64_t curve_every_steps = 200000;  // a training-curve point at the first round end past each multiple
  std::function<void(const TrainingProgress&)> progress;  // called at every round end (from the calling thread)
};

// Throws std::invalid_argument for non-positive threads, rounds or step limits.
TrainingResult train_sarsa(const Environment& env, const SarsaParams& params, const TrainingOptions& options = {});

// Fig. 10's "average return per state": mean over states of the best allowed action's Q.
double average_return_per_state(const Environment& env, const std::vector<float>& q);

// The greedy allowed action of a state (lowest index on ties). Inline: it runs at every training step.
inline int greedy_action(const Environment& env, const float* q_row, int last_motion) {
  const std::uint64_t allowed = env.actions().allowed_mask(last_motion);
  const int n = env.actions().size();
  // The maximum over the allowed actions first (a branch-free reduction the compiler vectorizes; the
  // others count as -infinity), then the first allowed action holding it.
  constexpr float kNone = -std::numeric_limits<float>::infinity();
  float best_q = kNone;
  for (int a = 0; a < n; ++a) {
    const float v = (allowed >> a & 1u) ? q_row[a] : kNone;
    best_q = v > best_q ? v : best_q;
  }
  int best = __builtin_ctzll(allowed);  // the lowest allowed action (the mask is never empty)
  while (!((allowed >> best & 1u) && q_row[best] == best_q)) ++best;
  return best;
}

}  // namespace prep
