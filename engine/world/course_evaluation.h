// Measures of a run over a course (courses.h, or any scenario), observed tick by tick from the World, and
// their totals over many courses with the acceptance checks of prep evaluate --random.
//
// Per course (the user character only):
// - goal: reached, and when (s).
// - Per launch of the user: alpha at the launch and alpha when its launch point first came within 1 m
//   (LaunchRecord::alpha_at_launch, alpha_at_1m; the latter is -1, not measured, when the approach began
//   closer than 1 m, e.g. out of the previous object's clip). Objects never acted on (an object not used, an
//   opponent not defeated) are counted.
// - Kept preparation: for two consecutive launches of the user at things less than kKeptDistance apart
//   (the objects' positions, or the opponents' where they stood, at each launch), the lowest smoothed
//   alpha (WorldCharacter::alpha) on the ticks strictly between the two launch ticks.
// - Alpha with no source in range: on the ticks where the user is not in a target motion and its source
//   is not in range (WorldCharacter::source_in_range false), the mean and median of its alpha. An episode
//   of these begins when the user comes out of range or out of a target motion; its relaxation time is
//   from there until alpha is below kRelaxedAlpha (0 if it already is). An episode that ends (a source
//   comes in range, or the run ends) before that has no time and is counted as unrelaxed. The first
//   stretch of the run, before any source was in range, is no episode: nothing was there to relax from.
// - Path ratio: the length of the user's root path on the floor up to the tick the goal is reached,
//   over the straight route (start -> each waypoint -> goal) less the goal radius (the goal counts as
//   reached on its edge, so walking straight in measures at least 1). Waypoints passed at a distance can
//   make it slightly below 1. Undefined (NaN) when the goal is not reached.
// - Circling: a visit to the current waypoint or goal (the last goal after it is reached) begins when the
//   user comes within kCirclingRadius of it and ends when the user is farther than kCirclingLeave from it
//   or it changes (a waypoint passed): a character orbiting on the edge of the circle, in and out of it
//   (seen at waypoints after a fight), makes one visit, not many short ones. The |heading change| of the
//   ticks of a visit is summed, and a visit whose sum exceeds 360 degrees counts as circling: the seconds
//   of such visits. The heading is averaged over the last kHeadingWindow seconds first: the pelvis (the
//   root) swings its yaw a few degrees either way in every stride, some 15 degrees a second summed while
//   walking straight, which over a long visit would add up to a circle that is not there.
// - Weaving: the user's turning clips (role TurnLeft or TurnRight) as they play, tick by tick. A reversal
//   is a turn clip beginning to play the other way from the last turn clip (whatever walked between; a
//   target motion forgets the last one). A course weaves when kWeaveReversals reversals fall within
//   kWeaveWindow seconds: left, right, left again in three seconds is a zigzag, not a route's turns. At
//   most kWeavePercent of the courses may weave.
// - Swerving (reported beside the checks): an approach is the run of ticks with one source (object or
//   opponent) while the user is not in a target motion; it counts once the source has come within
//   kSwerveAheadDeg of the facing. It swerves when the source's launch point (WorldCharacter::source) is
//   then more than kSwerveDeg off the facing while the point is still more than kSwerveNear ahead along the
//   approach: the character swung out from a source it was walking up to.
// - Clearance (clearance.h), every character: the frames on which a body is more than 1 cm inside an
//   object or two bodies overlap by more than 2 cm, the nearest approach to an object and between bodies
//   with who and what, and per launch of the user the nearest approach while its target motion played.
// A run (evaluate_course) lasts until the goal is reached and no character plays a target motion, plus
// kRelaxSeconds (relaxing at the goal is measured), and at most kBaseSeconds + kSecondsPerMetre per metre
// of straight route.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <glm/vec2.hpp>
#include <nlohmann/json.hpp>

#include "engine/world/clearance.h"
#include "engine/world/scenario.h"
#include "engine/world/world.h"

