#include "engine/world/course_evaluation.h"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>

#include "engine/world/courses.h"
#include "engine/world/policy_cache.h"
#include "tests/support/paths.h"

using namespace prep;

namespace {

// The built-in library's assets and policy with the default Params, made once per test binary (cached
// under the build's scratch folder, as in world_test.cpp). Not builtin_assets(), which has the obstacles
// scenario's Params (tests/world/builtin_assets.h).
std::shared_ptr<const WorldAssets> default_assets() {
  static std::shared_ptr<const WorldAssets> assets = [] {
    Scenario s;
    return prepare_world_assets(s, Params{}, test::tmp_dir() + "/policy-cache");
  }();
  return assets;
}

// The user at the origin facing +Z, the goal at (0, goal_z), and these objects.
Scenario straight_course(float goal_z, std::vector<ScenarioObject> objects = {}) {
  Scenario s;
  s.name = "straight";
  s.auto_launch = true;
  ScenarioCharacter user;
  s.characters.push_back(user);
  s.objects = std::move(objects);
  s.goal.push_back({0.0f, goal_z});
  return s;
}

ScenarioObject across(ObjectType type, float z, float height, float depth) {
  ScenarioObject o;
  o.type = type;
  o.action = default_action(type);
  o.position = {0.0f, z};
  o.size = {5.0f, height, depth};
  return o;
}

}  // namespace

TEST_CASE("percentile: linear between the closest ranks") {
  CHECK(percentile({4, 1, 3, 2}, 50) == doctest::Approx(2.5f));
  CHECK(percentile({4, 1, 3, 2}, 95) == doctest::Approx(3.85f));  // rank 2.85: 3 + 0.85 x (4 - 3)
  CHECK(percentile({4, 1, 3, 2}, 0) == doctest::Approx(1.0f));
  CHECK(percentile({4, 1, 3, 2}, 100) == doctest::Approx(4.0f));
  CHECK(percentile({7}, 95) == doctest::Approx(7.0f));
  CHECK(std::isnan(percentile({}, 50)));
}

TEST_CASE("alpha with no source in range: its ticks, and per episode the time to relax below 0.1") {
  constexpr float dt = 0.1f;
  NoSourceMeter m(true, 0.0f);  // the start, before any source: out of range, but no episode
  float t = 0.0f;
  auto feed = [&](int ticks, bool out, float alpha_from, float alpha_to) {
    for (int k = 1; k <= ticks; ++k) {
      t += dt;
      m.add(t, out, alpha_from + (alpha_to - alpha_from) * static_cast<float>(k) / static_cast<float>(ticks));
    }
  };
  feed(5, true, 0.0f, 0.0f);
  CHECK(m.relax_times().empty());
  feed(10, false, 0.0f, 0.8f);   // a source in range: alpha rises to 0.8
  feed(20, true, 0.8f, 0.0f);    // out of range at t = 1.6 s, alpha falls 0.04 a tick: below 0.1 on tick 18
  REQUIRE(m.relax_times().size() == 1);
  CHECK(m.relax_times()[0] == doctest::Approx(17 * dt));
  feed(3, false, 0.5f, 0.5f);
  feed(4, true, 0.5f, 0.5f);     // out for 0.4 s, still at 0.5 when the next source comes in range
  feed(2, false, 0.5f, 0.5f);
  CHECK(m.unrelaxed() == 1);
  feed(3, true, 0.05f, 0.05f);   // out of a target motion straight to 0.05: relaxed at once
  REQUIRE(m.relax_times().size() == 2);
  CHECK(m.relax_times()[1] == doctest::Approx(0.0f));
  feed(1, false, 0.9f, 0.9f);
  feed(3, true, 0.6f, 0.6f);     // the run ends out of range, unrelaxed
  m.finish();
  CHECK(m.unrelaxed() == 2);
  CHECK(m.alpha().size() == 1 + 5 + 20 + 4 + 3 + 3);  // every tick out of range, the first included
}

