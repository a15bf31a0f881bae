#include "engine/control/environment.h"

#include <algorithm>
#include <stdexcept>

namespace prep {

Situation make_situation(glm::vec2 position_xz, float heading, glm::vec2 goal_xz, glm::vec2 source_xz, int alpha_level,
                         int motion) {
  const float sh = std::sin(heading), ch = std::cos(heading);
  Situation s;
  const glm::vec2 g = goal_xz - position_xz, i = source_xz - position_xz;
  s.goal_forward = g.x * sh + g.y * ch;
  s.goal_left = g.x * ch - g.y * sh;
  s.source_forward = i.x * sh + i.y * ch;
  s.source_left = i.x * ch - i.y * sh;
  s.alpha_level = alpha_level;
  s.motion = motion;
  s.update_polar();
  return s;
}

Environment::Environment(const StateSpace& states, const ActionSpace& actions, const ActionTable& table,
                         const RewardParams& reward)
    : states_(states),
      actions_(actions),
      table_(table),
      reward_(reward, states.alpha_levels(), states.alpha_step()) {
  if (actions_.motions() != states_.motions() || actions_.alpha_levels() != states_.alpha_levels() ||
      table_.motions != states_.motions() || table_.alpha_levels != states_.alpha_levels() ||
      static_cast<int>(table_.effects.size()) != actions_.size())
    throw std::invalid_argument("environment: the state space, actions and action table disagree on motions or levels");
  for (int a = 0; a < 64; ++a) {
    const Action d = actions_.decode(a < actions_.size() ? a : 0);
    action_level_[a] = static_cast<std::uint8_t>(d.alpha_level);
    action_motion_[a] = static_cast<std::uint8_t>(d.motion);
  }
  first_start_bin_ = 0;
  while (first_start_bin_ < states_.d_g_bins() - 1 &&
         static_cast<float>(first_start_bin_ + 1) * states_.d_step() <= reward_.goal_radius())
    ++first_start_bin_;
}

void Environment::exploring_start(Rng& rng, float source_at_goal, float far_start_range, Situation& s) const {
  s.alpha_level = rng.below(states_.alpha_levels());
  s.motion = rng.below(states_.motions());
  float lo, hi;
  // The far end of the last distance bin's starts (see environment.h).
  auto far_edge = [&](int bins, float bin_hi) { return std::max(bin_hi, far_start_range * states_.d_step() * static_cast<float>(bins)); };
  const int dg_bin = first_start_bin_ + rng.below(states_.d_g_bins() - first_start_bin_);
  states_.distance_range(dg_bin, lo, hi);
  if (dg_bin == states_.d_g_bins() - 1) hi = far_edge(states_.d_g_bins(), hi);
  lo = std::max(lo, reward_.goal_radius());
  if (hi <= lo) hi = lo + states_.d_step();  // a goal radius beyond every bin: start just outside it
  const float d_g = rng.uniform(lo, hi);
  states_.theta_g_range(rng.below(states_.theta_g_bins()), lo, hi);
  const float theta_g = rng.uniform(lo, hi);
  s.goal_left = d_g * std::sin(theta_g);
  s.goal_forward = d_g * std::cos(theta_g);
  if (rng.uniform() < source_at_goal) {
    s.source_left = s.goal_left;
    s.source_forward = s.goal_forward;
  } else {
    const int di_bin = rng.below(states_.d_i_bins());
    states_.distance_range(di_bin, lo, hi);
    if (di_bin == states_.d_i_bins() - 1) hi = far_edge(states_.d_i_bins(), hi);
    const float d_i = rng.uniform(lo, hi);
    states_.theta_i_range(rng.below(states_.theta_i_bins()), lo, hi);
    const float theta_i = rng.uniform(lo, hi);
    s.source_left = d_i * std::sin(theta_i);
    s.source_forward = d_i * std::cos(theta_i);
  }
  s.update_polar();
}

}  // namespace prep
