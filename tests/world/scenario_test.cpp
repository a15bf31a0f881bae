#include "engine/world/scenario.h"

#include <doctest/doctest.h>

#include <cmath>
#include <string>

#include "engine/util/error.h"
#include "tests/support/paths.h"

using namespace prep;

namespace {

// The message of the InputError that parsing `text` throws ("" if none).
std::string error_of(const std::string& text) {
  try {
    parse_scenario(text, "bad.json");
  } catch (const InputError& e) {
    CHECK(e.file() == "bad.json");
    return e.what();
  }
  return "";
}

bool mentions(const std::string& message, const std::string& part) { return message.find(part) != std::string::npos; }

const char* kMinimal = R"({"characters": [{"position": [1, 2], "control": "user"}], "goal": [3, 4]})";

}  // namespace

TEST_CASE("the three scenarios of Sec. 7.2 load") {
  for (const char* name : {"kick", "fight", "obstacles"}) {
    const Scenario s = load_scenario(test::repo() + "/assets/scenarios/" + name + ".json");
    CHECK(s.name == name);
    CHECK(s.auto_launch);
    CHECK(s.motions == "builtin");
    REQUIRE(s.user() >= 0);
    CHECK_FALSE(s.goal.empty());
    CHECK_FALSE(s.objects.empty());
  }
  const Scenario kick = load_scenario(test::repo() + "/assets/scenarios/kick.json");
  REQUIRE(kick.objects.size() == 1);
  CHECK(kick.objects[0].type == ObjectType::Ball);
  CHECK(kick.objects[0].action == TargetAction::Kick);
  // The ball is the goal (Sec. 7.2: goal and source of influence are the same).
  CHECK(kick.goal.back().x == doctest::Approx(kick.objects[0].position.x));
  CHECK(kick.goal.back().y == doctest::Approx(kick.objects[0].position.y));

  const Scenario fight = load_scenario(test::repo() + "/assets/scenarios/fight.json");
  int opponents = 0;
  for (const auto& o : fight.objects) opponents += o.type == ObjectType::Opponent ? 1 : 0;
  CHECK(opponents >= 1);

  const Scenario course = load_scenario(test::repo() + "/assets/scenarios/obstacles.json");
  bool crawl = false, duck = false, jump = false;
  for (const auto& o : course.objects) {
    crawl = crawl || (o.type == ObjectType::Bar && o.action == TargetAction::Crawl);
    duck = duck || (o.type == ObjectType::Beam && o.action == TargetAction::Duck);
    jump = jump || (o.type == ObjectType::Hurdle && o.action == TargetAction::Jump);
  }
  CHECK(crawl);
  CHECK(duck);
  CHECK(jump);
}

TEST_CASE("a minimal scenario takes the defaults") {
  const Scenario s = parse_scenario(kMinimal, "scenarios/min.json");
  CHECK(s.name == "min");
  CHECK_FALSE(s.auto_launch);
  CHECK(s.motions == "builtin");
  CHECK(s.params_file.empty());
  REQUIRE(s.characters.size() == 1);
  CHECK(s.characters[0].position.x == 1.0f);
  CHECK(s.characters[0].position.y == 2.0f);
  CHECK(s.characters[0].heading == 0.0f);
  REQUIRE(s.goal.size() == 1);
  CHECK(s.goal[0].x == 3.0f);
  CHECK(s.goal[0].y == 4.0f);
}

TEST_CASE("headings are degrees in the file and radians in the engine, and waypoints keep their order") {
  const Scenario s = parse_scenario(R"({
    "characters": [{"position": [0, 0], "heading": 90, "control": "user"},
                   {"position": [0, 5], "heading": 180, "control": "opponent", "action": "punch_left"}],
    "objects": [{"type": "hurdle", "position": [0, 3], "heading": -45, "size": [2, 0.4, 0.1]},
                {"type": "opponent", "action": "punch_left", "position": [2, 2]}],
    "goal": [[0, 2], [0, 4], [1, 6]],
    "params": "p.json"})",
                                    "dir/x.json");
  CHECK(s.characters[0].heading == doctest::Approx(std::acos(-1.0) / 2));
  CHECK(s.characters[1].control == Control::Opponent);
  CHECK(s.characters[1].action == TargetAction::PunchLeft);
  CHECK(s.objects[0].action == TargetAction::Jump);  // the type's default
  CHECK(s.objects[0].heading == doctest::Approx(-std::acos(-1.0) / 4));
  CHECK(s.objects[0].size.y == doctest::Approx(0.4f));
  CHECK(s.objects[1].action == TargetAction::PunchLeft);
  REQUIRE(s.goal.size() == 3);
  CHECK(s.goal[2].x == 1.0f);
  CHECK(s.goal[2].y == 6.0f);
  CHECK(s.params_file == "dir/p.json");  // relative to the scenario's folder
}