TEST_CASE("circling: an orbit round the goal turns past 360 degrees, a pass through and the pelvis' sway do not") {
  constexpr float dt = 1.0f / 60.0f, kPi = 3.14159265358979f;
  const glm::vec2 goal{0.0f, 0.0f};

  // 15 s on a circle of 1.5 m round the goal at 1 m/s, counter-clockwise from +X (heading 0, then turning
  // right): the heading turns 1/1.5 rad/s, 573 degrees.
  CirclingMeter orbit(dt, 0.0f);
  for (int k = 1; k <= 900; ++k) {
    const float a = static_cast<float>(k) * dt / 1.5f;  // angle on the circle, counter-clockwise from +X
    orbit.add({1.5f * std::cos(a), 1.5f * std::sin(a)}, std::remainder(-a, 2.0f * kPi), 0, goal);
  }
  orbit.finish();
  CHECK(orbit.visits() == 1);
  CHECK(orbit.seconds() == doctest::Approx(15.0f).epsilon(0.01));
  CHECK(orbit.max_turn_deg() == doctest::Approx(573.0f - 19.0f).epsilon(0.03));  // less the averaging's lag

  // Walking straight through, 0.5 m beside the goal, swaying the heading 6 degrees either way at 1 Hz; then
  // standing 30 s within 2 m of it still swaying: a raw sum would be 24 degrees a second.
  CirclingMeter sway(dt, 0.0f);
  for (int k = 1; k <= 2400; ++k) {
    const float t = static_cast<float>(k) * dt;
    const glm::vec2 p{0.5f, std::min(-4.0f + 1.4f * t, 1.0f)};
    sway.add(p, 6.0f * kPi / 180.0f * std::sin(2.0f * kPi * t), 0, goal);
  }
  sway.finish();
  CHECK(sway.visits() == 0);
  CHECK(sway.seconds() == 0.0f);
  CHECK(sway.max_turn_deg() < 30.0f);

  // In and out of the 2 m circle on an orbit of 2.2 m: one visit, as long as it stays within 3 m.
  CirclingMeter edge(dt, 0.0f);
  edge.add({1.9f, 0.0f}, 0.0f, 0, goal);  // comes within 2 m
  for (int k = 1; k <= 900; ++k) {
    const float a = static_cast<float>(k) * dt / 2.2f;
    edge.add({2.2f * std::cos(a), 2.2f * std::sin(a)}, std::remainder(-a, 2.0f * kPi), 0, goal);
  }
  edge.finish();
  CHECK(edge.visits() == 1);
  // A new goal point ends the visit: the same orbit split by a waypoint passed half way is two short turns.
  CirclingMeter split(dt, 0.0f);
  for (int k = 1; k <= 900; ++k) {
    const float a = static_cast<float>(k) * dt / 1.5f;
    split.add({1.5f * std::cos(a), 1.5f * std::sin(a)}, std::remainder(-a, 2.0f * kPi), k <= 450 ? 0 : 1, goal);
  }
  split.finish();
  CHECK(split.visits() == 0);
}

