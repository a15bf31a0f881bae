// The effect of an action a = {m, alpha} on where the character is: its root displacement in the
// character's frame, its turn and its duration, per core motion m and preparation level.
//
// Tabulated from the motion data through the synthesis pipeline's trajectory adjustment: the clip's root
// travel is replayed frame by frame with advance_root (Eq. 3-4), whose displacement shrinks by (1 - w_r)
// as the root's Eq. 1 weight w_r rises with alpha; the heading follows the locomotion (blend_root_rotation
// keeps it), so a turning motion still turns when prepared. Nothing here is typed in by hand.
//
// One action plays QuantizationParams::footsteps_per_action footsteps of its clip: the clip's loop is cut
// into as many equal parts as it has footsteps (touchdowns in its contacts, at least two: one gait cycle),
// consecutive parts are grouped by footsteps_per_action, each group measured in the frame the character
// had at its start, and the effect is their mean (left and right steps differ slightly).
//
// Why a gait cycle (2 footsteps) by default, not one footstep. (1) The hierarchical motion graph passes
// from one cyclic core node to another at its loop, once per cycle (Sec. 4.1): an action is one play of a
// node. (2) With the paper's discount of 0.3 the learner sees about one action ahead. Inside the source
// radius alpha is forced to 1 after every action (reward.h), so to move on the character pays Eq. 16 twice
// per action (1 -> 0.8 -> 1: 0.048) and gains Eq. 15's 0.15 m^-1 of approach: a footstep at alpha 0.8
// (0.195 m in the built-in walk, 0.029) does not pay for it and the learned policy stops short of the
// goal forever; a cycle (0.39 m, 0.059) does. (3) A cycle of a built-in turn turns 45 degrees, one
// theta_g bin of Table I.
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
  float inv_chord2 = 0.0f;  // 1 / (forward^2 + left^2), 0 for an action that does not move (ditto)
  void precompute();        // the three above from forward, left and turn
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

// The footsteps of a cyclic clip's loop: two per gait cycle (see footsteps_in_loop in the .cpp).
int footsteps_in_loop(const MotionClip& clip);

// One action of a cyclic clip played with root weight w_r: `footsteps` footsteps (at most the loop's; at
// least one), the mean over the loop. Throws InputError naming the source for a clip without a loop.
ActionEffect action_effect(const MotionClip& clip, float w_root, int footsteps, const std::string& source_name);

// The table for the given core clips, levels alpha = l * alpha_step for l < alpha_levels.
ActionTable tabulate_action_effects(const std::vector<const MotionClip*>& core, const RootCurve& curve,
                                    int alpha_levels, float alpha_step, int footsteps_per_action,
                                    const std::string& source_name);

// The table for a motion set and its core clips (core_clips below). Throws InputError naming the set when
// an entry names no clip or a core clip is not cyclic.
ActionTable tabulate_action_effects(const MotionSet& set, const Params& params);

// The core clips of a set, in the order of quantization.core_roles: an entry that is a role name picks the
// set's first cyclic clip of that role; any other entry must be the name of a cyclic locomotion clip.
// Empty core_roles (the default) means the set's own: default_core_clips.
std::vector<const MotionClip*> core_clips(const MotionSet& set, const QuantizationParams& q);

// A slow walk is one whose loop covers ground at most this fraction of the walk's speed.
constexpr float kSlowWalkRatio = 0.8f;

// The set's own core motions: its first cyclic walk, left turn and right turn, then its slow walk when it
// has one (the slowest other cyclic walk, at most kSlowWalkRatio of the walk's speed over its loop).
// Throws InputError naming the set when a walk or a turn has no cyclic clip.
std::vector<const MotionClip*> default_core_clips(const MotionSet& set);

// Ground speed over a cyclic clip's loop, m/s.
float loop_speed(const MotionClip& clip);

}  // namespace prep
