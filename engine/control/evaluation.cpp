#include "engine/control/evaluation.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "engine/control/angles.h"
#include "engine/control/arrival.h"
#include "engine/control/controller.h"
#include "engine/control/sarsa.h"

namespace prep {
namespace {

using control_angles::kPi;

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// A core motion at alpha 0 as a constant velocity in the character's own frame (forward, left) and a
// constant turn rate, chosen so that integrating them over the action's duration gives the action
// table's effect exactly: with the frame turning at w = turn / T, the displacement in the start frame is
// M u with M = [[S, -C], [C, S]], S = sin(turn) / w, C = (1 - cos(turn)) / w (both T when turn = 0).
struct MotionRate {
  float forward = 0, left = 0, turn = 0;  // m/s, m/s, rad/s
};

MotionRate rate_of(const ActionEffect& e) {
  MotionRate r;
  if (!(e.duration > 0.0f)) return r;
  r.turn = e.turn / e.duration;
  float S = e.duration, C = 0.0f;
  if (std::fabs(e.turn) > 1e-6f) {
    S = std::sin(e.turn) / r.turn;
    C = (1.0f - std::cos(e.turn)) / r.turn;
  }
  const float det = S * S + C * C;
  r.forward = (S * e.forward + C * e.left) / det;
  r.left = (-C * e.forward + S * e.left) / det;
  return r;
}

glm::vec2 forward_of(float heading) { return {std::sin(heading), std::cos(heading)}; }
glm::vec2 left_of(float heading) { return {std::cos(heading), -std::sin(heading)}; }

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

PolicyEvaluation evaluate_policy(std::shared_ptr<const Policy> policy, const Params& params, int episodes, std::uint64_t seed) {
  const ActionTable& table = policy->table;
  const ArrivalModel arrival(table, policy->quantization.alpha_step, params.runtime);
  std::vector<MotionRate> rates;
  for (int m = 0; m < table.motions; ++m) rates.push_back(rate_of(table.at(m * table.alpha_levels)));
  const StateSpace states = policy->state_space();
  const float range = static_cast<float>(states.d_g_bins()) * states.d_step();
  const float dt = params.runtime.fixed_dt, goal_radius = params.reward.goal_radius;
  const float cos45 = std::cos(kPi / 4.0f), one_metre = 1.0f;  // the distance of alpha_at_1m_ratio, by definition
  const int max_decisions = params.sarsa.max_episode_steps;

  Rng rng(seed);
  PolicyEvaluation e;
  e.episodes = episodes;
  std::vector<double> steps_to_goal, seconds_to_goal, alpha_at_source, level_at_arrival, alpha_at_1m;
  int reached = 0, prepared_at_1m = 0, played_prepared_at_1m = 0;
  Controller controller(policy, params);
  for (int ep = 0; ep < episodes; ++ep) {
    const float d = rng.uniform(range, 2.0f * range), bearing = rng.uniform(-kPi, kPi);
    const glm::vec2 goal(d * std::sin(bearing), d * std::cos(bearing));
    glm::vec2 position(0.0f);
    float heading = 0.0f, time = 0.0f, next_decision = 0.0f;
    int decisions = 0, motion = 0;
    bool seen_1m = false;
    controller.reset(0, 0);
    while (true) {
      // The world's order per tick: decide (at the end of an action; the level again when the source comes
      // a distance bin nearer, RuntimeParams::level_per_source_bin), filter, move, then arrival and launch.
      ControlInput in;
      in.position = position;
      in.heading = heading;
      in.goal = in.source = goal;
      if (!controller.arrived() && time >= next_decision) {
        if (decisions == max_decisions) break;
        const ControlDecision c = controller.decide(in);
        motion = c.motion;
        next_decision = time + std::max(table.at(c.action).duration, dt);
        ++decisions;
      } else if (!controller.arrived() && params.runtime.level_per_source_bin &&
                 controller.source_came_nearer(glm::length(goal - position))) {
        controller.decide_level(in);
      }
      const float alpha = controller.tick();
      const MotionRate& r = rates[static_cast<size_t>(motion)];
      const float stride = 1.0f - table.curve.weight(alpha);  // Eq. 3-4
      position += stride * dt * (r.forward * forward_of(heading) + r.left * left_of(heading));
      heading += r.turn * dt;
      time += dt;

      const glm::vec2 to_goal = goal - position;
      const float distance = glm::length(to_goal);
      const bool ahead = glm::dot(to_goal, forward_of(heading)) >= cos45 * distance;
      if (!seen_1m && distance <= one_metre) {
        seen_1m = true;
        const float level = controller.alpha_of_level(controller.alpha_level());  // the state's alpha (Eq. 13)
        alpha_at_1m.push_back(alpha);
        if (level >= 0.5f) ++prepared_at_1m;
        if (alpha >= 0.5f) ++played_prepared_at_1m;
      }
      if (!controller.arrived() && ahead && distance - goal_radius <= arrival.radius()) {
        level_at_arrival.push_back(controller.alpha_of_level(controller.alpha_level()));
        controller.set_arrived(true);
      }
      const bool at_point = ahead && distance <= goal_radius;
      if (at_point || (controller.arrived() && alpha >= arrival.launch_alpha())) {
        alpha_at_source.push_back(alpha);
        steps_to_goal.push_back(decisions);
        seconds_to_goal.push_back(time);
        ++reached;
        break;
      }
    }
  }
  if (episodes > 0) {
    e.goal_reached_ratio = static_cast<double>(reached) / episodes;
    e.alpha_at_1m_ratio = static_cast<double>(prepared_at_1m) / episodes;
    e.played_alpha_at_1m_ratio = static_cast<double>(played_prepared_at_1m) / episodes;
  }
  e.median_steps_to_goal = median(steps_to_goal);
  e.median_seconds_to_goal = median(seconds_to_goal);
  e.median_alpha_at_source = median(alpha_at_source);
  e.median_level_at_arrival = median(level_at_arrival);
  e.median_alpha_at_1m = median(alpha_at_1m);
  return e;
}

}  // namespace prep
