// The training environment of Sec. 6: a character on the floor plane, a goal and a source of influence
// (separate, Fig. 9; often the same point). Lean by design, it runs tens of millions of steps a second:
// the character's own frame is the simulation frame (goal and source are kept relative to the character,
// so an action is one translation and one rotation by its precomputed cos/sin), angles come from a small
// polynomial atan2, the reward's power terms are tabulated, and nothing allocates after construction.
#pragma once

#include <algorithm>
#include <cmath>

#include <glm/vec2.hpp>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "engine/control/action_effects.h"
#include "engine/control/actions.h"
#include "engine/control/random.h"
#include "engine/control/reward.h"
#include "engine/control/state.h"

namespace prep {

// atan(t) on [0, 1] as t * (c0 + s * (c1 + s * (c2 + s * (c3 + s * c4)))), s = t^2: a polynomial fitted by
// us (max error 1.2e-5 rad). Shared by fast_atan2 and its four-lane version, which must agree bit for bit.
constexpr float kAtanC0 = 0.99986642f, kAtanC1 = -0.33030633f, kAtanC2 = 0.18016580f, kAtanC3 = -0.08516615f,
                kAtanC4 = 0.02084992f;
constexpr float kHalfPiF = 1.57079633f, kPiF = 3.14159265f;

// atan2 from that polynomial, then octant fix-ups.
inline float fast_atan2(float y, float x) {
  const float ax = std::fabs(x), ay = std::fabs(y);
  const float hi = ax > ay ? ax : ay, lo = ax > ay ? ay : ax;
  if (hi == 0.0f) return 0.0f;
  const float t = lo / hi, s = t * t;
  float r = t * (kAtanC0 + s * (kAtanC1 + s * (kAtanC2 + s * (kAtanC3 + s * kAtanC4))));
  if (ay > ax) r = kHalfPiF - r;
  if (x < 0.0f) r = kPiF - r;
  return y < 0.0f ? -r : r;
}

#if defined(__SSE2__)
// fast_atan2 and the length sqrt(x^2 + y^2) of four vectors at once, without branches: the same float
// operations lane by lane, so the same values bit for bit (the octant fix-ups become selects, the sign a
// flip). Training takes the goal's and the source's bearing at every step; their octants are random, and
// the scalar version's mispredicted branches cost more than its arithmetic.
inline void fast_atan2_and_length_x4(__m128 y, __m128 x, __m128& angle, __m128& length) {
  const __m128 sign = _mm_set1_ps(-0.0f), zero = _mm_setzero_ps();
  auto select = [](__m128 mask, __m128 a, __m128 b) { return _mm_or_ps(_mm_and_ps(mask, a), _mm_andnot_ps(mask, b)); };
  length = _mm_sqrt_ps(_mm_add_ps(_mm_mul_ps(y, y), _mm_mul_ps(x, x)));
  const __m128 ax = _mm_andnot_ps(sign, x), ay = _mm_andnot_ps(sign, y);
  const __m128 hi = _mm_max_ps(ax, ay), lo = _mm_min_ps(ay, ax);  // ax > ay ? ax : ay, ax > ay ? ay : ax
  const __m128 at_origin = _mm_cmpeq_ps(hi, zero);
  const __m128 t = _mm_div_ps(lo, select(at_origin, _mm_set1_ps(1.0f), hi)), s = _mm_mul_ps(t, t);  // origin: t = 0
  __m128 p = _mm_add_ps(_mm_set1_ps(kAtanC3), _mm_mul_ps(s, _mm_set1_ps(kAtanC4)));
  p = _mm_add_ps(_mm_set1_ps(kAtanC2), _mm_mul_ps(s, p));
  p = _mm_add_ps(_mm_set1_ps(kAtanC1), _mm_mul_ps(s, p));
  p = _mm_add_ps(_mm_set1_ps(kAtanC0), _mm_mul_ps(s, p));
  __m128 r = _mm_mul_ps(t, p);
  r = select(_mm_cmpgt_ps(ay, ax), _mm_sub_ps(_mm_set1_ps(kHalfPiF), r), r);
  r = select(_mm_cmplt_ps(x, zero), _mm_sub_ps(_mm_set1_ps(kPiF), r), r);
  r = _mm_xor_ps(r, _mm_and_ps(_mm_cmplt_ps(y, zero), sign));
  angle = _mm_andnot_ps(at_origin, r);  // the scalar version's early return of +0 (r is already +0 there)
}
#endif

// The continuous situation: goal and source relative to the character (left = +X when facing +Z,
// forward = facing), their distances and bearings (positive to the left), the state's alpha level
// (Eq. 13) and the last core motion.
struct Situation {
  float goal_left = 0, goal_forward = 0;
  float source_left = 0, source_forward = 0;
  float d_g = 0, theta_g = 0, d_i = 0, theta_i = 0;
  int alpha_level = 0;
  int motion = 0;

