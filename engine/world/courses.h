// Random courses: scenarios made from a seed, for unattended evaluation on many situations at once
// (prep evaluate --random N --seed S). Course `index` of seed `seed` is the same scenario on every run and
// every machine: its random numbers come from our own generator (SplitMix64) seeded by (seed, index), never
// from the standard library's distributions, whose outputs differ between implementations.
//
// A course is laid out along a route, a polyline from the user's start through 0-2 waypoints to the goal,
// with the objects on the route in order. Units: metres, headings in radians about +Y (scenario.h). The
// distributions (U(a, b) uniform):
// - Orientation: the first leg's direction U(0, 360) degrees. The user starts at (0, 0) facing along the
//   first leg within U(-20, 20) degrees (65%), or anywhere all round U(-180, 180) (35%; such a start has
//   2 m more before whatever comes first, room to turn round).
// - Opponents (only when the set has a punch): 30% of the courses open with a fight, 1 opponent (65%) or
//   2 (35%), the first U(4, 7) m along the route, each off the route by U(-1, 1) m, facing back along it,
//   met with punch_left or punch_right (50/50 among those the set has). They come first because an
//   opponent walks in to attack at once and, while one still fights, it is the user's source of influence
//   whatever else lies on the way (world.h): an obstacle before it would be walked through unprepared.
// - Then 1-4 other objects (0-3 after a fight), each kind equally likely among those the set can act on:
//   ball (kick), bar (crawl), beam (duck), hurdle (jump). The first object's launch point (where its clip,
//   entered at T_p, starts: CourseOptions::reach before it) is U(3, 6) m along the route from the start,
//   the room a character needs to prepare from standing; from one object to the next along the route: close U(1.5, 3) m (35%),
//   medium U(3, 6) m (40%) or far U(6, 10) m (25%).
// - Sizes are those the built-in clips were made for (library::obstacle_of: the height of a bar's or
//   beam's underside or a hurdle's top, and its depth); a ball is 0.22 m across. Width: U(4.5, 6) m, the
//   route crossing it U(-0.8, 0.8) m from its middle: a character that strays up to 1.4 m off the route
//   still passes within the width, where the world makes an obstacle a source.
// - With CourseOptions::vary_sizes, other sizes (see there).
// - Obstacle headings: the route's direction there plus U(-30, 30) degrees. Balls lie U(-0.2, 0.2) m off
//   the route (the kick is launched along the character's facing, within 45 degrees of the ball).
// - Waypoints: none (55%), one (30%) or two (15%), each in a different gap of the route (before an object
//   or before the goal): the gap becomes U(2.5, 4) m to the waypoint, a bend of U(25, 75) degrees either
//   way, and U(3, 5) m on to the next object (room to turn and line up before it).
// - Goal: U(2.5, 5) m beyond the last object along the route.
// - auto: true (target motions launch unattended).
// An object whose footprint (an obstacle's width x depth, a ball's, an opponent's 0.6 m square) comes
// within 0.3 m of another's, within 1 m of the start, a waypoint or the goal, or whose bar crosses
// another leg of the route, is drawn again (a new heading and offset), 0.25 m further along the route each
// time, so no two objects overlap and the route crosses each obstacle once.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <glm/vec2.hpp>

#include "engine/world/scenario.h"
#include "engine/world/world.h"

namespace prep {

struct CourseOptions {
  std::uint64_t seed = 1;
  std::string motions = "builtin";  // the scenarios' "motions": "builtin" or a manifest path
  std::string params_file;          // the scenarios' Params file (resolved path), "" for the defaults
  // The target actions the motion set can act on (actions_of): object kinds needing any other are left out.
  std::vector<TargetAction> actions{TargetAction::Kick,  TargetAction::Crawl,     TargetAction::Duck,
                                    TargetAction::Jump,  TargetAction::PunchLeft, TargetAction::PunchRight};
  // m from each target action's launch point to its object (TargetMotion::reach, by TargetAction; reaches_of);
  // empty: 0 for every action.
  std::vector<float> reach;
  // Obstacles of varied sizes (the shipped sizes otherwise): width U(2, 6) m, the route crossing up to
  // 0.8 m from the middle but at least 0.9 m inside the ends; rail or board depth U(0.05, 0.2) m; height
  // U(lo, hi) from `heights` (by TargetAction: crawl, duck, jump; heights_of gives what a set can pass).
  // The shipped heights are also brought within `heights`, and a kind whose range is empty (lo > hi: its
  // clip passes none) is left out. Empty: no limits.
  bool vary_sizes = false;
  std::vector<glm::vec2> heights;
};

// The obstacle heights a world's motion set can pass (obstacle_fit.h), within the ranges courses draw from:
// bars 0.55-0.9 m, beams 1.0-1.4 m, hurdles 0.3-0.55 m, for the deepest rail or board (0.2 m). Indexed by
// TargetAction; (0, 0) for the others and for an action without a clip; lo > hi when the clip passes none.
std::vector<glm::vec2> heights_of(const WorldAssets& assets);

// The target actions a world's motion set has a clip for (TargetMotion::clip >= 0).
std::vector<TargetAction> actions_of(const WorldAssets& assets);
// Each target action's reach (TargetMotion::reach), indexed by TargetAction.
std::vector<float> reaches_of(const WorldAssets& assets);

// Course `index` (0-based) of the options' seed, named "random-<seed>-<index>". Throws std::invalid_argument
// when the options allow no object kind at all.
Scenario make_course(const CourseOptions& options, int index);
// Courses 0 .. count-1. Throws std::invalid_argument when count <= 0.
std::vector<Scenario> make_courses(const CourseOptions& options, int count);

// The straight route of a scenario: the user's start, then each goal point (waypoints, goal) in order.
std::vector<glm::vec2> course_route(const Scenario& scenario);
float polyline_length(const std::vector<glm::vec2>& points);

}  // namespace prep
