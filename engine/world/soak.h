// The soak: the world run for hours of simulated time as fast as it goes, under everything a user does to
// it, checked on every tick. Worlds of random courses (courses.h) hold the characters, users and opponents,
// until there are at least the number asked for; a course is regenerated once it is done or its time is up.
// Half the worlds' users have their goal moved every 2-6 s to a random point up to 6 m away. Every 10 s one
// tunable of the Params (any field of params.h, found through its JSON) is set to a new value that does
// not retrain the controller, and applied to every world live; every 10 minutes one that does, and the
// policy is retrained for it (the worlds whose motion graph it leaves alone get it at once, the others as
// their courses are regenerated). Each change starts again from the defaults, so the Params never drift.
//
// Checked on every tick, for every character:
//   a pose with no NaN or infinity; feet (heel and toe points) at most 1 cm below the floor; the root's
//   height within the set's clips' range widened by 0.3 m (obstacle fits lift or lower the body); alpha in
//   [0, 1]; a user that makes no progress toward its goal for 30 s (0.25 m closer than its best since)
//   is stuck.
// And the memory the heap holds at the end is within 1 MB of what it held after the first simulated minute.
// The last 3 minutes make no change that builds new assets, so every world is back on the defaults' by then.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "engine/world/world.h"

namespace prep {

struct SoakOptions {
  double hours = 1.0;
  int characters = 100;
  std::uint64_t seed = 1;
  std::string cache_dir;  // policies ("" = default_policy_cache_dir())
};

struct SoakViolations {
  std::int64_t bad_pose = 0;        // a NaN or infinity in a pose or position
  std::int64_t foot_below = 0;      // a heel or toe more than 1 cm below the floor
  std::int64_t root_height = 0;     // the root outside the set's range
  std::int64_t alpha_range = 0;     // alpha outside [0, 1]
  std::int64_t stuck = 0;           // a user without progress for 30 s
  std::int64_t memory = 0;          // the heap over 1 MB above the first minute's at the end
  std::int64_t total() const { return bad_pose + foot_below + root_height + alpha_range + stuck + memory; }
};

struct SoakPeriod {
  int hour = 0;                      // 1-based
  double simulated_s = 0.0;
  std::int64_t ticks = 0;            // world ticks (each world counts its own)
  std::int64_t character_ticks = 0;
  int courses = 0;                   // courses started
  int goals_moved = 0;
  int params_changes = 0;            // applied
  int params_refused = 0;            // a new value the Params loader refused (out of its range): skipped
  int retrains = 0;
  SoakViolations violations;
  double rss_mb = 0.0;               // resident, at the period's end
  double heap_mb = 0.0;              // allocated and not freed, at the period's end
  std::vector<std::string> first_violations;  // the first few, described
};

struct SoakReport {
  std::vector<SoakPeriod> hours;
  double heap_first_minute_mb = 0.0;  // allocated and not freed (the leak measure)
  double heap_end_mb = 0.0;
  double rss_first_minute_mb = 0.0;   // resident (reported: the allocator keeps freed pages)
  double rss_end_mb = 0.0;
  double wall_s = 0.0;
  int characters = 0;
  bool ok() const;
};

// `on_period` is called at the end of each simulated hour (and of a last, shorter one).
SoakReport run_soak(const SoakOptions& options, const std::function<void(const SoakPeriod&)>& on_period = {});

nlohmann::json soak_json(const SoakReport& report);

// One character's checks of the list above, stuck excepted, on the set's skeleton. Adds to `v`; returns a
// description of the first failing check ("" when none).
std::string check_character(const WorldCharacter& c, const MotionSet& set, glm::vec2 root_range, SoakViolations& v);

// The root heights (min, max) over a set's clips.
glm::vec2 root_height_range(const MotionSet& set);

// The process's resident memory, MB (Linux /proc/self/statm; 0 elsewhere).
double resident_mb();
// What the heap holds, allocated and not freed, MB (glibc's mallinfo2).
double heap_in_use_mb();

}  // namespace prep
