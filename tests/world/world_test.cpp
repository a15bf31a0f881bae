#include "engine/world/world.h"

#include <doctest/doctest.h>

#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "engine/motion/center_of_mass.h"
#include "engine/motion/contacts.h"
#include "engine/motion/kinematics.h"
#include "engine/motion/support_polygon.h"
#include "engine/world/policy_cache.h"
#include "tests/support/paths.h"
#include "tests/world/builtin_assets.h"

using namespace prep;

namespace {

using test::builtin_assets;

Scenario scenario(const std::string& name) { return load_scenario(test::repo() + "/assets/scenarios/" + name + ".json"); }

// The scenarios' acceptance: with auto on, within 30 s, every object gets the target motion it calls for, the
// user launches each at its launch point with a smoothed alpha of at least RuntimeParams::launch_alpha
// (0.9), and the goal is reached. The policy is the paper's configuration (the scenarios name no Params).
constexpr float kRunSeconds = 30.0f;

struct Outcome {
  RunSummary summary;
  std::vector<float> user_alphas;
};

Outcome run_scenario(const std::string& name, bool check_alpha) {
  const Scenario s = scenario(name);
  World world(s, builtin_assets());
  world.run(kRunSeconds);
  Outcome out{summarize(world), {}};
  INFO(summary_text(out.summary));
  CHECK(out.summary.goal_reached);
  CHECK(out.summary.unused_objects.empty());
  for (size_t k = 0; k < s.objects.size(); ++k) {
    bool met = false;
    for (const LaunchRecord& r : out.summary.launches) {
      if (r.character != world.user()) continue;
      const bool at_object = r.object == static_cast<int>(k) ||
                             (world.objects()[k].character >= 0 && r.target_character == world.objects()[k].character);
      if (at_object && r.action == s.objects[k].action) {
        met = true;
        CHECK(r.automatic);
        if (check_alpha) CHECK(r.alpha_at_launch >= world.params().runtime.launch_alpha);
        // On the launch point: not short of it by more than the glide's last few centimetres, not past it.
        CHECK(r.miss > -0.05f);
        CHECK(r.miss < 0.2f);
        CHECK(r.level_at_arrival == doctest::Approx(0.8));  // the policy itself came in at its top moving level
        out.user_alphas.push_back(r.alpha_at_launch);
      }
    }
    CHECK_MESSAGE(met, "object " << k << " (" << object_type_name(s.objects[k].type) << ")");
  }
  return out;
}

}  // namespace

TEST_CASE("the target motions: T_p and a reach ahead for every action of the built-in library") {
  const auto assets = builtin_assets();
  for (int k = 0; k < kTargetActionCount; ++k) {
    const TargetMotion& t = assets->targets[static_cast<size_t>(k)];
    INFO(target_action_name(t.action));
    REQUIRE(t.clip >= 0);
    const MotionClip& mc = assets->set->clips[static_cast<size_t>(t.clip)];
    CHECK(t.reference_frame <= mc.target_frame);  // T_p precedes T_t (Sec. 4.2)
    CHECK(t.reach > 0.0f);                          // the object is met ahead of where the clip is entered
    CHECK(t.reach < 3.0f);
  }
  CHECK(static_cast<bool>(assets->policy));
  CHECK(assets->core_nodes.size() == 4);  // the set's own: walk, turn left, turn right, slow walk
  CHECK(assets->set->clips[static_cast<size_t>(assets->core_nodes.back())].clip.name == "walk_slow");
}

