// The demo's engine side: the fixed step and the interpolated drawing, the scenario list, bad files, and
// the background work (first start, retraining after a Params change) that must never hold a frame up.
#include "app/demo/world_session.h"

#include <doctest/doctest.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <set>
#include <thread>

#include "engine/util/error.h"
#include "tests/support/paths.h"

using namespace prep;

namespace {

std::string scenario_path(const std::string& name) { return test::repo() + "/assets/scenarios/" + name + ".json"; }

demo::SessionOptions blocking() {
  demo::SessionOptions o;
  o.cache_dir = test::tmp_dir() + "/policy-cache";
  o.background = false;
  return o;
}

glm::vec3 drawn_root(const demo::WorldSession& s) {
  const render::Scene scene = s.scene(false);
  return scene.characters.at(static_cast<size_t>(s.world()->user())).joint_positions[0];
}

glm::vec3 engine_root(const demo::WorldSession& s) {
  return s.world()->characters()[static_cast<size_t>(s.world()->user())].pose.root_position;
}

}  // namespace

TEST_CASE("the picker lists the scenario files and leaves the Params file beside them out") {
  const auto list = demo::list_scenarios(demo::default_scenarios_dir());
  std::set<std::string> names;
  for (const auto& e : list) {
    names.insert(e.name);
    CHECK_FALSE(e.description.empty());
    // The Params files (controller*.json) beside the scenarios are not scenarios.
    CHECK(std::filesystem::path(e.path).filename().string().rfind("controller", 0) == std::string::npos);
  }
  for (const char* sec72 : {"fight", "kick", "obstacles"}) CHECK(names.count(sec72) == 1);
  // Sorted by name.
  for (size_t i = 1; i < list.size(); ++i) CHECK(list[i - 1].name <= list[i].name);
}

TEST_CASE("fixed step: whole ticks per frame, the drawing interpolates between the last two ticks") {
  demo::WorldSession s(blocking());
  s.open(scenario_path("obstacles"));
  REQUIRE(s.phase() == demo::SessionPhase::Running);
  const double dt = s.params().runtime.fixed_dt;
  s.advance(2.0);  // walking by now; a frame this slow runs kMaxTicksPerFrame ticks, the rest is dropped
  CHECK(s.ticks_last_advance() == demo::WorldSession::kMaxTicksPerFrame);
  CHECK(s.blend() < 1.0f);
  CHECK(s.advance(dt) == 1);
  const glm::vec3 a = engine_root(s);
  CHECK(s.advance(dt) == 1);
  const glm::vec3 b = engine_root(s);
  REQUIRE(glm::length(b - a) > 1e-3f);  // it moves
  // Right after a tick the drawing shows the tick before (it lags by one tick at most) ...
  CHECK(s.blend() == doctest::Approx(0.0f).epsilon(1e-6));
  CHECK(glm::length(drawn_root(s) - a) < 1e-5f);
  // ... and half a tick later it is half-way to the last one.
  CHECK(s.advance(0.5 * dt) == 0);
  CHECK(s.blend() == doctest::Approx(0.5f).epsilon(1e-4));
  CHECK(glm::length(drawn_root(s) - 0.5f * (a + b)) < 1e-4f);
  // Frames of 2.5 ticks alternate 2 and 3 ticks: no time is lost or made up.
  const float t0 = s.world()->time();
  int ticks = 0;
  for (int i = 0; i < 4; ++i) ticks += s.advance(2.5 * dt);
  CHECK(ticks == 10);
  CHECK(s.world()->time() - t0 == doctest::Approx(10 * dt).epsilon(1e-3));
  // Paused: no ticks; time_scale halves the ticks.
  s.paused = true;
  CHECK(s.advance(1.0) == 0);
  s.paused = false;
  s.time_scale = 0.5f;
  ticks = 0;
  for (int i = 0; i < 8; ++i) ticks += s.advance(dt);
  CHECK(ticks == 4);
}