TEST_CASE("bad scenarios are refused with the file and the field") {
  CHECK(mentions(error_of("{"), "not valid JSON"));
  CHECK(mentions(error_of(R"({"characters": [{"position": [0, 0], "control": "user"}]})"), "'goal' is missing"));
  CHECK(mentions(error_of(R"({"goal": [0, 1]})"), "'characters' is missing"));
  const std::string unknown_type = error_of(R"({"characters": [{"position": [0, 0], "control": "user"}],
      "objects": [{"type": "wall", "position": [0, 1], "size": [1, 1, 1]}], "goal": [0, 2]})");
  CHECK(mentions(unknown_type, "bad.json"));
  CHECK(mentions(unknown_type, "objects[0].type"));
  CHECK(mentions(unknown_type, "wall"));
  CHECK(mentions(error_of(R"({"characters": [{"position": "here", "control": "user"}], "goal": [0, 2]})"),
                 "'characters[0].position' must be a floor point"));
  CHECK(mentions(error_of(R"({"characters": [{"position": [0, "a"], "control": "user"}], "goal": [0, 2]})"),
                 "'characters[0].position[1]' must be a number, not string"));
  CHECK(mentions(error_of(R"({"characters": [{"position": [0, 0], "control": "user"}], "goal": [0, 2], "auto": "yes"})"),
                 "'auto' must be true or false"));
  CHECK(mentions(error_of(R"({"characters": [{"position": [0, 0], "control": "user"}], "goal": [0, 2], "speed": 3})"),
                 "'speed' is not a known field"));
  CHECK(mentions(error_of(R"({"characters": [{"position": [0, 0], "control": "robot"}], "goal": [0, 2]})"),
                 "'characters[0].control' must be \"user\" or \"opponent\""));
  CHECK(mentions(error_of(R"({"characters": [{"position": [0, 0], "control": "opponent"}], "goal": [0, 2]})"),
                 "exactly one character"));
  CHECK(mentions(error_of(R"({"characters": [{"position": [0, 0], "control": "user"}],
      "objects": [{"type": "bar", "action": "jump", "position": [0, 1], "size": [1, 1, 1]}], "goal": [0, 2]})"),
                 "\"jump\" is not an action for a bar"));
  CHECK(mentions(error_of(R"({"characters": [{"position": [0, 0], "control": "user"}],
      "objects": [{"type": "bar", "position": [0, 1]}], "goal": [0, 2]})"),
                 "'objects[0].size' is missing"));
  CHECK(mentions(error_of(R"({"characters": [{"position": [0, 0], "control": "user"}],
      "objects": [{"type": "bar", "position": [0, 1], "size": [1, -1, 1]}], "goal": [0, 2]})"),
                 "'objects[0].size[1]' must be positive"));
  CHECK(mentions(error_of(R"({"characters": [{"position": [0, 0], "control": "user"}], "goal": [[0, 2], [1]]})"),
                 "'goal[1]' must be a floor point"));
  CHECK(mentions(error_of(R"({"characters": [{"position": [0, 0], "control": "user"}], "goal": [0, 1e999]})"),
                 "not valid JSON"));
  CHECK_THROWS_AS(load_scenario(test::repo() + "/assets/scenarios/no_such_file.json"), InputError);
}

TEST_CASE("scenario numbers beyond a million metres or degrees are refused with the file and the field") {
  // 1e39 is finite as a double but infinite as the float it was stored in, and scenario_json wrote it back as
  // null (found by the scenario fuzz target; the input is in its corpus).
  CHECK_THROWS_WITH_AS(load_scenario(test::repo() + "/tests/fuzz/corpus/scenario/far_away.json"),
                       doctest::Contains("far_away.json: 'characters[0].position[0]' is 1e+39: more than a million (metres or degrees) either way"),
                       InputError);
  CHECK(mentions(error_of(R"({"characters": [{"position": [0, 0], "heading": -1e7, "control": "user"}], "goal": [0, 2]})"),
                 "'characters[0].heading' is -10000000.0: more than a million"));
  const Scenario edge = parse_scenario(R"({"characters": [{"position": [1e6, -1e6], "control": "user"}], "goal": [0, 2]})", "edge.json");
  CHECK(edge.characters[0].position.x == 1e6f);
}