TEST_CASE("the world steps at the fixed time step and keeps per-frame data reachable") {
  World world(scenario("obstacles"), builtin_assets());
  const WorldCharacter& u = world.characters()[static_cast<size_t>(world.user())];
  const glm::vec2 start = u.position;
  world.run(2.0f);
  CHECK(world.ticks() == static_cast<int>(std::lround(2.0f / world.params().runtime.fixed_dt)));
  CHECK(world.time() == doctest::Approx(2.0f).epsilon(1e-3));
  // The user walks toward the goal (+Z on the course) and has a source ahead: the bar.
  CHECK(u.position.y > start.y + 0.5f);
  CHECK(u.has_source);
  CHECK(u.source_object == 0);
  CHECK(u.prepared_for == TargetAction::Crawl);
  CHECK(u.alpha >= 0.0f);
  CHECK(u.alpha <= 1.0f);
  CHECK(u.pose.rotations.size() == static_cast<size_t>(world.assets().set->skeleton->size()));
  CHECK(std::isfinite(u.com.y));
  CHECK(u.com.y > 0.5f);  // a standing or walking body's COM is around its hips
  CHECK(world.alpha_history().size() == static_cast<size_t>(world.ticks()));
  const WorldScene scene = world.scene();
  CHECK(scene.characters.size() == 1);
  CHECK(scene.objects.size() == 3);
  REQUIRE(scene.source.has_value());
  CHECK(scene.source->z == doctest::Approx(world.scenario().objects[0].position.y));
  REQUIRE(scene.launch_point.has_value());
  // The launch point stands the crawl's reach before the bar.
  CHECK(scene.source->z - scene.launch_point->z == doctest::Approx(world.assets().target(TargetAction::Crawl).reach).epsilon(0.01));
  CHECK(scene.objects[0].is_source);
}

TEST_CASE("a world without its alpha history (a crowd's) moves exactly as one with it") {
  World kept(scenario("obstacles"), builtin_assets());
  World without(scenario("obstacles"), builtin_assets());
  without.set_alpha_history(false);
  kept.set_auto(true);
  without.set_auto(true);
  for (int t = 0; t < 1500; ++t) {  // 25 s: the approach, the crawl and on
    kept.step();
    without.step();
  }
  const WorldCharacter& a = kept.characters()[0];
  const WorldCharacter& b = without.characters()[0];
  CHECK(a.pose.root_position == b.pose.root_position);
  for (size_t j = 0; j < a.pose.rotations.size(); ++j) CHECK(a.pose.rotations[j] == b.pose.rotations[j]);
  CHECK(kept.launches().size() == without.launches().size());
  CHECK(kept.launches().size() >= 1);
  CHECK(without.alpha_history().empty());
  CHECK(kept.alpha_history().size() >= static_cast<size_t>(World::kAlphaHistory));
}

TEST_CASE("a user launch plays the target clip and returns to locomotion") {
  Scenario s = scenario("obstacles");
  s.auto_launch = false;
  World world(s, builtin_assets());
  world.run(0.5f);
  CHECK(world.launch(TargetAction::Duck));
  CHECK_FALSE(world.launch(TargetAction::Duck));  // already playing one
  REQUIRE(world.launches().size() == 1);
  CHECK(world.launches()[0].action == TargetAction::Duck);
  CHECK_FALSE(world.launches()[0].automatic);
  CHECK(world.launches()[0].time == doctest::Approx(0.5f).epsilon(0.05));
  const WorldCharacter& u = world.characters()[static_cast<size_t>(world.user())];
  CHECK(u.in_target);
  const MotionClip& duck = world.assets().set->clips[static_cast<size_t>(world.assets().target(TargetAction::Duck).clip)];
  world.run(duck.clip.duration() + 1.0f);
  CHECK_FALSE(u.in_target);
}

TEST_CASE("kick: the ball is kicked prepared and the goal is reached") { run_scenario("kick", true); }
TEST_CASE("obstacles: crawl, duck and jump each launched prepared, and the goal is reached") {
  const Outcome o = run_scenario("obstacles", true);
  CHECK(o.user_alphas.size() == 3);
}
TEST_CASE("fight: every opponent is met with a prepared punch and the goal is reached") { run_scenario("fight", true); }

TEST_CASE("without auto launch the user arrives, stops on the launch point fully prepared, and waits") {
  Scenario s = scenario("kick");
  s.auto_launch = false;
  World world(s, builtin_assets());
  world.run(20.0f);
  const WorldCharacter& u = world.characters()[static_cast<size_t>(world.user())];
  REQUIRE(u.has_source);
  CHECK(u.arrived);
  CHECK(u.source_ahead);
  CHECK(std::fabs(u.to_launch) < 0.15f);
  CHECK(u.alpha == doctest::Approx(1.0));  // forced to 1 on arrival (arrival.h): w_r = 1, no stride left
  const glm::vec2 before = u.position;
  world.run(1.0f);
  CHECK(glm::length(u.position - before) < 0.02f);
  CHECK(world.launches().empty());
  REQUIRE(world.launch(TargetAction::Kick));
  REQUIRE(world.launches().size() == 1);
  CHECK(world.launches()[0].object == 0);
  CHECK(world.launches()[0].alpha_at_launch == doctest::Approx(1.0));
}