TEST_CASE("weaving: turn clips reversing three times within 3 s weave, a route's turns a few seconds apart do not") {
  const float dt = 1.0f / 60.0f;
  // Plays `pattern` (+1 a left turn clip, -1 a right one, 0 a walk, 2 a target motion), each entry for
  // `seconds`, into a meter.
  auto play = [&](const std::vector<int>& pattern, float seconds) {
    WeavingMeter m;
    float t = 0.0f;
    for (int p : pattern)
      for (int k = 0; k < static_cast<int>(seconds / dt); ++k, t += dt) m.add(t, p == 2 ? 0 : p, p == 2);
    return m;
  };
  // Left, right, left, right, a second each: three reversals in 3 s (at 1, 2 and 3 s less a tick).
  const WeavingMeter zigzag = play({1, -1, 1, -1}, 1.0f);
  CHECK(zigzag.reversals() == 3);
  CHECK(zigzag.most_in_window() == course_metric::kWeaveReversals);
  // The same turns with walks of a second between: the reversals are 2 s apart, at most two in 3 s.
  const WeavingMeter route = play({1, 0, -1, 0, 1, 0, -1}, 1.0f);
  CHECK(route.reversals() == 3);
  CHECK(route.most_in_window() == 2);
  // Turns the same way with walks between never reverse.
  CHECK(play({1, 0, 1, 0, 1}, 1.0f).reversals() == 0);
  // A target motion between two turns forgets the first: a right turn after a launch is no reversal.
  CHECK(play({1, 2, -1, 0, 1}, 1.0f).reversals() == 1);
}

TEST_CASE("swerving: a source once ahead and then more than 60 degrees off before its last metre swerves") {
  // The user at the origin; the source's launch point 4 m away at `deg` off the facing (+Z), `to_launch`
  // along the approach.
  auto tick = [](SwerveMeter& m, int source, float deg, float to_launch) {
    const float a = deg * 3.14159265f / 180.0f;
    m.add(source, 4.0f * glm::vec2(std::sin(a), std::cos(a)), to_launch, glm::vec2(0.0f), 0.0f);
  };
  SwerveMeter m;
  tick(m, 0, 10.0f, 4.0f);   // source 0 comes ahead: an approach
  tick(m, 0, 70.0f, 3.0f);   // swung 70 degrees off 3 m out: a swerve
  tick(m, 0, 20.0f, 2.0f);
  tick(m, 1, 90.0f, 4.0f);   // source 1 beside, never ahead: no approach, whatever it does
  tick(m, 1, 120.0f, 3.0f);
  tick(m, 2, 30.0f, 3.0f);   // source 2 ahead ...
  tick(m, 2, 80.0f, 0.8f);   // ... and 80 degrees off within its last metre (squaring up): no swerve
  tick(m, -1, 0.0f, 0.0f);   // none (a target motion)
  tick(m, 2, 5.0f, 3.0f);    // source 2 again after it: a new approach
  m.finish();
  CHECK(m.approaches() == 3);
  CHECK(m.swerves() == 1);
  CHECK(m.widest_deg() == doctest::Approx(70.0f).epsilon(1e-3));
}

TEST_CASE("a straight walk to the goal: path ratio at least 1, no circling, no source, the run ends 2.5 s after") {
  const Scenario s = straight_course(8.0f);
  const CourseEvaluation e = evaluate_course(s, default_assets());
  REQUIRE(e.reached_goal);
  CHECK(e.route_length == doctest::Approx(8.0f));
  // Walked from the start to the goal's 0.4 m edge: at least the 7.6 m of the straight line, and a
  // straight walk adds only its sway.
  CHECK(e.path_ratio >= 1.0f);
  CHECK(e.path_ratio < 1.1f);
  CHECK(e.path_length == doctest::Approx(e.path_ratio * 7.6f));
  CHECK(e.circling_seconds == 0.0f);
  CHECK(e.circling_visits == 0);
  CHECK(e.max_visit_turn_deg < 90.0f);
  CHECK(e.launches.empty());
  CHECK(e.kept.empty());
  CHECK(e.objects == 0);
  // Never a source: every tick is a no-source tick, and there was nothing to relax from.
  CHECK(e.no_source_alpha.size() == e.alpha.size());
  CHECK(e.relax_times.empty());
  CHECK(e.unrelaxed_episodes == 0);
  CHECK(e.seconds == doctest::Approx(e.goal_time + course_metric::kRelaxSeconds).epsilon(0.01));
  CHECK(e.times.size() == e.alpha.size());
}

