#include "engine/control/arrival.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "engine/control/controller.h"

namespace prep {

ArrivalModel::ArrivalModel(const ActionTable& table, float alpha_step, const RuntimeParams& runtime)
    : launch_alpha_(runtime.launch_alpha) {
  if (!(launch_alpha_ > 0.0f && launch_alpha_ <= 1.0f)) throw std::invalid_argument("runtime.launch_alpha must be in (0, 1]");
  if (table.alpha_levels < 2 || table.motions < 1) throw std::invalid_argument("arrival: the action table needs two alpha levels");
  const int level = table.alpha_levels - 2;
  approach_level_ = static_cast<float>(level) * alpha_step;
  // The fastest core motion at the approach level (m/s), from the table (Eq. 3-4 are in it).
  approach_speed_ = 0.0f;
  for (int m = 0; m < table.motions; ++m) {
    const ActionEffect& e = table.at(m * table.alpha_levels + level);
    if (e.duration > 0.0f) approach_speed_ = std::max(approach_speed_, std::hypot(e.forward, e.left) / e.duration);
  }
  // The speed at alpha = 0, which Eq. 3-4 scale by (1 - w_r) tick by tick as the filter raises alpha.
  const float w_approach = table.curve.weight(approach_level_);
  const float free_speed = w_approach < 1.0f ? approach_speed_ / (1.0f - w_approach) : 0.0f;
  // Replay the forcing tick by tick as the world does: push 1 into the filter, then move with the
  // filtered alpha, until the stride is gone (the filter reaches 1 exactly after its last tap).
  AlphaFilter filter(runtime.alpha_sigma_s, runtime.fixed_dt);
  filter.reset(approach_level_);
  glide_distance_ = glide_time_ = stop_time_ = 0.0f;
  for (int k = 0; k <= filter.taps() && filter.value() < 1.0f; ++k) {
    const float alpha = filter.push(1.0f);
    glide_distance_ += (1.0f - table.curve.weight(alpha)) * free_speed * runtime.fixed_dt;  // Eq. 3-4
    stop_time_ += runtime.fixed_dt;
    if (alpha < launch_alpha_) glide_time_ += runtime.fixed_dt;
  }
}

}  // namespace prep
