// Walking built from published gait biomechanics.
//
// The sagittal hip, knee and ankle angles over the gait cycle follow the normative curves of adult walking
// at natural cadence (D. A. Winter, "The Biomechanics and Motor Control of Human Gait: Normal, Elderly and
// Pathological", 2nd ed., 1991; J. Perry, "Gait Analysis: Normal and Pathological Function", 1992): our
// own table of the curves' values every 5% of the cycle, read by periodic Catmull-Rom. Around them: pelvic
// rotation, obliquity and tilt, the lateral sway and vertical bob of the pelvis, thorax counter-rotation and
// arm swing opposite the legs (Perry ch. 9 and 10). Stance lasts 60% of the cycle (Perry: toe-off at 60%), so each
// double support lasts 10%. The feet are then planted by realize(): anchors on the floor, IK for the legs.
#pragma once

#include <functional>
#include <vector>

#include <glm/vec2.hpp>

#include "engine/library/dof_pose.h"
#include "engine/library/draft.h"

namespace prep::library {

constexpr float kStanceFraction = 0.60f;  // heel strike at phase 0, toe-off at 0.60 (right leg; left +0.5)

struct GaitStyle {
  float amplitude = 1.0f;        // sagittal excursions relative to natural cadence (slower walks swing less)
  float arm_swing = 1.0f;        // arm swing relative to natural walking
  float step_half_width = 0.06f; // m: each foot's centre line beside the path (step width ~12 cm)
  float toe_out = 0.10f;         // rad: foot progression angle outward
  float trunk_lean = 0.06f;      // rad: forward lean of the trunk
  float fps = 60.0f;
  // Derived by plan_gait():
  float cycle_s = 1.0f;          // one stride (two steps), a whole number of frames
  float stride_m = 1.4f;
  float speed = 1.4f;            // stride / cycle
  std::vector<float> pelvis_height;  // root height over one cycle (phase samples), from the stance legs
};

// Plans a gait of about `speed` m/s: stride from the leg angles (times `amplitude`), a cycle that is a
// whole number of frames, the pelvis height that keeps the stance legs on the floor.
GaitStyle plan_gait(float speed, float amplitude, float fps);

// The walking pose at right-leg phase `phase` (0 = right heel strike) in the path's frame: root on the
// path's origin (plus the lateral sway), heading 0.
DofPose gait_pose(const GaitStyle& style, float phase);

// A walker on a path: time t (s) has phase phase0 + t / cycle; the path starts at `origin` (its point at
// t = 0) and turns with heading(t) (radians, + left); the root travels at the gait's speed.
class Walker {
 public:
  Walker(GaitStyle style, float phase0, glm::vec2 origin, float heading0, std::function<float(float)> heading_change = {});

  const GaitStyle& style() const { return style_; }
  float phase(float t) const { return phase0_ + t / style_.cycle_s; }
  float heading(float t) const { return heading0_ + (turn_ ? turn_(t) : 0.0f); }
  glm::vec2 path(float t) const;  // root path point (without sway)
  DofPose pose(float t) const;     // world pose
  DofPose velocity(float t) const; // d pose / dt (central difference)
  // Stance intervals of `side` (0 left, 1 right) overlapping [t_begin, t_end], as frames of a clip whose
  // frame 0 is at time clip_t0; anchors on the path at mid-stance.
  std::vector<Support> supports(int side, float t_begin, float t_end, float clip_t0) const;

 private:
  GaitStyle style_;
  float phase0_, heading0_;
  glm::vec2 origin_;
  std::function<float(float)> turn_;
  std::vector<glm::vec2> path_;  // sampled path for t in [path_t0_, ...) at path_dt_
  float path_t0_ = 0, path_dt_ = 0;
};

}  // namespace prep::library
