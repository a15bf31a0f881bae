// A course made playable by a motion set: left out, brought within reach, a ball added; each change said.
#include "engine/world/set_course.h"

#include <doctest/doctest.h>

#include "engine/world/courses.h"
#include "tests/support/paths.h"
#include "tests/world/builtin_assets.h"

using namespace prep;

namespace {

ScenarioObject set_course_obstacle(ObjectType type, TargetAction action, float z, float height) {
  ScenarioObject o;
  o.type = type;
  o.action = action;
  o.position = {0.0f, z};
  o.size = {4.0f, height, 0.1f};
  return o;
}

}  // namespace

TEST_CASE("a course on a set: what it has no clip for is left out, a height beyond its clip brought within it, a ball added") {
  // The built-in set without its crawl and with its jump: what a user's folder might give.
  const WorldAssets& all = *test::builtin_assets();
  WorldAssets assets = all;
  assets.targets[static_cast<size_t>(TargetAction::Crawl)].clip = -1;

  Scenario course = load_scenario(test::repo() + "/assets/scenarios/obstacles.json");
  course.objects.push_back(set_course_obstacle(ObjectType::Hurdle, TargetAction::Jump, 16.0f, 0.9f));  // far beyond any jump
  course.goal.back() = {0.0f, 18.0f};
  const SetCourse fitted = course_for_set(course, assets, "my_set.json");
  CHECK(fitted.scenario.motions == "my_set.json");
  // bar left out; beam and both hurdles kept, the tall one lowered to what the jump clears; a ball added.
  REQUIRE(fitted.scenario.objects.size() == 4);
  CHECK(fitted.scenario.objects[0].type == ObjectType::Beam);
  CHECK(fitted.scenario.objects[1].type == ObjectType::Hurdle);
  CHECK(fitted.scenario.objects[1].size.y == doctest::Approx(0.45f));  // the shipped height: passable, kept
  CHECK(fitted.scenario.objects[2].size.y < 0.9f);
  CHECK(fitted.scenario.objects[2].size.y <= heights_of(assets)[static_cast<size_t>(TargetAction::Jump)].y + 1e-6f);
  CHECK(fitted.scenario.objects[3].type == ObjectType::Ball);
  CHECK(fitted.scenario.objects[3].position == glm::vec2(0.0f, 18.0f));
  CHECK(fitted.scenario.goal.back().y == doctest::Approx(20.5f));
  REQUIRE(fitted.changes.size() == 3);
  CHECK(fitted.changes[0] == "left out the bar at (0.0, 3.5): this set has no crawl");
  CHECK(fitted.changes[1].find("the hurdle at (0.0, 16.0): lowered from 0.90 m to") == 0);
  CHECK(fitted.changes[2] == "added the ball at (0.0, 18.0): the set kicks");
  // The world takes it: every object is one its clips can pass.
  World world(fitted.scenario, test::builtin_assets());
  CHECK(world.objects().size() == 4);
}