namespace prep {

// The constants that define the measures and the acceptance (fixed, like metric:: in evaluation.h).
namespace course_metric {
constexpr float kKeptDistance = 3.0f;      // m: two launches this close keep preparation between them
constexpr float kRelaxedAlpha = 0.1f;      // alpha below this is relaxed
constexpr float kCirclingRadius = 2.0f;    // m around the current waypoint or goal: a visit begins within ...
constexpr float kCirclingLeave = 3.0f;     // m: ... and ends beyond this
constexpr float kCirclingTurnDeg = 360.0f; // a visit turning more than this is circling
constexpr float kHeadingWindow = 1.0f;     // s: the heading is averaged over this (about a gait cycle)
constexpr int kWeaveReversals = 3;         // this many reversals of the turning ...
constexpr float kWeaveWindow = 3.0f;       // ... within this many seconds are weaving
constexpr int kWeavePercent = 2;           // acceptance: at most this percentage of the courses weaving
constexpr float kSwerveAheadDeg = 45.0f;   // an approach counts once its source is within this of the facing
constexpr float kSwerveDeg = 60.0f;        // it swerves when the source is then more than this off ...
constexpr float kSwerveNear = 1.0f;        // m: ... while its launch point is farther than this along the approach
constexpr float kRelaxSeconds = 2.5f;      // s a run goes on after the goal and the last target motion
constexpr float kBaseSeconds = 12.0f;      // s: the longest run is this ...
constexpr float kSecondsPerMetre = 2.5f;   // ... plus this per metre of straight route
constexpr float kLaunchAlpha = 0.85f;      // acceptance: alpha at launch at least this ...
constexpr float kLaunchFraction = 0.95f;   // ... on this fraction of the launches
constexpr float kAlpha1m = 0.5f;           // alpha 1 m before the launch point at least this ...
constexpr float kAlpha1mFraction = 0.90f;  // ... on this fraction of the launches where it was measured
constexpr float kGoalFraction = 0.98f;     // goal reached on this fraction of the courses
constexpr float kPathMedian = 1.15f;       // path ratio median at most this ...
constexpr float kPathP95 = 1.5f;           // ... and its 95th percentile at most this
constexpr float kNoSourceMedian = 0.1f;    // median alpha with no source in range at most this
}  // namespace course_metric

struct CourseLaunch {
  TargetAction action = TargetAction::Kick;
  float time = 0;             // s
  int tick = 0;               // observed frame (index into CourseEvaluation::alpha)
  int object = -1;            // the object, or
  int target_character = -1;  // the opponent character, launched at (-1: none)
  glm::vec2 at{0.0f};         // where that stood at the launch (the user's position when neither)
  float alpha_at_launch = 0;
  float alpha_at_1m = -1;     // -1: not measured
  float min_clearance = 0;    // m: the nearest approach while its target motion played (LaunchClearance)
  float strike_gap = 0;       // m: a kick's foot to the ball's surface at the strike (NaN: not struck)
  float slide_forward = 0, slide_side = 0;  // m: LaunchRecord's
  float turn = 0;                           // rad: LaunchRecord's
};

struct KeptPreparation {
  int first = 0, second = 0;  // indices into CourseEvaluation::launches
  float distance = 0;         // m between what they were launched at
  float min_alpha = 0;        // the lowest alpha between the two launch ticks (exclusive)
};

struct CourseEvaluation {
  std::string name, description;
  float seconds = 0;                 // run length
  bool reached_goal = false;
  float goal_time = -1;              // s; -1 when not reached
  float route_length = 0;            // m: start -> waypoints -> goal
  float path_length = 0;             // m: walked until the goal was reached (or the run ended)
  float path_ratio = 0;              // NaN when the goal was not reached
  int objects = 0, objects_unused = 0;
  std::vector<CourseLaunch> launches;         // the user's, in order
  std::vector<KeptPreparation> kept;
  std::vector<float> no_source_alpha;         // the user's alpha on every tick with no source in range
  std::vector<float> relax_times;             // s, per episode that relaxed
  int unrelaxed_episodes = 0;
  float circling_seconds = 0;
  int circling_visits = 0;
  float max_visit_turn_deg = 0;               // the largest turn of any visit
  int turn_reversals = 0;                     // weaving (above)
  int most_reversals_in_window = 0;           // the most within any kWeaveWindow
  int approaches = 0, swerving_approaches = 0;  // swerving (above)
  float widest_approach_deg = 0;              // the largest bearing of a source after it came ahead
  std::vector<float> times, alpha;            // the user's smoothed alpha per observed frame
  ClearanceSummary clearance;                 // of every character (ClearanceLog)

  float no_source_mean() const;    // NaN without such ticks
  float no_source_median() const;
};

// Alpha with no source in range on its own (above), fed one tick at a time: whether the user is out of
// range (no source in range and not in a target motion) and its alpha.
class NoSourceMeter {
 public:
  NoSourceMeter(bool out, float alpha);  // the first tick
  void add(float time, bool out, float alpha);
  void finish();  // an episode under way ends unrelaxed
  const std::vector<float>& alpha() const { return alpha_; }       // on the ticks out of range
  const std::vector<float>& relax_times() const { return relax_; }  // s, per episode that relaxed
  int unrelaxed() const { return unrelaxed_; }

 private:
  std::vector<float> alpha_, relax_;
  int unrelaxed_ = 0;
  bool was_out_;
  bool in_episode_ = false;  // an episode has not relaxed yet
  float episode_start_ = 0;
};

// The circling measure on its own (above), fed one tick at a time.
class CirclingMeter {
 public:
  CirclingMeter(float dt, float heading);  // the first tick's heading (radians)
  // One tick: the user's position and heading (radians, as the world gives it) and its current goal
  // point (`goal_index` tells one from the next).
  void add(glm::vec2 position, float heading, int goal_index, glm::vec2 goal_point);
  void finish();                                        // ends a visit under way
  float seconds() const { return seconds_; }            // of the visits that circled
  int visits() const { return visits_; }                // that circled
  float max_turn_deg() const { return max_turn_deg_; }  // the largest turn of any visit

