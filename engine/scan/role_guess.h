// What role a recorded take plays, from what the motion does and, as a hint, from its file name.
#pragma once

#include <optional>
#include <string>

#include "engine/motion/motion_set.h"
#include "engine/scan/motion_signals.h"

namespace prep {

// The role a file name says, from its words (split at anything not a letter): crawl, duck, jump/hop/leap,
// kick, punch/jab/cross/hook/box, turn, step, idle/stand, walk/run/jog; a side from left/right. A target
// word wins over a locomotion word ("run_jump" is a jump). nullopt when it says none of them.
std::optional<Role> role_from_name(const std::string& file_name);

struct MotionRole {
  Role role = Role::Walk;
  float strength = 0.0f;  // 0..1: how clearly the motion shows it
  std::string reason;     // what was measured, for the scan's table
};

// The role the motion in frames [first, last] shows, checked in this order:
//   crawl: the head down by 40% of standing height or more with a wrist within 30 cm of the floor, slowly;
//   jump: a flight of 0.15 s or more with the root 20 cm or more above its usual height;
//   duck: the head down by 20% or more, on the move, and back up;
//   kick: a foot 6 m/s or more faster than the body over the ground, once (not at every stride);
//   punch: a hand striking (hand_strikes) while the body moves under 1.5 m/s;
//   idle: the body moves under 0.25 m/s (median);
//   turn: the heading turns 60 degrees or more, at 15 degrees/s or more on average;
//   walk: anything else that moves.
MotionRole role_from_motion(const MotionSignals& s, int first, int last);

struct RoleGuess {
  Role role = Role::Walk;
  float confidence = 0.0f;  // 0.95 when name and motion agree; 0.6 for a name the motion does not show
  std::string evidence;
};

// The name wins when it names a role (a user names files on purpose); the motion decides otherwise.
RoleGuess guess_role(const std::string& file_name, const MotionSignals& s, int first, int last);

}  // namespace prep
