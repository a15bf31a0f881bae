// The behaviour controller at run time (Sec. 6.1 end, Sec. 8).
//
// Each control step (when the character may switch motion: at the end of an action, one gait cycle) the
// controller quantizes the situation (Eq. 11) and takes the greedy action a = {m, alpha} of its policy; the
// chosen alpha becomes the state's alpha (Eq. 13). Discrete alpha levels would give discrete behaviour,
// so the alpha that reaches synthesis passes a Gaussian filter over time.
//
// The forcing of alpha to 1 at the source (Sec. 6.2) happens at run time as in training: a decision taken
// within RewardParams::source_radius of the source is taken in the state whose alpha is 1 (Eq. 13's
// override, environment.h), so the policy is asked only the questions it was trained on. Once the
// character has arrived at its launch point (arrival.h, decided by the world) the played alpha itself is
// forced to 1 and the character glides to a stop, prepared.
//
// The filter is causal (it only knows the past): each engine tick it records the alpha chosen last, and
// outputs the Gaussian-weighted mean of the recorded history, weight exp(-(k dt)^2 / (2 sigma^2)) for the
// sample k ticks ago, k = 0 .. ceil(3 sigma / dt) (sigma = RuntimeParams::alpha_sigma_s). That is the right
// half of a Gaussian kernel: a step in the chosen alpha comes out as a smooth rise following
// erf(t / (sigma sqrt 2)), reaching 68% after sigma and 99.7% after 3 sigma. Until the history is full
// the weights of the samples seen so far are renormalised (the first output is the first chosen alpha).
//
// Sec. 8: a policy serves every target motion whose lower-body (root) blend curve is the one it was
// trained with, because that curve alone shapes the stride (Eq. 3-4); a ControllerBank keeps one policy per
// curve and hands out the one for a target's curve.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <glm/vec2.hpp>

#include "engine/control/environment.h"
#include "engine/control/policy.h"
#include "engine/params/params.h"

namespace prep {

class AlphaFilter {
 public:
  AlphaFilter(float sigma_s, float dt);
  void reset(float alpha);     // history filled with alpha
  float push(float alpha);     // records one tick's chosen alpha, returns the filtered alpha
  float value() const { return value_; }
  void prefetch() const;  // asks the processor for the memory the next push() reads (its buffers)
  int taps() const { return static_cast<int>(weights_.size()); }

 private:
  std::vector<float> weights_;      // [k] for the sample k ticks ago
  std::vector<float> weight_sums_;  // [k]: weights_[0] + ... + weights_[k]
  std::vector<float> history_;  // ring buffer
  int head_ = 0, count_ = 0;
  float value_ = 0.0f;
  bool value_pushed_ = false;  // value_ is the sum push() took (not reset()'s level)
  int same_run_ = 0;           // the newest samples in a row with the same bits
};

// Where things are on the floor, in world coordinates (x, z).
struct ControlInput {
  glm::vec2 position{0.0f};
  float heading = 0.0f;  // the character faces (sin h, 0, cos h)
  glm::vec2 goal{0.0f};
  glm::vec2 source{0.0f};
  // Actions the caller's run-time rules rule out (bit a: action a), on top of those Next(m) does not allow.
  // Ignored when it would leave no action.
  std::uint64_t ruled_out = 0;
};

struct ControlDecision {
  int action = 0;
  int motion = 0;         // index into the policy's core motions
  int alpha_level = 0;
  float alpha = 0.0f;     // the chosen (unfiltered) level
  int state = 0;          // the quantized state it was chosen in (-1 at the goal: the action kept)
  bool at_goal = false;   // the goal is within the goal radius: the last action is kept (controller.cpp)
  bool at_source = false; // within the source radius: the state's alpha was forced to 1 (Eq. 13)
};

class Controller {
 public:
  Controller(std::shared_ptr<const Policy> policy, const Params& params);

  // The greedy action in the current situation; updates the state's alpha (Eq. 13) and last motion.
  ControlDecision decide(const ControlInput& in);
  // The greedy level for the motion playing, the motion kept (its gait cycle plays on): the level chosen
  // again in the situation the character is now in (RuntimeParams::level_per_source_bin), unless it is
  // below the level playing, which then stays.
  ControlDecision decide_level(const ControlInput& in);
  // The distance bin (the state's d_i) of a source this far away.
  int source_bin(float distance) const { return states_.d_i_bin(distance); }
  // A source this far away lies in a nearer distance bin than the one the level was last chosen in (by
  // decide or decide_level, each of which keeps the bin of its input's source).
  bool source_came_nearer(float distance) const { return source_bin(distance) < chosen_bin_; }
  // One engine tick (RuntimeParams::fixed_dt): the filtered alpha for synthesis (1 is played once arrived).
  // Relaxed (no source calls for preparation, RuntimeParams::relax_without_source), 0 is played whatever
  // the level: the policy and its state are the paper's, only what synthesis plays relaxes. Beyond the
  // paper, whose Eq. 14-17 never lower alpha when nothing is near (Eq. 16 only penalises change).
  float tick(bool relaxed = false) {
    return filter_.push(arrived_ ? 1.0f : relaxed ? 0.0f : alpha_of_level(alpha_level_));
  }
  float filtered_alpha() const { return filter_.value(); }
  // Arrival at the launch point (arrival.h): the played alpha is forced to 1 and the state's alpha is the
  // top level until set_arrived(false).
  void set_arrived(bool arrived);
  bool arrived() const { return arrived_; }
  // Asks the processor for the memory the next decision or alpha step reads: level 0 the controller, 1 its
  // filter's buffers (World::prefetch).
  void prefetch(int level) const;

  void reset(int motion, int alpha_level);  // also ends an arrival; the filter restarts at that level
  // A new width of the Gaussian filter (RuntimeParams::alpha_sigma_s) or tick, as a panel changes it while
  // the world runs: the filter starts over from the alpha it gives now, so the played alpha does not jump.
  void set_smoothing(float sigma_s, float dt);
  int motion() const { return motion_; }
  int alpha_level() const { return alpha_level_; }
  float alpha_of_level(int level) const { return states_.alpha_of(level); }
  const Policy& policy() const { return *policy_; }
  const ActionEffect& effect(int action) const { return policy_->table.at(action); }
  const std::string& motion_role(int motion) const { return policy_->table.motion_roles[static_cast<size_t>(motion)]; }
  const std::string& motion_name(int motion) const { return policy_->table.motion_names[static_cast<size_t>(motion)]; }

 private:
  // The greedy action among `candidates` (a mask of actions), as decide() takes it.
  ControlDecision choose(const ControlInput& in, std::uint64_t candidates);

  std::shared_ptr<const Policy> policy_;
  StateSpace states_;
  ActionSpace actions_;
  AlphaFilter filter_;
  float goal_radius_, source_radius_;
  int motion_ = 0, alpha_level_ = 0;
  int chosen_bin_ = 0;  // the source's distance bin where the level was last chosen
  bool arrived_ = false;
};

// One policy per lower-body blend curve (Sec. 8).
class ControllerBank {
 public:
  // Throws std::invalid_argument if a policy for the same curve is already held.
  void add(std::shared_ptr<const Policy> policy);
  // The policy for a target whose root curve is `curve`; nullptr if none was trained for it.
  std::shared_ptr<const Policy> for_curve(const RootCurve& curve) const;
  size_t size() const { return policies_.size(); }

 private:
  std::vector<std::shared_ptr<const Policy>> policies_;
};

}  // namespace prep
