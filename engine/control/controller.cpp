#include "engine/control/controller.h"

#include <cmath>
#include <cstring>
#include <stdexcept>

#include <algorithm>

#include "engine/util/prefetch.h"

namespace prep {

AlphaFilter::AlphaFilter(float sigma_s, float dt) {
  if (!(sigma_s >= 0.0f) || !(dt > 0.0f)) throw std::invalid_argument("alpha filter: sigma must be >= 0 and dt > 0");
  const int k_max = sigma_s > 0.0f ? static_cast<int>(std::ceil(3.0f * sigma_s / dt)) : 0;
  weights_.resize(static_cast<size_t>(k_max + 1));
  for (int k = 0; k <= k_max; ++k) {
    const float t = static_cast<float>(k) * dt;
    weights_[static_cast<size_t>(k)] = sigma_s > 0.0f ? std::exp(-t * t / (2.0f * sigma_s * sigma_s)) : 1.0f;
  }
  history_.assign(weights_.size(), 0.0f);
  // The weights' running sums, added in the order push() adds them, so that its sum is the same float.
  weight_sums_.resize(weights_.size());
  float sum = 0.0f;
  for (size_t k = 0; k < weights_.size(); ++k) weight_sums_[k] = sum += weights_[k];
}

void AlphaFilter::reset(float alpha) {
  std::fill(history_.begin(), history_.end(), alpha);
  count_ = static_cast<int>(history_.size());
  value_ = alpha;
  value_pushed_ = false;  // not the filter's sum: the next push takes it
  same_run_ = count_;
}

float AlphaFilter::push(float alpha) {
  const int n = static_cast<int>(history_.size());
  const bool repeated = count_ == n && std::memcmp(&alpha, &history_[static_cast<size_t>(head_)], sizeof alpha) == 0;
  same_run_ = repeated ? same_run_ + 1 : 1;
  head_ = head_ + 1 == n ? 0 : head_ + 1;
  history_[static_cast<size_t>(head_)] = alpha;
  if (count_ < n) ++count_;
  // The window and the one before it hold the same value throughout: the sum below would be the one the
  // last push took, to the bit (a level held for long, e.g. full preparation at the source).
  if (same_run_ > n && value_pushed_) return value_;
  // Newest first: k ticks ago is head_ - k, wrapping once from the ring's start to its end.
  float sum = 0.0f;
  const float* w = weights_.data();
  const float* h = history_.data();
  const int before_wrap = std::min(count_, head_ + 1);
  for (int k = 0; k < before_wrap; ++k) sum += w[k] * h[head_ - k];
  for (int k = before_wrap; k < count_; ++k) sum += w[k] * h[head_ - k + n];
  value_ = sum / weight_sums_[static_cast<size_t>(count_ - 1)];
  value_pushed_ = true;
  return value_;
}

Controller::Controller(std::shared_ptr<const Policy> policy, const Params& params)
    : policy_(std::move(policy)),
      states_(policy_->state_space()),
      actions_(policy_->action_space()),
      filter_(params.runtime.alpha_sigma_s, params.runtime.fixed_dt),
      goal_radius_(params.reward.goal_radius),
      source_radius_(params.reward.source_radius) {
  filter_.reset(0.0f);
}

void Controller::reset(int motion, int alpha_level) {
  motion_ = motion;
  alpha_level_ = alpha_level;
  arrived_ = false;
  filter_.reset(alpha_of_level(alpha_level));
}

void Controller::set_smoothing(float sigma_s, float dt) {
  const float now = filter_.value();
  filter_ = AlphaFilter(sigma_s, dt);
  filter_.reset(now);
}

void Controller::set_arrived(bool arrived) {
  arrived_ = arrived;
  if (arrived) alpha_level_ = states_.top_alpha_level();  // Eq. 13's override: the state's alpha is 1
}

ControlDecision Controller::decide(const ControlInput& in) {
  // Greedy over the actions Next(last motion) allows and the caller has not ruled out.
  const std::uint64_t next = actions_.allowed_mask(motion_);
  chosen_bin_ = source_bin(glm::length(in.source - in.position));
  return choose(in, (next & ~in.ruled_out) != 0 ? next & ~in.ruled_out : next);
}

ControlDecision Controller::decide_level(const ControlInput& in) {
  // The levels of the motion playing that Next(m) allows (a core motion may follow itself: its loop).
  const int levels = actions_.alpha_levels();
  const std::uint64_t of_motion = (levels >= 64 ? ~std::uint64_t{0} : (std::uint64_t{1} << levels) - 1) << (motion_ * levels);
  const int playing = alpha_level_;
  chosen_bin_ = source_bin(glm::length(in.source - in.position));
  ControlDecision d = choose(in, actions_.allowed_mask(motion_) & of_motion);
  if (d.state >= 0 && d.alpha_level < playing) {
    // A nearer source calls for no less preparation than the level playing.
    d.alpha_level = alpha_level_ = playing;
    d.alpha = alpha_of_level(playing);
    d.action = actions_.index({motion_, playing});
  }
  return d;
}

ControlDecision Controller::choose(const ControlInput& in, std::uint64_t candidates) {
  const Situation s = make_situation(in.position, in.heading, in.goal, in.source, alpha_level_, motion_);
  ControlDecision d;
  d.at_goal = s.d_g < goal_radius_;
  if (d.at_goal || candidates == 0) {
    // Training ends an episode on entering the goal radius, so the policy never learned anything inside
    // it (its Q values there are untouched): the character carries on with the action it plays (for a
    // goal that is also the launch point, until the arrival stops it there, arrival.h).
    d.action = actions_.index({motion_, alpha_level_});
    d.motion = motion_;
    d.alpha_level = alpha_level_;
    d.alpha = alpha_of_level(alpha_level_);
    d.state = -1;
    return d;
  }
  // At the source the state's alpha is 1, as after every training action that ends there (environment.h).
  d.at_source = s.d_i < source_radius_;
  if (d.at_source || arrived_) alpha_level_ = states_.top_alpha_level();
  StateBins b;
  b.alpha = alpha_level_;
  b.motion = motion_;
  b.d_g = states_.d_g_bin(s.d_g);
  b.theta_g = states_.theta_g_bin(s.theta_g);
  b.d_i = states_.d_i_bin(s.d_i);
  b.theta_i = states_.theta_i_bin(s.theta_i);
  d.state = states_.index(b);
  // Greedy over the candidates (lowest index on ties, as in training).
  const float* row = policy_->row(d.state);
  int best = -1;
  for (int a = 0; a < actions_.size(); ++a)
    if ((candidates >> a & 1u) && (best < 0 || row[a] > row[best])) best = a;
  d.action = best;
  const Action a = actions_.decode(best);
  d.motion = a.motion;
  d.alpha_level = a.alpha_level;
  d.alpha = alpha_of_level(a.alpha_level);
  motion_ = a.motion;
  alpha_level_ = a.alpha_level;  // Eq. 13
  return d;
}

void ControllerBank::add(std::shared_ptr<const Policy> policy) {
  if (for_curve(policy->table.curve)) throw std::invalid_argument("controller bank: a policy for this lower-body curve is already held");
  policies_.push_back(std::move(policy));
}

std::shared_ptr<const Policy> ControllerBank::for_curve(const RootCurve& curve) const {
  for (const auto& p : policies_)
    if (p->table.curve == curve) return p;
  return nullptr;
}

void AlphaFilter::prefetch() const {
  prefetch_vector(weights_);
  prefetch_vector(weight_sums_);
  prefetch_vector(history_);
}

void Controller::prefetch(int level) const {
  if (level == 0) prefetch_object(*this);
  if (level == 1) filter_.prefetch();
}

}  // namespace prep