TEST_CASE("a world without its balance view makes the same poses, and turned on again it shows the next tick's") {
  World shown(scenario("obstacles"), builtin_assets()), hidden(scenario("obstacles"), builtin_assets());
  for (World* w : {&shown, &hidden}) w->set_auto(true);
  hidden.set_balance_view(false);
  const MotionSet& set = *shown.assets().set;
  std::vector<SupportPolygon> as_built;  // taken when the world was made, and not since
  for (const WorldCharacter& c : hidden.characters()) as_built.push_back(c.support);
  for (int tick = 0; tick < 60 * 20; ++tick) {
    shown.step();
    hidden.step();
    CAPTURE(tick);
    for (size_t i = 0; i < shown.characters().size(); ++i) {
      const WorldCharacter &a = shown.characters()[i], &b = hidden.characters()[i];
      REQUIRE(a.pose.rotations == b.pose.rotations);
      REQUIRE(a.pose.root_position == b.pose.root_position);
      REQUIRE(a.balanced == b.balanced);
      CHECK(b.support.hull == as_built[i].hull);
    }
  }
  CHECK(shown.launches().size() >= 2);
  CHECK(hidden.launches().size() == shown.launches().size());
  hidden.set_balance_view(true);
  shown.step();
  hidden.step();
  std::vector<glm::vec3> positions, centroids;
  std::vector<glm::quat> rotations;
  for (size_t i = 0; i < hidden.characters().size(); ++i) {
    const WorldCharacter& c = hidden.characters()[i];
    forward_kinematics(*set.skeleton, c.pose, positions, &rotations);
    segment_centroids(*set.skeleton, set.mass, positions, rotations, centroids);
    CHECK(c.com == center_of_mass(set.mass, centroids));
    CHECK(c.com == shown.characters()[i].com);
    CHECK(c.support.hull == shown.characters()[i].support.hull);
    CHECK(c.com_in_support == shown.characters()[i].com_in_support);
  }
}

TEST_CASE("every tick the COM and the support polygon are those of the pose shown, however the pose was made") {
  // The world reuses the synthesizer's kinematics and support polygon when the pose is the synthesized one;
  // through launches, cross-fades and recorded clips they must equal a fresh computation from the pose.
  World world(scenario("obstacles"), builtin_assets());
  world.set_auto(true);
  const MotionSet& set = *world.assets().set;
  std::vector<glm::vec3> positions, centroids;
  std::vector<glm::quat> rotations;
  int launches_seen = 0;
  for (int tick = 0; tick < 60 * 25; ++tick) {
    world.step();
    for (const WorldCharacter& c : world.characters()) {
      forward_kinematics(*set.skeleton, c.pose, positions, &rotations);
      segment_centroids(*set.skeleton, set.mass, positions, rotations, centroids);
      CHECK(c.com == center_of_mass(set.mass, centroids));
      const SupportPolygon fresh =
          support_polygon(foot_points(*set.skeleton, set.body, positions, rotations), c.contacts, world.params().contacts);
      REQUIRE(c.support.hull.size() == fresh.hull.size());
      for (size_t k = 0; k < fresh.hull.size(); ++k) CHECK(c.support.hull[k] == fresh.hull[k]);
    }
    launches_seen = static_cast<int>(world.launches().size());
  }
  CHECK(launches_seen >= 2);  // the run went through launches and the cross-fades around them
}

TEST_CASE("a filter width set on a running world reaches its controllers: it plays as a world built with it") {
  Params wide = builtin_assets()->params;
  wide.runtime.alpha_sigma_s = 0.6f;
  auto built_wide = std::make_shared<WorldAssets>(*builtin_assets());
  built_wide->params = wide;
  World set_live(scenario("obstacles"), builtin_assets()), built(scenario("obstacles"), built_wide),
      unchanged(scenario("obstacles"), builtin_assets());
  set_live.set_params(wide);
  bool differs_from_unchanged = false;
  for (int t = 0; t < 600; ++t) {  // 10 s: the approach to the bar, alpha rising
    set_live.step();
    built.step();
    unchanged.step();
    const float a = set_live.characters()[0].alpha;
    CHECK(a == built.characters()[0].alpha);
    differs_from_unchanged |= a != unchanged.characters()[0].alpha;
  }
  CHECK(differs_from_unchanged);
}