  void update_polar() {
#if defined(__SSE2__)
    __m128 angle, length;  // lane 0 the goal, lane 1 the source
    fast_atan2_and_length_x4(_mm_setr_ps(goal_left, source_left, 0.0f, 0.0f),
                             _mm_setr_ps(goal_forward, source_forward, 0.0f, 0.0f), angle, length);
    d_g = _mm_cvtss_f32(length);
    theta_g = _mm_cvtss_f32(angle);
    d_i = _mm_cvtss_f32(_mm_shuffle_ps(length, length, _MM_SHUFFLE(1, 1, 1, 1)));
    theta_i = _mm_cvtss_f32(_mm_shuffle_ps(angle, angle, _MM_SHUFFLE(1, 1, 1, 1)));
#else
    d_g = std::sqrt(goal_left * goal_left + goal_forward * goal_forward);
    theta_g = fast_atan2(goal_left, goal_forward);
    d_i = std::sqrt(source_left * source_left + source_forward * source_forward);
    theta_i = fast_atan2(source_left, source_forward);
#endif
  }
};

// A situation from world positions on the floor (x, z) and the character's heading (facing
// (sin h, 0, cos h)).
Situation make_situation(glm::vec2 position_xz, float heading, glm::vec2 goal_xz, glm::vec2 source_xz, int alpha_level,
                         int motion);

struct StepOutcome {
  float reward = 0;
  bool at_goal = false;    // the episode ends (absorbing goal, see reward.h)
  bool at_source = false;  // alpha was forced to 1
};

class Environment {
 public:
  Environment(const StateSpace& states, const ActionSpace& actions, const ActionTable& table, const RewardParams& reward);

  const StateSpace& states() const { return states_; }
  const ActionSpace& actions() const { return actions_; }
  const ActionTable& table() const { return table_; }
  const RewardModel& reward() const { return reward_; }

  // Eq. 11: the quantized state of a situation.
  int quantize(const Situation& s) const {
    return states_.index_of(s.alpha_level, s.motion, s.d_g, s.theta_g, s.d_i, s.theta_i);
  }

  // Plays action a from s: moves and turns the character, applies Eq. 13 (and the forcing of alpha to 1 at
  // the source), and returns the reward of Eq. 17.
  StepOutcome step(Situation& s, int action) const {
    const int level = action_level_[action], motion = action_motion_[action];  // decode without a division
    const ActionEffect& e = table_.at(action);
    const float d_g = s.d_g, theta_g = s.theta_g;
    // The closest the action's chord comes to the goal (the world checks the goal every tick, so a goal the
    // character walks through is reached even if the action ends beyond it).
    const float along = (s.goal_left * e.left + s.goal_forward * e.forward) * e.inv_chord2;
    const float t = std::min(1.0f, std::max(along, 0.0f));  // along < 0 ? 0 : along > 1 ? 1 : along (minss, maxss)
    const float cl = s.goal_left - t * e.left, cf = s.goal_forward - t * e.forward;
    const float closest_g = std::sqrt(cl * cl + cf * cf);
    move(s.goal_left, s.goal_forward, e);
    move(s.source_left, s.source_forward, e);
    s.update_polar();
    StepOutcome out;
    out.at_source = s.d_i < reward_.source_radius();  // at the source: within its radius (reward.h)
    out.at_goal = closest_g < reward_.goal_radius();
    // Reached mid-action, the character stops there, having walked at the goal from the bearing it had when
    // the action began: Eq. 14-15 are taken there (past the goal, its bearing would be behind).
    const float d_g_next = out.at_goal ? closest_g : s.d_g;
    const float theta_g_next = out.at_goal ? theta_g : s.theta_g;
    out.reward = reward_(std::fabs(theta_g_next), d_g, d_g_next, s.alpha_level, level, out.at_source);  // Eq. 17
    s.alpha_level = out.at_source ? states_.top_alpha_level() : level;  // Eq. 13, forced at the source
    s.motion = motion;
    return out;
  }

  // Exploring start: a uniformly random state (alpha level, last motion, and a goal and source placed at a
  // uniformly random point of random bins), never one already at the goal. With probability
  // source_at_goal the source of influence is the goal itself. The last distance bin means "that far or
  // farther"; its starts are drawn from its lower edge out to far_start_range x the quantized range
  // (d_step x bins), so that what the policy does in it is learned from the distances it will meet there
  // (prep evaluate-policy starts at 1-2 x the range; a scenario's obstacles lie 2-5 m ahead), not only from
  // the bin's first 0.4 m. A far_start_range of 1 or less keeps the bin's own width.
  void exploring_start(Rng& rng, float source_at_goal, float far_start_range, Situation& s) const;

 private:
  static void move(float& left, float& forward, const ActionEffect& e) {
    // Into the character's frame after the action: translate by the footstep, then rotate by -turn.
    const float l = left - e.left, f = forward - e.forward;
    forward = f * e.cos_turn + l * e.sin_turn;
    left = l * e.cos_turn - f * e.sin_turn;
  }

  StateSpace states_;
  ActionSpace actions_;
  ActionTable table_;
  RewardModel reward_;
  int first_start_bin_;  // the first d_g bin with room outside the goal radius
  std::uint8_t action_level_[64], action_motion_[64];
};

}  // namespace prep
