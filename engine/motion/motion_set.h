// A motion set (Sec. 4): clips on one reference skeleton, each with its role, loop range, the first frame
// of its target movement T_t, and its per-frame foot contacts. Loaded from a manifest (JSON) or built in
// memory (the built-in library).
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "engine/motion/body_map.h"
#include "engine/motion/center_of_mass.h"
#include "engine/motion/clip.h"
#include "engine/motion/contacts.h"
#include "engine/params/params.h"

namespace prep {

enum class Role { Idle, Walk, TurnLeft, TurnRight, StepLeft, StepRight, Crawl, Duck, Jump, PunchLeft, PunchRight, Kick };
constexpr int kRoleCount = 12;

const char* role_name(Role role);                      // "idle", "walk", "turn_left", ..., "kick"
std::optional<Role> parse_role(std::string_view name);
bool is_locomotion(Role role);                         // idle, walk, turns, side-steps: the graph's core nodes

struct MotionClip {
  Clip clip;                    // on the set's reference skeleton, cropped to the manifest's frame range
  Role role = Role::Walk;
  bool cyclic = false;          // true for locomotion with a loop range
  int loop_first = 0;           // loop range in clip frames (inclusive); frame loop_last joins loop_first
  int loop_last = -1;
  int target_frame = -1;        // T_t for target motions (clip frames), -1 for locomotion
  float steer_rad_per_s = 0.0f; // the manifest's steer_deg_per_s (steer.h), in rad/s; 0 for a clip as recorded
  std::string source_file;      // where it came from (a BVH path, or "builtin")
  std::string derived_from;     // the clip the loader made it from (a held stand, held_stand.h); empty for a take
  std::vector<FrameContacts> contacts;  // per frame, from detect_contacts
};

struct MotionSet {
  std::string name;
  std::string manifest_path;    // empty for a set built in memory
  std::shared_ptr<const Skeleton> skeleton;
  BodyMap body;
  MassModel mass;
  std::vector<MotionClip> clips;
  std::vector<std::string> warnings;  // non-fatal findings while loading (e.g. a BVH whose Frames: count is off)

  int find(std::string_view clip_name) const;  // index or -1
};

// Loads a manifest and its BVH clips. Throws InputError naming the manifest (and field) or the BVH (and line).
//
// Manifest schema (JSON):
// {
//   "name": "daz43",
//   "folder": "../shared/mocap/daz43",     // relative to the repository root, or absolute
//   "unit_scale": 0.01,                    // file units -> metres (or "units": "centimetres"|"inches"|"cmu"|"metres")
//   "skip_first_frame": true,              // daz43: frame 0 is the converter's reference pose
//   "reference": "walk_02_01.bvh",         // the clip whose skeleton is the set's (default: the first clip)
//   "floor": "auto",                       // default floor rule for every clip (see below)
//   "description": "...",                  // free text (also "notes" on a clip)
//   "clips": [
//     {"name": "walk", "file": "walk_02_01.bvh", "role": "walk", "frames": [1, 343], "loop": [10, 140]},
//     {"name": "jump", "file": "jump_forward_13_11.bvh", "role": "jump", "frames": [100, 330], "t_t": 237}
//   ]
// }
// "frames", "loop" and "t_t" count the file's frames (inclusive ranges); clips from other performers (same
// joint names, other offsets) play on the reference skeleton: rotations kept, root translation scaled by
// the leg-length ratio (thigh + shin, both legs averaged).
// "floor" per clip (or for the whole manifest): a number is the floor's height in metres in the clip's
// scaled coordinates, subtracted from the root; "auto" (the default) estimates it from the feet: per frame
// the lowest of the heel (ankle joint) and toe-tip heights of both feet; per 1-second window the 10th
// percentile of that, placed at the window's centre; the floor follows these values piecewise-linearly
// through the clip, the first and last segments extended to its ends (captured floors drift by several cm
// over a clip, steadily); a clip shorter than 1.5 windows gets one constant floor.
// Unknown fields and wrong types are errors naming the manifest and the field.
MotionSet load_motion_set(const std::string& manifest_path, const Params& params);
// The same from the manifest's text; `manifest_path` names it in errors and locates a relative "folder".
MotionSet parse_motion_set(const std::string& text, const std::string& manifest_path, const Params& params);

// The floor rule "auto" above: the floor's height under each frame of a clip (in its own coordinates).
std::vector<float> estimate_floor_heights(const Clip& clip, const BodyMap& body);

// Fills the derived data (body map, mass model, contacts) of a set whose skeleton and clips are set.
void finalize_motion_set(MotionSet& set, const Params& params);

// The first cyclic clip of the set with role `role` (-1 if none).
int find_cyclic_clip(const MotionSet& set, Role role);

}  // namespace prep
