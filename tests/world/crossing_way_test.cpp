// The way across an obstacle: what stands beyond it, met from any side, as a user steering with the keys
// meets it (World::launch_room_short).
#include <doctest/doctest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "engine/world/clearance.h"
#include "engine/world/floor.h"
#include "engine/world/world.h"
#include "tests/world/builtin_assets.h"

using namespace prep;

namespace {

// A hurdle and, 1.2 m beyond it and turned 28 degrees to it, a bar; the user crosses both to a waypoint
// beyond and comes back over them to a goal behind its start.
std::string there_and_back(float back_x, float back_z) {
  char text[900];
  std::snprintf(text, sizeof text,
                "{\"auto\": true, \"characters\": [{\"position\": [-0.73, 0], \"heading\": 0, \"control\": \"user\"}], "
                "\"objects\": [{\"type\": \"hurdle\", \"action\": \"jump\", \"position\": [0.0, 5.0], \"heading\": 6.14, "
                "\"size\": [5.0, 0.45, 0.1]}, {\"type\": \"bar\", \"action\": \"crawl\", \"position\": [-0.29, 6.18], "
                "\"heading\": 33.9, \"size\": [5.0, 0.7, 0.1]}], \"goal\": [[1.94, 9.5], [%.2f, %.2f]]}",
                back_x, back_z);
  return text;
}

}  // namespace

TEST_CASE("crossing back over two close obstacles, the crawl keeps room from the hurdle jumped on the way out") {
  // On the way back the hurdle has been jumped (used) and lies 1.2 m beyond the bar at an angle. Its room
  // was not counted against the crawl, which was launched where the gap is narrow: the body crawled into the
  // hurdle's board and was pushed back under the bar's rail (8 frames up to 5 cm deep on each course).
  for (const glm::vec2 back : {glm::vec2(1.0f, -1.0f), glm::vec2(0.0f, -1.5f), glm::vec2(1.5f, -1.0f), glm::vec2(-0.5f, -1.0f)}) {
    const std::string text = there_and_back(back.x, back.y);
    CAPTURE(text);
    World world(parse_scenario(text, "there-and-back"), test::builtin_assets());
    ClearanceLog log(world);
    world.run_until_done(90.0f, 1.0f, [&](const World& w) { log.observe(w); });
    CHECK(world.goal_reached());
    int crawls = 0, jumps = 0;
    for (const LaunchRecord& l : world.launches()) {
      crawls += l.action == TargetAction::Crawl;
      jumps += l.action == TargetAction::Jump;
    }
    CHECK(crawls == 2);  // both crossed both ways
    CHECK(jumps == 2);
    CHECK(log.summary.object_frames == 0);
    CHECK(log.summary.min_object >= -clearance_metric::kObjectTolerance);
  }
}
