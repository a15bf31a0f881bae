#include "engine/control/evaluation.h"

#include <algorithm>
#include <cmath>

#include "engine/control/sarsa.h"

namespace prep {
namespace {

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

}  // namespace

EpisodeTrace greedy_episode(const Environment& env, const std::vector<float>& q, Situation s, int max_steps) {
  EpisodeTrace trace;
  const size_t actions = static_cast<size_t>(env.actions().size());
  for (int t = 0; t < max_steps; ++t) {
    const int state = env.quantize(s);
    const int a = greedy_action(env, q.data() + static_cast<size_t>(state) * actions, s.motion);
    const StepOutcome out = env.step(s, a);
    trace.actions.push_back(a);
    trace.d_i.push_back(s.d_i);
    trace.alpha.push_back(env.states().alpha_of(env.actions().decode(a).alpha_level));
    if (out.at_goal) {
      trace.reached_goal = true;
      break;
    }
  }
  return trace;
}

PolicyEvaluation evaluate_policy(const Environment& env, const std::vector<float>& q, int episodes, std::uint64_t seed,
                                 int max_episode_steps, float discount) {
  constexpr float kPi = 3.14159265358979323846f;
  const float one_metre = 1.0f;  // the distance of alpha_at_1m_ratio, by its definition
  const float range = static_cast<float>(env.states().d_g_bins()) * env.states().d_step();
  int start_motion = 0;
  for (int m = 0; m < env.table().motions; ++m)
    if (env.table().motion_roles[static_cast<size_t>(m)] == "idle") start_motion = m;
  Rng rng(seed);
  PolicyEvaluation e;
  e.episodes = episodes;
  std::vector<double> steps_to_goal, alpha_at_source;
  int reached = 0, prepared_at_1m = 0;
  double return_sum = 0.0;
  const size_t actions = static_cast<size_t>(env.actions().size());
  for (int ep = 0; ep < episodes; ++ep) {
    const float d = rng.uniform(range, 2.0f * range), bearing = rng.uniform(-kPi, kPi);
    Situation s;
    s.goal_left = s.source_left = d * std::sin(bearing);
    s.goal_forward = s.source_forward = d * std::cos(bearing);
    s.alpha_level = 0;
    s.motion = start_motion;
    s.update_polar();
    bool seen_1m = false;
    double ret = 0.0, weight = 1.0;
    for (int t = 0; t < max_episode_steps; ++t) {
      const int state = env.quantize(s);
      const int a = greedy_action(env, q.data() + static_cast<size_t>(state) * actions, s.motion);
      const float alpha = env.states().alpha_of(env.actions().decode(a).alpha_level);
      const StepOutcome out = env.step(s, a);
      ret += weight * out.reward;  // Eq. 18
      weight *= discount;
      if (!seen_1m && s.d_i <= one_metre) {
        seen_1m = true;
        if (alpha >= 0.5f) ++prepared_at_1m;
      }
      if (out.at_goal) {
        alpha_at_source.push_back(alpha);  // the source is the goal: the level the character arrives with
        ++reached;
        steps_to_goal.push_back(t + 1);
        break;
      }
    }
    return_sum += ret;
  }
  if (episodes > 0) {
    e.goal_reached_ratio = static_cast<double>(reached) / episodes;
    e.alpha_at_1m_ratio = static_cast<double>(prepared_at_1m) / episodes;
    e.mean_return = return_sum / episodes;
  }
  e.median_steps_to_goal = median(steps_to_goal);
  e.median_alpha_at_source = median(alpha_at_source);
  return e;
}

}  // namespace prep
