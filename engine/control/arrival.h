// Arrival at the source of influence at run time: where Sec. 6.2's "when a character reaches the source of
// influence, alpha is forced to be 1.0" happens when the character moves tick by tick.
//
// In training an action is a whole gait cycle and "reaching" the source is ending one within
// RewardParams::source_radius, after which the state's alpha is 1 (reward.h). At run time the character
// must also stop where its target clip, entered at T_p, meets the object (the launch point, world.h), and
// at alpha = 1 it does stop: the root weight w_r is 1 and Eq. 3-4 leave no stride. So:
// - Arrival: once the launch point is within the arrival radius (and ahead), the alpha the controller
//   plays is forced to 1. The Gaussian filter (controller.h) raises the smoothed alpha from where it was,
//   Eq. 3-4 shorten the stride as it rises, and the character glides to a stop.
// - The arrival radius is computed here, not chosen: the stopping distance of a character walking
//   steadily at the highest level that still moves (the top level but one: 0.8) at the fastest core
//   motion's speed, from the moment the forcing starts until the stride is gone (the filter's output is 1
//   after its last tap, 3 sigma); plus, for a source that moves toward the character (an opponent), what
//   the source covers toward it until the character's smoothed alpha has reached launch_alpha.
// - Launch: within the arrival radius as soon as the smoothed alpha reaches RuntimeParams::launch_alpha
//   (0.9), or at the launch point (reached or passed) whatever the alpha.
// A character that arrives walking at the top moving level thus launches at launch_alpha a few
// centimetres before the launch point, where it would have stopped (the last of the glide is slow: the
// stride fades as sqrt(1 - alpha)). One that arrives less prepared is faster, reaches the launch point
// before its smoothed alpha has risen and launches there less prepared: the forcing does not hide an
// unprepared approach (that is what prep evaluate-policy's median_alpha_at_source and the scenarios'
// alpha_at_launch measure).
#pragma once

#include "engine/control/action_effects.h"
#include "engine/params/params.h"

namespace prep {

class ArrivalModel {
 public:
  // Throws std::invalid_argument if launch_alpha is not in (0, 1] or the table has fewer than two levels.
  ArrivalModel(const ActionTable& table, float alpha_step, const RuntimeParams& runtime);

  float launch_alpha() const { return launch_alpha_; }
  float approach_level() const { return approach_level_; }  // the top level that still moves (0.8)
  float approach_speed() const { return approach_speed_; }  // m/s: the fastest core motion at that level
  float glide_distance() const { return glide_distance_; }  // m: the stopping distance, see above
  float glide_time() const { return glide_time_; }          // s: from the forcing to launch_alpha
  float stop_time() const { return stop_time_; }            // s: from the forcing to the stop
  // The arrival radius for a source closing in at closing_speed m/s (0 for a still object).
  float radius(float closing_speed = 0.0f) const {
    return glide_distance_ + (closing_speed > 0.0f ? closing_speed * glide_time_ : 0.0f);
  }

 private:
  float launch_alpha_, approach_level_, approach_speed_, glide_distance_, glide_time_, stop_time_;
};

}  // namespace prep