TEST_CASE("a bad scenario file is named and the open one stays") {
  demo::WorldSession s(blocking());
  s.open(scenario_path("kick"));
  const std::string bad = test::tmp_dir() + "/demo_bad_scenario.json";
  std::filesystem::create_directories(test::tmp_dir());
  {
    std::FILE* f = std::fopen(bad.c_str(), "w");
    REQUIRE(f);
    std::fputs("{\"characters\": [{\"position\": [0, 0], \"control\": \"user\"}], \"goal\": [0, 5], \"speed\": 2}", f);
    std::fclose(f);
  }
  try {
    s.open(bad);
    FAIL("no error for an unknown field");
  } catch (const InputError& e) {
    CHECK(std::string(e.what()).find("demo_bad_scenario.json") != std::string::npos);
    CHECK(std::string(e.what()).find("speed") != std::string::npos);
  }
  CHECK(s.scenario().name == "kick");
  CHECK(s.phase() == demo::SessionPhase::Running);
  CHECK(s.world() != nullptr);
}

TEST_CASE("picking an object makes it the source and puts the goal where acting on it leads") {
  demo::WorldSession s(blocking());
  s.open(scenario_path("obstacles"));
  s.pick_object(2);  // the hurdle, behind the bar and the beam
  s.step_once();
  const WorldCharacter& u = s.world()->characters()[0];
  CHECK(u.source_object == 2);
  CHECK(u.prepared_for == TargetAction::Jump);
  const glm::vec3 hurdle = s.world()->objects()[2].position;  // heading 0: crossed along +Z
  CHECK(s.goal().x == doctest::Approx(hurdle.x));
  CHECK(s.goal().y == doctest::Approx(hurdle.z + 2.0f));
  s.pick_object(-1);  // out of range: nothing changes
  CHECK(s.world()->picked_source() == 2);
}

