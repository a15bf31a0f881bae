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
// the mean of their changes; tried flags are OR-ed; every replica restarts from the merged table (each
// worker copies the merged rows into its own replica at the start of its next round, in parallel). So the
// same seed and thread count give the same Q bit for bit, whatever the scheduling.
//
// Speed. A training step costs about 495 instructions (callgrind, exploring starts and merge
// included; 780 before these changes) and 2.5 mispredicted branches (14 before):
// the Q rows are padded to blocks of four actions with -infinity where an action is not allowed, so the
// greedy choice is a four-wide maximum (sarsa.cpp); the goal's and the source's bearings and distances
// are one four-wide pass (environment.h), as are the four bins of the state (state.h). Each of these
// computes the same float operations as the plain code, so the trained table is the same bit for bit.
#pragma once

#include <cstdint>
#include <functional>
#include <limits>
#include <vector>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

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

// The greedy allowed action of a Q row of n actions (lowest index on ties; a row whose allowed values are all
// NaN gives the lowest allowed action). Inline: it runs once or twice at every training step, where it was
// half of the step's instructions as a scalar loop. With SSE2 (every x86-64) it takes four actions at a
// time: the maximum over the allowed actions (the others count as -infinity), then a bit per action
// holding that maximum, and the lowest allowed one of those. Exactly the scalar loop's choice: maxps(v, m)
// is v > m ? v : m lane by lane (a NaN in v keeps m, as the scalar comparison does), a maximum does not
// depend on the order it is taken in, and +0 == -0 in the second pass as in the scalar one.
inline int greedy_action(const float* q_row, std::uint64_t allowed, int n) {
  constexpr float kNone = -std::numeric_limits<float>::infinity();
  float best_q = kNone;
  std::uint64_t holding = 0;  // bit a: q_row[a] == best_q
  int a = 0;
#if defined(__SSE2__)
  // kLanes[k]: lane j all ones where bit j of k is set (four actions' allowed bits).
  alignas(16) static constexpr std::uint32_t kLanes[16][4] = {
      {0, 0, 0, 0}, {~0u, 0, 0, 0}, {0, ~0u, 0, 0}, {~0u, ~0u, 0, 0}, {0, 0, ~0u, 0}, {~0u, 0, ~0u, 0},
      {0, ~0u, ~0u, 0}, {~0u, ~0u, ~0u, 0}, {0, 0, 0, ~0u}, {~0u, 0, 0, ~0u}, {0, ~0u, 0, ~0u},
      {~0u, ~0u, 0, ~0u}, {0, 0, ~0u, ~0u}, {~0u, 0, ~0u, ~0u}, {0, ~0u, ~0u, ~0u}, {~0u, ~0u, ~0u, ~0u}};
  const __m128 none = _mm_set1_ps(kNone);
  __m128 best4 = none;
  for (; a + 4 <= n; a += 4) {
    const __m128 lanes = _mm_load_ps(reinterpret_cast<const float*>(kLanes[(allowed >> a) & 15u]));
    const __m128 v = _mm_or_ps(_mm_and_ps(lanes, _mm_loadu_ps(q_row + a)), _mm_andnot_ps(lanes, none));
    best4 = _mm_max_ps(v, best4);
  }
  best4 = _mm_max_ps(best4, _mm_shuffle_ps(best4, best4, _MM_SHUFFLE(1, 0, 3, 2)));
  best4 = _mm_max_ps(best4, _mm_shuffle_ps(best4, best4, _MM_SHUFFLE(2, 3, 0, 1)));
  best_q = _mm_cvtss_f32(best4);
  const int blocks_end = a;
#endif
  for (int t = a; t < n; ++t) {
    const float v = (allowed >> t & 1u) ? q_row[t] : kNone;
    best_q = v > best_q ? v : best_q;
  }
#if defined(__SSE2__)
  const __m128 best = _mm_set1_ps(best_q);
  for (a = 0; a < blocks_end; a += 4)
    holding |= static_cast<std::uint64_t>(_mm_movemask_ps(_mm_cmpeq_ps(_mm_loadu_ps(q_row + a), best))) << a;
#endif
  for (; a < n; ++a) holding |= static_cast<std::uint64_t>(q_row[a] == best_q) << a;
  const std::uint64_t found = holding & allowed;
  return __builtin_ctzll(found != 0 ? found : allowed);  // the mask is never empty
}

inline int greedy_action(const Environment& env, const float* q_row, int last_motion) {
  return greedy_action(q_row, env.actions().allowed_mask(last_motion), env.actions().size());
}

}  // namespace prep