TEST_CASE("a beam and a hurdle 2 m apart: the kept preparation is the lowest alpha between the two launches") {
  const Scenario s = straight_course(9.0f, {across(ObjectType::Beam, 4.0f, 1.2f, 0.2f), across(ObjectType::Hurdle, 6.0f, 0.45f, 0.1f)});
  const CourseEvaluation e = evaluate_course(s, default_assets());
  REQUIRE(e.launches.size() == 2);
  CHECK(e.launches[0].action == TargetAction::Duck);
  CHECK(e.launches[1].action == TargetAction::Jump);
  CHECK(e.objects_unused == 0);
  for (const CourseLaunch& l : e.launches) {
    CHECK(e.times[static_cast<size_t>(l.tick)] == doctest::Approx(l.time));
    CHECK(e.alpha[static_cast<size_t>(l.tick)] == doctest::Approx(l.alpha_at_launch));
  }
  REQUIRE(e.kept.size() == 1);
  const KeptPreparation& k = e.kept[0];
  CHECK(k.first == 0);
  CHECK(k.second == 1);
  CHECK(k.distance == doctest::Approx(2.0f));
  // By hand over the recorded alpha: the ticks strictly between the two launches.
  float lowest = 1.0f;
  for (int t = e.launches[0].tick + 1; t < e.launches[1].tick; ++t) lowest = std::min(lowest, e.alpha[static_cast<size_t>(t)]);
  CHECK(k.min_alpha == lowest);
  // After the jump nothing is left: the user goes out of range once more, an episode to relax in.
  CHECK(e.relax_times.size() + static_cast<size_t>(e.unrelaxed_episodes) >= 1);
  for (float r : e.relax_times) {
    CHECK(r >= 0.0f);
    CHECK(r <= e.seconds);
  }

  // The same two obstacles 5 m apart are no close pair.
  const Scenario apart = straight_course(12.0f, {across(ObjectType::Beam, 4.0f, 1.2f, 0.2f), across(ObjectType::Hurdle, 9.0f, 0.45f, 0.1f)});
  CHECK(evaluate_course(apart, default_assets()).kept.empty());
}

TEST_CASE("four random courses through the evaluator on two threads: sane measures, the same as run alone") {
  CourseOptions o;
  o.seed = 3;
  const std::vector<Scenario> courses = make_courses(o, 4);
  const std::vector<CourseEvaluation> runs = evaluate_courses(courses, default_assets(), 2);
  REQUIRE(runs.size() == 4);
  for (size_t i = 0; i < runs.size(); ++i) {
    const CourseEvaluation& e = runs[i];
    CAPTURE(e.name);
    CAPTURE(e.description);
    CHECK(e.name == courses[i].name);
    CHECK(e.seconds <= course_time_limit(courses[i]) + 0.02f);
    CHECK(e.route_length == doctest::Approx(polyline_length(course_route(courses[i]))));
    CHECK(e.objects == static_cast<int>(courses[i].objects.size()));
    CHECK(e.objects_unused >= 0);
    CHECK(e.objects_unused <= e.objects);
    CHECK(static_cast<int>(e.launches.size()) <= e.objects);  // the user acts on each object once at most
    if (e.reached_goal) {
      CHECK(e.goal_time <= e.seconds);
      CHECK(e.path_ratio >= 0.9f);
    } else {
      CHECK(std::isnan(e.path_ratio));
    }
    for (float a : e.alpha) {
      CHECK(a >= 0.0f);
      CHECK(a <= 1.0f);
    }
    for (const KeptPreparation& k : e.kept) {
      CHECK(k.distance < course_metric::kKeptDistance);
      CHECK(k.second == k.first + 1);
    }
    CHECK(e.circling_seconds <= e.seconds);
  }
  const CourseEvaluation alone = evaluate_course(courses[1], default_assets());
  CHECK(alone.seconds == runs[1].seconds);
  CHECK(alone.path_length == runs[1].path_length);
  CHECK(alone.alpha == runs[1].alpha);
}