 private:
  float dt_;
  float last_heading_;         // as given last tick
  float heading_;              // unwrapped (continuous over turns)
  std::vector<float> window_;  // the unwrapped heading over the last kHeadingWindow of ticks (a ring) ...
  size_t next_ = 0;
  double sum_;                 // ... their sum
  float smoothed_;             // ... and their mean
  int visit_goal_ = -1;        // the goal point of the visit under way, -1: none
  float visit_turn_ = 0;       // radians turned in it so far
  int visit_ticks_ = 0;
  float seconds_ = 0, max_turn_deg_ = 0;
  int visits_ = 0;
};

// The weaving measure on its own (above), fed one tick at a time: the time, and the turning clip playing
// (+1 to the left, -1 to the right, 0 none) or a target motion.
class WeavingMeter {
 public:
  void add(float time, int turning, bool in_target);
  int reversals() const { return static_cast<int>(reversal_times_.size()); }
  int most_in_window() const { return most_in_window_; }

 private:
  int last_turning_ = 0;
  std::vector<float> reversal_times_;
  size_t window_start_ = 0;  // the first reversal within kWeaveWindow of the latest
  int most_in_window_ = 0;
};

// The swerving measure on its own (above), fed one tick at a time: which source the user has (-1: none, or
// in a target motion), where its launch point is and how far along the approach, and the user's position
// and heading (radians, as the world gives it).
class SwerveMeter {
 public:
  void add(int source, glm::vec2 launch_point, float to_launch, glm::vec2 position, float heading);
  void finish();  // ends the approach under way
  int approaches() const { return approaches_; }
  int swerves() const { return swerves_; }
  float widest_deg() const { return widest_deg_; }

 private:
  int source_ = -1;
  bool ahead_ = false, swerved_ = false;  // of the approach under way
  int approaches_ = 0, swerves_ = 0;
  float widest_deg_ = 0;
};

class CourseRecorder {
 public:
  explicit CourseRecorder(const World& world);  // the world's current state is the first frame
  void observe(const World& world);             // after every World::step()
  CourseEvaluation finish(const World& world) const;

 private:
  CourseEvaluation e_;
  size_t launches_seen_ = 0;
  glm::vec2 last_position_{0.0f};
  NoSourceMeter no_source_;
  CirclingMeter circling_;
  WeavingMeter weaving_;
  SwerveMeter swerve_;
  ClearanceLog clearance_;
};

// The longest run for a course (the header's limit), s.
float course_time_limit(const Scenario& scenario);
// Runs the course headless with auto launches until the end condition above.
CourseEvaluation evaluate_course(const Scenario& scenario, std::shared_ptr<const WorldAssets> assets);
// Runs every course on up to `threads` threads (a World per course, the assets shared read-only); the
// results are in the courses' order whatever the threads.
std::vector<CourseEvaluation> evaluate_courses(const std::vector<Scenario>& courses, std::shared_ptr<const WorldAssets> assets,
                                               int threads);

// --- Totals over courses ------------------------------------------------------------------------------

// Percentile p (0-100) with linear interpolation between the closest ranks; NaN for no values.
float percentile(std::vector<float> values, float p);

struct CourseCheck {
  std::string name;     // "goal reached", ...
  std::string measure;  // what was measured, in words with the figure
  bool pass = false;
};

struct CourseTotals {
  int courses = 0, goals = 0;
  int launches = 0, launches_prepared = 0;   // alpha at launch >= kLaunchAlpha
  int measured_1m = 0, prepared_1m = 0;      // alpha at 1 m measured, and >= kAlpha1m
  int objects = 0, objects_unused = 0;
  float path_median = 0, path_p95 = 0;       // over the courses that reached the goal
  float no_source_median = 0, no_source_mean = 0;  // over every no-source tick of every course
  float relax_median = 0, relax_max = 0;     // over every relaxed episode
  int unrelaxed_episodes = 0;
  int circling_courses = 0;
  float circling_seconds = 0;
  int weaving_courses = 0;
  float reversals_per_minute = 0;            // turn reversals over every course's run time
  int approaches = 0, swerving_approaches = 0;  // swerving, reported beside the checks
  int kept_pairs = 0;
  float kept_min = 0, kept_median = 0;       // of the pairs' minima (NaN without pairs)
  // Clearance (clearance.h), reported beside the checks: the courses with a body more than 1 cm inside an
  // object, or two bodies overlapping more than 2 cm, on any frame.
  int penetrating_courses = 0, overlapping_courses = 0;
  float min_object_clearance = 0, min_character_clearance = 0;  // m, over every course
  std::string min_object_what, min_character_what;              // where (course name and what)
  std::vector<CourseCheck> checks;
  bool pass() const;
};

CourseTotals course_totals(const std::vector<CourseEvaluation>& courses);

// JSON: {"courses": [per course], "total": {..., "checks": {"<name>": {"pass", "measure"}}, "pass"}}.
nlohmann::json course_json(const CourseEvaluation& e);
nlohmann::json course_totals_json(const CourseTotals& t);

}  // namespace prep