TEST_CASE("first start and retraining run in the background: the scene shows and the world ticks meanwhile") {
  // A cache of its own (a short training must not replace the full policy the other tests share).
  const std::string cache = test::tmp_dir() + "/policy-cache-demo-background";
  std::filesystem::remove_all(cache);
  demo::SessionOptions o;
  o.cache_dir = cache;
  o.background = true;
  demo::WorldSession s(o);
  Params p = load_scenario_params(load_scenario(scenario_path("obstacles")));
  p.sarsa.max_steps = 300000;  // not part of the policy's hash: a short training of the same problem
  s.open(scenario_path("obstacles"), p);
  CHECK(s.world() == nullptr);
  // The scene before the world runs: the course is there at once.
  CHECK(s.scene(false).objects.size() == 3);
  CHECK(s.scene(false).goal.size() == 1);
  s.set_goal(s.goal() + glm::vec2(1.0f, 0.0f));  // intent before the world exists is kept
  bool saw_training = false, saw_characters = false;
  const auto give_up = std::chrono::steady_clock::now() + std::chrono::minutes(3);  // a guard, not a timing
  while (s.phase() != demo::SessionPhase::Running && std::chrono::steady_clock::now() < give_up) {
    const int ticks = s.advance(1.0 / 60.0);
    if (s.phase() != demo::SessionPhase::Running) CHECK(ticks == 0);  // nothing runs before the world
    saw_training |= s.phase() == demo::SessionPhase::Training;
    if (s.phase() == demo::SessionPhase::Training) saw_characters |= s.scene(false).characters.size() == 1;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  REQUIRE(s.phase() == demo::SessionPhase::Running);
  CHECK(saw_training);
  CHECK(saw_characters);  // once the motions are loaded, the character stands at its start
  const glm::vec2 scenario_goal = load_scenario(scenario_path("obstacles")).goal.front();
  CHECK(s.goal().x == doctest::Approx(scenario_goal.x + 1.0f));
  CHECK(s.goal().y == doctest::Approx(scenario_goal.y));
  CHECK(std::filesystem::exists(policy_cache_path(cache, *s.assets()->set, p)));

  // A change the policy depends on: the old policy plays on while the new one trains.
  const std::uint64_t old_hash = s.assets()->policy->params_hash;
  Params q = p;
  q.reward.source_radius = 0.9f;
  s.set_params(q);
  CHECK(s.policy_stale());
  CHECK(s.world()->params().reward.source_radius == doctest::Approx(0.9f));  // applied at once
  const float t0 = s.world()->time();
  int frames = 0;
  while (s.policy_stale() && std::chrono::steady_clock::now() < give_up) {
    s.advance(1.0 / 60.0);
    ++frames;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  CHECK_FALSE(s.policy_stale());
  CHECK(s.assets()->policy->params_hash == policy_params_hash(q));
  CHECK(s.assets()->policy->params_hash != old_hash);
  CHECK(s.world()->time() - t0 == doctest::Approx(frames * s.params().runtime.fixed_dt).epsilon(0.02));  // never held up

  // Two changes within the retraining delay train once, for the last; going back to the policy playing
  // trains nothing.
  Params r1 = q, r2 = q;
  r1.reward.source_radius = 0.95f;
  r2.reward.source_radius = 1.0f;
  s.set_params(r1);
  s.set_params(r2);
  while (s.policy_stale() && std::chrono::steady_clock::now() < give_up) {
    s.advance(1.0 / 60.0);
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  CHECK(s.assets()->policy->params_hash == policy_params_hash(r2));
  CHECK_FALSE(std::filesystem::exists(policy_cache_path(cache, *s.assets()->set, r1)));
  s.set_params(r1);
  s.set_params(r2);
  CHECK_FALSE(s.policy_stale());
  CHECK_FALSE(s.retraining());
}

TEST_CASE("steering: the goal leads the character in the held direction, the character follows and stops once let go") {
  // An open floor: the user alone, its goal ahead; nothing to prepare for.
  std::filesystem::create_directories(test::tmp_dir());
  const std::string floor = test::tmp_dir() + "/demo_open_floor.json";
  {
    std::FILE* f = std::fopen(floor.c_str(), "w");
    REQUIRE(f);
    std::fputs("{\"name\": \"open floor\", \"characters\": [{\"position\": [0, 0], \"control\": \"user\"}], \"goal\": [0, 5]}", f);
    std::fclose(f);
  }
  demo::WorldSession s(blocking());
  s.open(floor);
  const double dt = 1.0 / 30.0;
  const auto user = [&]() -> const WorldCharacter& { return s.world()->characters()[static_cast<size_t>(s.world()->user())]; };
  const glm::vec2 start = user().position;
  // Along +X, to the character's right, held for 4 s.
  const glm::vec2 dir(1.0f, 0.0f);
  s.steer(3.0f * dir);  // any length: a direction
  CHECK(glm::length(s.steering() - dir) < 1e-6f);
  glm::vec2 at_3s(0.0f);
  for (int f = 0; f < 120; ++f) {
    s.advance(dt);
    // Every tick the goal is kSteerLead ahead of the character, in the held direction (the world's goal).
    REQUIRE(user().goal.size() == 1);
    CHECK(glm::length(user().goal.front() - (user().position + demo::WorldSession::kSteerLead * dir)) < 0.05f);
    if (f == 89) at_3s = user().position;
  }
  // It turns that way (its turning motions: about 45 degrees a gait cycle, walking on meanwhile), then
  // walks along it at a walking pace, facing it.
  CHECK((user().position - start).x > 1.5f);
  const glm::vec2 last_second = user().position - at_3s;
  CHECK(glm::dot(last_second, dir) > 0.95f * glm::length(last_second));
  CHECK(glm::length(last_second) > 0.6f);
  CHECK(glm::length(last_second) < 1.8f);
  CHECK(glm::dot(glm::vec2(std::sin(user().heading), std::cos(user().heading)), dir) > 0.95f);

  // Let go: the goal stays where it was last placed, and the character walks there and stops.
  s.steer({0.0f, 0.0f});
  CHECK(s.steering() == glm::vec2(0.0f));
  const glm::vec2 goal = s.goal();
  CHECK(glm::length(goal - user().position) == doctest::Approx(demo::WorldSession::kSteerLead).epsilon(0.05));
  for (int f = 0; f < 120; ++f) s.advance(dt);
  CHECK(s.goal() == goal);
  CHECK(s.world()->goal_reached());
  CHECK(glm::length(user().position - goal) < s.params().reward.goal_radius + 0.3f);
  const glm::vec2 rest = user().position;
  for (int f = 0; f < 30; ++f) s.advance(dt);
  CHECK(glm::length(user().position - rest) < 0.1f);  // standing
}