TEST_CASE("course totals: fractions, percentiles and the pass/fail checks") {
  auto course = [](bool goal, float ratio, std::vector<float> at_launch, std::vector<float> at_1m) {
    CourseEvaluation e;
    e.reached_goal = goal;
    e.path_ratio = goal ? ratio : NAN;
    for (size_t k = 0; k < at_launch.size(); ++k) {
      CourseLaunch l;
      l.alpha_at_launch = at_launch[k];
      l.alpha_at_1m = at_1m[k];
      e.launches.push_back(l);
    }
    e.no_source_alpha = {0.0f, 0.0f, 0.05f};
    return e;
  };
  std::vector<CourseEvaluation> all{course(true, 1.0f, {0.9f, 0.95f}, {0.6f, -1.0f}), course(true, 1.1f, {0.9f}, {0.7f})};
  CourseTotals t = course_totals(all);
  CHECK(t.courses == 2);
  CHECK(t.goals == 2);
  CHECK(t.launches == 3);
  CHECK(t.launches_prepared == 3);
  CHECK(t.measured_1m == 2);  // the -1 is not measured
  CHECK(t.prepared_1m == 2);
  CHECK(t.path_median == doctest::Approx(1.05f));
  CHECK(t.no_source_median == doctest::Approx(0.0f));
  CHECK(t.no_source_mean == doctest::Approx(0.1f / 6.0f));
  REQUIRE(t.checks.size() == 7);
  CHECK(t.pass());

  // One course short of its goal, one launch unprepared, one circling: those checks fail, the others pass.
  all.push_back(course(false, 0.0f, {0.5f}, {0.2f}));
  all.back().circling_visits = 1;
  all.back().circling_seconds = 4.0f;
  t = course_totals(all);
  CHECK_FALSE(t.pass());
  for (const CourseCheck& c : t.checks) {
    CAPTURE(c.name);
    CAPTURE(c.measure);
    const bool should_fail = c.name == "goal_reached" || c.name == "alpha_at_launch" || c.name == "alpha_at_1m" || c.name == "circling";
    CHECK(c.pass == !should_fail);
  }
  CHECK(t.path_median == doctest::Approx(1.05f));  // the unreached course has no ratio
  CHECK(t.circling_courses == 1);
  // Weaving: a course weaving and 6 reversals over the courses' 2 minutes. One of three courses is more than
  // the 2% allowed; two of a hundred are not, three are.
  CHECK(t.weaving_courses == 0);
  all[0].most_reversals_in_window = course_metric::kWeaveReversals;
  all[0].turn_reversals = 6;
  all[0].seconds = 60.0f;
  all[1].seconds = 60.0f;
  t = course_totals(all);
  CHECK(t.weaving_courses == 1);
  CHECK(t.reversals_per_minute == doctest::Approx(3.0f));
  REQUIRE(t.checks.size() == 7);
  CHECK(t.checks[6].name == "weaving");
  CHECK_FALSE(t.checks[6].pass);
  std::vector<CourseEvaluation> hundred(100, all[1]);
  hundred[0] = hundred[1] = all[0];
  const CourseTotals two_in_a_hundred = course_totals(hundred);
  CHECK(two_in_a_hundred.weaving_courses == 2);
  CHECK(two_in_a_hundred.checks[6].pass);
  hundred[2] = all[0];
  CHECK_FALSE(course_totals(hundred).checks[6].pass);
  const nlohmann::json j = course_totals_json(t);
  CHECK(j["weaving_courses"] == 1);
  CHECK(j["checks"]["weaving"]["pass"] == false);
  CHECK(j["checks"]["circling"]["pass"] == false);
  CHECK(j["checks"]["path_ratio"]["pass"] == true);
  CHECK(j["pass"] == false);
  CHECK(j["goal_reached"].get<double>() == doctest::Approx(2.0 / 3.0));
}
