// The generators of the built-in library, one function per clip family. Each returns a finished clip on
// builtin_skeleton() with its role, loop range and T_t; builtin.cpp assembles them into the MotionSet.
#pragma once

#include <string>
#include <vector>

#include "engine/library/draft.h"
#include "engine/motion/motion_set.h"

namespace prep::library {

constexpr float kLibraryFps = 60.0f;  // the engine's tick (RuntimeParams::fixed_dt = 1/60)

struct GeneratedClip {
  Clip clip;
  Role role = Role::Walk;
  bool cyclic = false;
  int loop_first = 0, loop_last = -1;
  int target_frame = -1;
  RealizeReport report;
};

// An obstacle the clip is made for, in the clip's coordinates: a bar/beam/hurdle across the path (along
// x) between z_near and z_far. Under a bar or beam every body point between z_near and z_far stays below
// `clearance`; over a hurdle every foot point between them stays above it.
struct Obstacle {
  float z_near = 0, z_far = 0;
  float height = 0;     // of the bar, beam or hurdle top
  float clearance = 0;  // the design limit the tests check
  bool over = false;    // true: a hurdle to clear; false: a bar or beam to pass under
};

// Cuts frames [first, first + count) of a padded clip.
Clip crop(const Clip& clip, int first, int count);

// Locomotion (locomotion.cpp).
GeneratedClip make_walk(const std::string& name, float speed, float amplitude);
GeneratedClip make_turn(const std::string& name, bool left);
GeneratedClip make_side_step(const std::string& name, bool left);
GeneratedClip make_idle(const std::string& name);

// Target motions, each: walk in, the action, walk out (Fig. 4's three parts).
GeneratedClip make_crawl(const std::string& name, Obstacle* bar);     // crawl.cpp
GeneratedClip make_duck(const std::string& name, Obstacle* beam);     // duck.cpp
GeneratedClip make_jump(const std::string& name, Obstacle* hurdle);   // jump.cpp
GeneratedClip make_punch(const std::string& name, bool left);         // strikes.cpp
GeneratedClip make_kick(const std::string& name);                     // strikes.cpp

// Every clip of the library in a fixed order (names are the clip names in the manifest).
std::vector<GeneratedClip> make_all_clips();

// The obstacle each target clip was made for, by clip name (empty height if none).
Obstacle obstacle_of(const std::string& clip_name);

}  // namespace prep::library
