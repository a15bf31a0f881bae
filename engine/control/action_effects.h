// The effect of an action a = {m, alpha} on where the character is: its root displacement in the
// character's frame, its turn and its duration, per core motion m and preparation level.
//
// Tabulated from the motion data through the synthesis pipeline's trajectory adjustment: the clip's root
// travel is replayed frame by frame with advance_root (Eq. 3-4), whose displacement shrinks by (1 - w_r)
// as the root's Eq. 1 weight w_r rises with alpha; the heading follows the locomotion (blend_root_rotation
// keeps it), so a turning motion still turns when prepared. Nothing here is typed in by hand.
//
// One action is one footstep (the motion graph can switch motion at each): the clip's loop is cut into as
// many equal parts as it has footsteps (touchdowns in its contacts, at least two: one gait cycle), each
// part measured in the frame the character had at its start, and the effect is their mean (left and right
// steps differ slightly).
#pragma once

#include <string>
#include <vector>

#include "engine/motion/motion_set.h"
#include "engine/params/params.h"

namespace prep {

struct ActionEffect {
  float forward = 0.0f;   // m along the character's facing at the start of the action
  float left = 0.0f;      // m to the character's left (+X when facing +Z)
  float turn = 0.0f;      // rad, positive to the left (counter-clockwise seen from above)
  float duration = 0.0f;  // s
  float cos_turn = 1.0f;  // cos(turn) and sin(turn), precomputed for the environment step
  float sin_turn = 0.0f;
};

// The lower-body (root) blend curve the table was made with: Eq. 1's C and c of the root, or linear.
// Targets whose root curve is the same share a table and so a controller (Sec. 8).
struct RootCurve {
  float C = 1.0f;
  float c = 1.0f;
  bool linear = false;
  bool operator==(const RootCurve& o) const { return C == o.C && c == o.c && linear == o.linear; }
  float weight(float alpha) const;  // w_r (Eq. 1, via synthesis)
};

struct ActionTable {
  int motions = 0;
  int alpha_levels = 0;
  std::vector<std::string> motion_names;  // the core motions (clip names), index = motion
  std::vector<std::string> motion_roles;  // their roles ("walk", ...)
  RootCurve curve;
  std::vector<ActionEffect> effects;      // index = motion * alpha_levels + level (the action index)

  const ActionEffect& at(int action) const { return effects[static_cast<size_t>(action)]; }
};

// The root curve of a motion set's skeleton under BlendParams (C_lower, overrides, method).
RootCurve root_curve(const MotionSet& set, const BlendParams& blend);

// One footstep of a cyclic clip played with root weight w_r (the mean over the footsteps of its loop).
ActionEffect footstep_effect(const MotionClip& clip, float w_root, const std::string& source_name);

// The table for the given core clips, levels alpha = l * alpha_step for l < alpha_levels.
ActionTable tabulate_action_effects(const std::vector<const MotionClip*>& core, const RootCurve& curve,
                                    int alpha_levels, float alpha_step, const std::string& source_name);

// The table for a motion set: its core clips are the first clip of each role in quantization.core_roles.
// Throws InputError naming the set when a role has no clip or a core clip is not cyclic.
ActionTable tabulate_action_effects(const MotionSet& set, const Params& params);

// The core clips of a set (first clip of each role of quantization.core_roles), in that order.
std::vector<const MotionClip*> core_clips(const MotionSet& set, const QuantizationParams& q);

}  // namespace prep
