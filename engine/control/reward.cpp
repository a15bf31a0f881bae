#include "engine/control/reward.h"

#include <cmath>

#include "engine/control/angles.h"

namespace prep {
namespace {
using control_angles::kPi;
}

float reward_facing(float theta_g_next, const RewardParams& p) {
  return 1.0f - std::fabs(theta_g_next) / (p.theta_norm_deg * kPi / 180.0f);  // Eq. 14
}

float reward_approach(float d_g, float d_g_next, const RewardParams& p) {
  return (p.d_norm + d_g - d_g_next) / (2.0f * p.d_norm);  // Eq. 15
}

float reward_steadiness(float alpha, float alpha_next, const RewardParams& p) {
  return 1.0f - std::pow(std::fabs(alpha_next - alpha), p.C_alpha);  // Eq. 16
}

float reward_steadiness_at_source(float alpha, float action_alpha, const RewardParams& p) {
  // Eq. 16 on both changes of the played alpha: to the action's alpha (Eq. 13), then forced to 1.
  return 1.0f - std::pow(std::fabs(action_alpha - alpha), p.C_alpha) - std::pow(std::fabs(1.0f - action_alpha), p.C_alpha);
}

RewardTerms reward_terms(float theta_g_next, float d_g, float d_g_next, float alpha, float action_alpha,
                         bool at_source, const RewardParams& p) {
  RewardTerms t;
  t.facing = reward_facing(theta_g_next, p);
  t.approach = reward_approach(d_g, d_g_next, p);
  t.steadiness = at_source ? reward_steadiness_at_source(alpha, action_alpha, p) : reward_steadiness(alpha, action_alpha, p);
  t.total = p.w_theta * t.facing + p.w_d * t.approach + p.w_alpha * t.steadiness;  // Eq. 17
  return t;
}

float goal_value(const RewardParams& reward, float discount) {
  const float r_max = reward.w_theta + reward.w_d + reward.w_alpha;  // Eq. 17 with every term at 1
  return r_max / (1.0f - discount);                                 // Eq. 18 summed over an endless stay
}

RewardModel::RewardModel(const RewardParams& p, int alpha_levels, float alpha_step)
    : levels_(alpha_levels),
      facing_bias_(p.w_theta),
      facing_slope_(p.w_theta / (p.theta_norm_deg * kPi / 180.0f)),
      approach_bias_(p.w_d * 0.5f),
      approach_slope_(p.w_d / (2.0f * p.d_norm)),
      goal_radius_(p.goal_radius),
      source_radius_(p.source_radius),
      max_reward_(p.w_theta + p.w_d + p.w_alpha) {
  steadiness_.resize(static_cast<size_t>(2 * levels_ * levels_));
  for (int from = 0; from < levels_; ++from)
    for (int to = 0; to < levels_; ++to) {
      const float a = static_cast<float>(from) * alpha_step, b = static_cast<float>(to) * alpha_step;
      steadiness_[static_cast<size_t>(from * levels_ + to)] = p.w_alpha * reward_steadiness(a, b, p);
      steadiness_[static_cast<size_t>((levels_ + from) * levels_ + to)] = p.w_alpha * reward_steadiness_at_source(a, b, p);
    }
}

}  // namespace prep
