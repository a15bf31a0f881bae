// A course made playable by a motion set: what the set has no clip for is left out, an obstacle its clip
// cannot pass at the course's height is brought to the nearest height it passes, and a set that kicks gets
// a ball past the last object. Each change is said in words, for the front end to show.
#pragma once

#include <string>
#include <vector>

#include "engine/world/scenario.h"
#include "engine/world/world.h"

namespace prep {

struct SetCourse {
  Scenario scenario;
  std::vector<std::string> changes;  // "left out the bar at (0.0, 3.5): this set has no crawl", ...
};

// `course` (for example assets/scenarios/obstacles.json) on `assets`' motion set; the scenario's "motions"
// becomes `motions` (the set's manifest path).
SetCourse course_for_set(const Scenario& course, const WorldAssets& assets, const std::string& motions);

}  // namespace prep
