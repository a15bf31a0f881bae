// Behaviour on courses beyond the shipped scenarios: preparation kept between close targets, relaxed when
// nothing is ahead, and goals reached without circling (world.h, steering.h).
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "engine/world/course_evaluation.h"
#include "engine/world/courses.h"
#include "engine/world/policy_cache.h"
#include "engine/world/steering.h"
#include "engine/world/world.h"
#include "tests/support/angles.h"
#include "tests/support/paths.h"
#include "tests/world/builtin_assets.h"
#include "tests/world/builtin_courses.h"

using namespace prep;

namespace {

using test::builtin_assets;
using test::builtin_course_options;
using test::builtin_random_course;
using test::kPi;

std::string obstacle(const char* type, float z, float width, float height, float depth) {
  return std::string("{\"type\": \"") + type + "\", \"position\": [0, " + std::to_string(z) + "], \"size\": [" +
         std::to_string(width) + ", " + std::to_string(height) + ", " + std::to_string(depth) + "]}";
}


// Course k of a seed on one of our CMU sets (its manifest, its controller Params), with the set's assets, as
// `prep evaluate --random N --seed S --motions assets/manifests/SET.json` draws it.
struct CourseOfSet {
  std::shared_ptr<const WorldAssets> assets;
  Scenario course;
};
CourseOfSet set_random_course(const std::string& set, std::uint64_t seed, int k) {
  Scenario probe;
  probe.motions = test::repo() + "/assets/manifests/" + set + ".json";
  probe.params_file = test::repo() + "/assets/scenarios/controller_" + set + ".json";
  CourseOfSet r;
  r.assets = prepare_world_assets(probe, load_scenario_params(probe), test::tmp_dir() + "/policy-cache");
  CourseOptions options;
  options.seed = seed;
  options.motions = probe.motions;
  options.params_file = probe.params_file;
  options.actions = actions_of(*r.assets);
  options.reach = reaches_of(*r.assets);
  options.heights = heights_of(*r.assets);
  r.course = make_courses(options, k + 1)[static_cast<size_t>(k)];
  return r;
}

Scenario course(const std::vector<std::string>& objects, float goal_z) {
  std::string list;
  for (const std::string& o : objects) list += (list.empty() ? "" : ", ") + o;
  const std::string text = "{\"auto\": true, \"characters\": [{\"position\": [0, 0], \"control\": \"user\"}], \"objects\": [" +
                           list + "], \"goal\": [0, " + std::to_string(goal_z) + "]}";
  return parse_scenario(text, "course");
}

// The user's smoothed alpha per tick with the world time, until `seconds` have passed.
struct Trace {
  std::vector<float> time, alpha;
  float min_between(float from, float to) const {
    float m = 1.0f;
    for (size_t k = 0; k < time.size(); ++k)
      if (time[k] > from && time[k] < to) m = std::min(m, alpha[k]);
    return m;
  }
};

Trace run(World& world, float seconds) {
  Trace t;
  const int ticks = static_cast<int>(std::lround(seconds / world.params().runtime.fixed_dt));
  for (int k = 0; k < ticks; ++k) {
    world.step();
    t.time.push_back(world.time());
    t.alpha.push_back(world.characters()[static_cast<size_t>(world.user())].alpha);
  }
  return t;
}

// A built-in course with one ball: the goal reached, nothing left, the ball kicked once and prepared.
void check_goal_and_one_prepared_kick(const Scenario& course) {
  const CourseEvaluation e = evaluate_courses({course}, builtin_assets(), 1)[0];
  CHECK(e.reached_goal);
  CHECK(e.objects_unused == 0);
  int kicks = 0;
  for (const CourseLaunch& l : e.launches) {
    if (l.action != TargetAction::Kick) continue;
    ++kicks;
    CHECK(l.alpha_at_launch >= 0.85f);
  }
  CHECK(kicks == 1);
}

// Runs generated courses on both cores: each must reach its goal with no body in an object; `check` is
// given each course's index and evaluation for the rest.
template <class Check>
void check_generated_courses(const std::vector<Scenario>& courses, Check&& check) {
  const std::vector<CourseEvaluation> runs = evaluate_courses(courses, builtin_assets(), 2);
  for (size_t k = 0; k < runs.size(); ++k) {
    CAPTURE(k);
    INFO(runs[k].clearance.min_object_what);
    CHECK(runs[k].reached_goal);
    CHECK(runs[k].clearance.object_frames == 0);
    check(k, runs[k]);
  }
}

const LaunchRecord* launch_of(const World& world, TargetAction action) {
  for (const LaunchRecord& r : world.launches())
    if (r.character == world.user() && r.action == action) return &r;
  return nullptr;
}

}  // namespace

TEST_CASE("kept preparation: between a bar and a beam 2 m apart alpha stays at or above 0.5") {
  const Scenario s = course({obstacle("bar", 3.5f, 4.0f, 0.7f, 0.1f), obstacle("beam", 5.5f, 4.0f, 1.2f, 0.2f)}, 9.0f);
  World world(s, builtin_assets());
  const Trace t = run(world, 30.0f);
  INFO(summary_text(summarize(world)));
  const LaunchRecord* crawl = launch_of(world, TargetAction::Crawl);
  const LaunchRecord* duck = launch_of(world, TargetAction::Duck);
  REQUIRE(crawl != nullptr);
  REQUIRE(duck != nullptr);
  CHECK(crawl->alpha_at_launch >= 0.85f);
  CHECK(duck->alpha_at_launch >= 0.85f);
  CHECK(t.min_between(crawl->time, duck->time) >= 0.5f);
  CHECK(world.goal_reached());
}

TEST_CASE("kept preparation: a hurdle 1.5 m behind a beam is jumped prepared") {
  const Scenario s = course({obstacle("beam", 6.0f, 4.0f, 1.2f, 0.2f), obstacle("hurdle", 7.5f, 4.0f, 0.45f, 0.1f)}, 10.0f);
  World world(s, builtin_assets());
  const Trace t = run(world, 30.0f);
  INFO(summary_text(summarize(world)));
  const LaunchRecord* duck = launch_of(world, TargetAction::Duck);
  const LaunchRecord* jump = launch_of(world, TargetAction::Jump);
  REQUIRE(duck != nullptr);
  REQUIRE(jump != nullptr);
  CHECK(jump->alpha_at_launch >= 0.85f);
  // 1 m before the launch point: met on the approach, or (the approach began closer, out of the duck) the
  // alpha never fell below 0.5 on the way from the duck.
  if (jump->alpha_at_1m >= 0.0f) CHECK(jump->alpha_at_1m >= 0.5f);
  CHECK(t.min_between(duck->time, jump->time) >= 0.5f);
  CHECK(world.goal_reached());
}

TEST_CASE("relaxation: with no source in range alpha falls to 0.1 within 2 s and stays there at the goal") {
  const Scenario s = course({obstacle("bar", 3.5f, 4.0f, 0.7f, 0.1f)}, 12.0f);
  World world(s, builtin_assets());
  float back = -1.0f, relaxed = -1.0f, goal = -1.0f, worst_after_goal = 0.0f;
  bool was_in_target = false;
  for (int k = 0; k < 40 * 60 && (goal < 0.0f || world.time() < goal + 4.0f); ++k) {
    world.step();
    const WorldCharacter& u = world.characters()[static_cast<size_t>(world.user())];
    if (was_in_target && !u.in_target && back < 0.0f) back = world.time();
    was_in_target = u.in_target;
    if (back >= 0.0f && relaxed < 0.0f && u.alpha <= 0.1f) relaxed = world.time();
    if (goal < 0.0f && u.reached_goal) goal = world.time();
    if (goal >= 0.0f && world.time() >= goal + 2.0f) worst_after_goal = std::max(worst_after_goal, u.alpha);
  }
  INFO(summary_text(summarize(world)));
  REQUIRE(back > 0.0f);
  REQUIRE(relaxed > 0.0f);
  CHECK(relaxed - back <= 2.0f);
  REQUIRE(goal > 0.0f);
  CHECK(worst_after_goal <= 0.1f);
}

TEST_CASE("the switches off restore the paper's behaviour: at the goal the last chosen level stays") {
  Params paper = builtin_assets()->params;
  paper.runtime.relax_without_source = false;
  paper.runtime.kept_alpha = -1.0f;
  paper.runtime.tight_turn_deg_per_s = 0.0f;
  paper.runtime.waypoint_pass_radius = 0.0f;
  paper.runtime.anticipate_closing = false;
  paper.runtime.end_turn_at_goal_bearing = false;
  paper.runtime.keep_source_ahead = false;
  paper.runtime.make_for_ball_source = false;
  paper.runtime.level_per_source_bin = false;
  const Scenario s = load_scenario(test::repo() + "/assets/scenarios/obstacles.json");
  World relaxed(s, builtin_assets()), as_paper(s, builtin_assets());
  as_paper.set_params(paper);
  relaxed.run(32.0f);
  as_paper.run(32.0f);
  REQUIRE(relaxed.goal_reached());
  REQUIRE(as_paper.goal_reached());
  // Eq. 14-17 never lower alpha when nothing is near, and at the goal the controller keeps its last action
  // (controller.h): the paper's character stands there part prepared; the relaxed one stands upright.
  CHECK(as_paper.characters()[0].alpha > 0.1f);
  CHECK(as_paper.characters()[0].alpha == doctest::Approx(as_paper.characters()[0].chosen_alpha));
  CHECK(relaxed.characters()[0].alpha <= 0.1f);
}

TEST_CASE("steering: the turning circle and waypoints passed by") {
  // A goal 1 m to the left, radius 2 m: inside the circle on the left; 5 m ahead: not.
  CHECK(inside_turning_circle({0, 0}, 0.0f, {1.0f, 0.0f}, 2.0f));
  CHECK_FALSE(inside_turning_circle({0, 0}, 0.0f, {0.0f, 5.0f}, 2.0f));
  CHECK(inside_turning_circle({0, 0}, 0.0f, {0.0f, -1.5f}, 2.0f));  // behind within a U-turn's width
  CHECK(bearing_to({0, 0}, 0.0f, {1.0f, 0.0f}) == doctest::Approx(kPi / 2));  // +X is to the left of +Z
  CHECK(tight_turn({0, 0}, 0.0f, {1.0f, 0.0f}, 2.0f, 2.0f).rate == doctest::Approx(2.0f));  // capped
  CHECK(tight_turn({0, 0}, 0.0f, {0.0f, 5.0f}, 2.0f, 2.0f).rate == 0.0f);
  // A goal 8 m away, 80 degrees to the left: the walking turns reach it. Nearly straight behind: the tight
  // turn toward it (to the right, the shorter way), at the shortest stride.
  CHECK(tight_turn({0, 0}, 0.0f, {7.88f, 1.39f}, 2.0f, 2.0f).rate == 0.0f);
  const TightTurn back = tight_turn({0, 0}, 0.0f, {-0.5f, -8.0f}, 2.0f, 2.0f);
  CHECK(back.rate == doctest::Approx(-2.0f));
  CHECK(back.stride == doctest::Approx(kTightStride));
  CHECK(passed_waypoint({0, 0}, 0.0f, {0.5f, -0.1f}, 1.0f));
  CHECK(passed_waypoint({0, 0}, 0.0f, {0.5f, 0.3f}, 1.0f));         // beside: 59 degrees off the facing
  CHECK_FALSE(passed_waypoint({0, 0}, 0.0f, {0.3f, 0.5f}, 1.0f));   // 31 degrees off: still ahead
  CHECK_FALSE(passed_waypoint({0, 0}, 0.0f, {0.0f, -1.5f}, 1.0f));  // too far
}

TEST_CASE("a goal behind at the start: the character turns round where it stands, not in a loop away from it") {
  // Random course 24 of seed 2026: the user starts facing away from a goal 11.8 m off, a bar on the way.
  // With the goal nearly straight behind the policy's bearing bins flipped between left and right: the
  // character walked 6 m away from the goal, then looped back, 2.3 times the route in all.
  const Scenario course = builtin_random_course(2026, 24);
  REQUIRE(course.goal.size() == 1);
  World world(course, builtin_assets());
  world.set_auto(true);
  const glm::vec2 goal = course.goal.front();
  const float start_distance = glm::length(goal - world.characters()[0].position);
  float farthest = start_distance;
  world.run_until_done(60.0f, 1.0f, [&](const World& w) {
    farthest = std::max(farthest, glm::length(goal - w.characters()[0].position));
  });
  CHECK(world.goal_reached());
  CHECK(farthest <= start_distance + 1.0f);  // a stride or two while it turns, not 6 m
  const CourseEvaluation e = evaluate_courses({course}, builtin_assets(), 1)[0];
  CHECK(e.reached_goal);
  CHECK(e.path_ratio <= 1.4f);
}

TEST_CASE("goals 0.5-2 m to the side and behind a walking character are reached without a full circle") {
  const Scenario s = course({}, 40.0f);
  for (float distance : {0.5f, 1.0f, 2.0f}) {
    for (float bearing_deg : {90.0f, -90.0f, 135.0f, 180.0f, -135.0f}) {
      World world(s, builtin_assets());
      world.run(4.0f);  // walking toward the far goal
      const WorldCharacter& u = world.characters()[0];
      const float b = u.heading + bearing_deg * kPi / 180.0f;
      world.set_goal(u.position + distance * glm::vec2(std::sin(b), std::cos(b)));
      float turned = 0.0f, heading = u.heading;
      float reached = -1.0f;
      for (int k = 0; k < 12 * 60 && reached < 0.0f; ++k) {
        world.step();
        float dh = world.characters()[0].heading - heading;
        while (dh > kPi) dh -= 2.0f * kPi;
        while (dh < -kPi) dh += 2.0f * kPi;
        turned += std::fabs(dh);
        heading = world.characters()[0].heading;
        if (world.goal_reached()) reached = world.time() - 4.0f;
      }
      INFO("goal " << distance << " m at " << bearing_deg << " deg: reached after " << reached << " s, turned "
                   << turned * 180.0f / kPi << " deg");
      CHECK(reached > 0.0f);
      CHECK(reached < 8.0f);
      CHECK(turned < 2.0f * kPi);
    }
  }
}

TEST_CASE("late entry: past an obstacle's launch point the clip is entered where it has come as far") {
  const TargetMotion& duck = builtin_assets()->target(TargetAction::Duck);
  REQUIRE(duck.advance.size() > 2);
  CHECK(duck.advance.front() == 0.0f);
  CHECK(duck.entry_frame(0.0f) == duck.reference_frame);
  const float half = 0.5f * duck.advance.back();
  const int f = duck.entry_frame(half);
  CHECK(f > duck.reference_frame);
  CHECK(duck.advance[static_cast<size_t>(f - duck.reference_frame)] >= half);
  CHECK(duck.advance[static_cast<size_t>(f - duck.reference_frame - 1)] < half);
  // Farther than the clip goes before its fit to the beam fades in: that frame, the latest entry, past T_t.
  const MotionClip& clip = builtin_assets()->set->clips[static_cast<size_t>(duck.clip)];
  CHECK(duck.last_entry_frame > clip.target_frame);
  CHECK(duck.entry_frame(100.0f) == duck.last_entry_frame);
  const ObstacleFit fit = fit_obstacle(builtin_assets()->sweeps[static_cast<size_t>(TargetAction::Duck)], duck, ObjectType::Beam,
                                       {1.0f, 1.2f, 0.1f});
  CHECK(duck.last_entry_frame < fit.first);
}

TEST_CASE("squaring up: the turn toward an obstacle's crossing, capped, none within the tolerance") {
  CHECK(squaring_rate(0.0f, 0.5f, 10.0f) == doctest::Approx(0.5f / kTightTurnTime));
  CHECK(squaring_rate(0.0f, -0.5f, 10.0f) == doctest::Approx(-0.5f / kTightTurnTime));
  CHECK(squaring_rate(0.0f, 1.5f, 2.0f) == doctest::Approx(2.0f));                  // capped
  CHECK(squaring_rate(3.0f, -3.0f, 10.0f) > 0.0f);                                  // the short way round
  CHECK(squaring_rate(0.0f, 0.5f * kSquareTolerance, 10.0f) == 0.0f);
  CHECK(squaring_rate(0.0f, 0.5f, 0.0f) == 0.0f);                                   // off
}

// Label "slow": the sanitizer tree leaves it out (scripts/test.sh); the tests above run the world's courses there.
TEST_CASE("random courses of seed 1 with varied obstacles (the first 100): every acceptance check passes and bodies stay clear" *
          doctest::test_suite("slow")) {
  // Varied widths, depths and heights (those the set can pass), angled up to 30 degrees, close pairs, fights
  // with one or two opponents (courses.h). A hundred courses, about 200 launches: over the first 50 the
  // share of launches prepared 1 m before (90% asked) turned on a single launch, which any change of the
  // paths walked reshuffles (90/99 before the turn round toward a goal behind, 89/99 after; 92.8% and 91.8%
  // over the first 100).
  const CourseTotals t =
      course_totals(evaluate_courses(make_courses(builtin_course_options(1, true), 100), builtin_assets(), 2));
  REQUIRE(!t.checks.empty());
  for (const CourseCheck& c : t.checks) {
    INFO(c.name << ": " << c.measure);
    CHECK(c.pass);
  }
  // Clearance (clearance.h): no body more than 1 cm inside an object, no two bodies overlapping more than
  // 2 cm (a punch's striking arm on its target excepted), on any frame of any of them.
  INFO(t.min_object_what);
  INFO(t.min_character_what);
  CHECK(t.penetrating_courses == 0);
  CHECK(t.overlapping_courses == 0);
  CHECK(t.min_object_clearance >= -clearance_metric::kObjectTolerance);
  CHECK(t.min_character_clearance >= -clearance_metric::kCharacterTolerance);
}

TEST_CASE("two obstacles at an angle whose gap narrows below a crawl's length: the launch lines up where it widens") {
  // A bar crossed along +Z and a hurdle behind it turned 12 or 18 degrees either way, 1.3 or 1.8 m beyond it
  // at the middle, so that at one end the gap is 0.7-1.4 m: too little for the crawl's body, which reaches
  // 1.6 m beyond the bar by the frame it may be left, to come up between them. The user starts in front of
  // that end. Launched there, the crawl ran into the hurdle, came up under the bar and was set back out of
  // it on the side it came from, and the user never crossed. (Turned 24 degrees with 1.3 m, the crawl lines
  // up well, but the user then turns away from the hurdle before its jump, which clips the board by 2 cm:
  // README, "Not met".)
  std::vector<Scenario> courses;
  for (const float turn : {12.0f, 18.0f, 24.0f})
    for (const float side : {-1.0f, 1.0f})
      for (const float gap : {1.3f, 1.8f}) {
        const float narrow_x = 1.8f * side;  // the end where the hurdle comes closest
        const float heading = side * turn;  // turned so that it comes nearer the bar at narrow_x
        char text[640];
        std::snprintf(text, sizeof text,
                      "{\"auto\": true, \"name\": \"narrowing %+.0f deg %.1f m\", \"characters\": [{\"control\": \"user\", "
                      "\"position\": [%.2f, 0]}], \"objects\": [{\"type\": \"bar\", \"position\": [0, 3], \"size\": [5.8, 0.65, 0.2]}, "
                      "{\"type\": \"hurdle\", \"position\": [0, %.2f], \"heading\": %.1f, \"size\": [5.6, 0.4, 0.1]}], "
                      "\"goal\": [%.2f, %.2f]}",
                      heading, gap, narrow_x, 3.0f + gap, heading, narrow_x, 3.0f + gap + 4.0f);
        courses.push_back(parse_scenario(text, "narrowing"));
        // The gap at the user's side really is narrow: the hurdle's line there, less the rail and board.
        const float at_user = gap - narrow_x * std::tan(heading * kPi / 180.0f);
        CHECK(at_user - 0.15f < 1.3f);
      }
  const std::vector<CourseEvaluation> runs = evaluate_courses(courses, builtin_assets(), 2);
  for (const CourseEvaluation& e : runs) {
    INFO(e.name << ": " << e.clearance.min_object_what);
    CHECK(e.reached_goal);
    REQUIRE(e.launches.size() == 2);
    CHECK(e.launches[0].action == TargetAction::Crawl);
    CHECK(e.launches[1].action == TargetAction::Jump);
    CHECK(e.clearance.object_frames == 0);
  }
}

TEST_CASE("a bar close beyond a hurdle, at any angle: the crawl follows the jump without being slid back through the hurdle") {
  // Generated pairs: a hurdle 5 m ahead turned up to 15 degrees, a bar 1.1-1.7 m beyond it, up to 0.8 m to
  // either side and turned up to 30 degrees from it; the user starts up to 1.5 m to either side. The crawl
  // covers almost no ground before it kneels, so it cannot be entered late: out of a jump launched where the
  // bar is too near, it was slid back (half a metre in a third of a second in one case), through the hurdle
  // just jumped (a leg up to 10 cm in its board). The jump lines up where the crawl has room to follow on.
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f), gap(1.1f, 1.7f);
  std::vector<Scenario> courses;
  for (int k = 0; k < 16; ++k) {
    const float hurdle_heading = 15.0f * unit(rng), turn = 30.0f * unit(rng), beyond = gap(rng), aside = 0.8f * unit(rng);
    const float start_x = 1.5f * unit(rng);
    const float h = hurdle_heading * kPi / 180.0f, b = (hurdle_heading + turn) * kPi / 180.0f;
    const float bar_x = beyond * std::sin(h) + aside * std::cos(h), bar_z = 5.0f + beyond * std::cos(h) - aside * std::sin(h);
    char text[640];
    std::snprintf(text, sizeof text,
                  "{\"auto\": true, \"name\": \"pair %d\", \"characters\": [{\"control\": \"user\", \"position\": [%.3f, 0]}], "
                  "\"objects\": [{\"type\": \"hurdle\", \"position\": [0, 5], \"heading\": %.2f, \"size\": [5.0, 0.45, 0.1]}, "
                  "{\"type\": \"bar\", \"position\": [%.3f, %.3f], \"heading\": %.2f, \"size\": [5.0, 0.7, 0.1]}], "
                  "\"goal\": [%.3f, %.3f]}",
                  k, start_x, hurdle_heading, bar_x, bar_z, hurdle_heading + turn, bar_x + 4.0f * std::sin(b),
                  bar_z + 4.0f * std::cos(b));
    courses.push_back(parse_scenario(text, "hurdle and bar"));
  }
  const std::vector<CourseEvaluation> runs = evaluate_courses(courses, builtin_assets(), 2);
  for (const CourseEvaluation& e : runs) {
    INFO(e.name << ": " << e.clearance.min_object_what);
    CHECK(e.reached_goal);
    REQUIRE(e.launches.size() == 2);
    CHECK(e.launches[0].action == TargetAction::Jump);
    CHECK(e.launches[1].action == TargetAction::Crawl);
    CHECK(e.launches[1].slide_forward > -0.2f);
    CHECK(e.clearance.object_frames == 0);
  }
}

TEST_CASE("walked along a bar to a launch place away from its middle, the bar stays the source and is crawled prepared") {
  // A generated course and its mirror image: a hurdle, a bar 1.4 m beyond it turned 10 degrees, and a second
  // bar 1.3 m beyond that. Out of the jump the crawl's body has no room before the second bar where the
  // character lands, so it walks along the first bar, sideways, to where it has. Its middle then fell more
  // than 120 degrees off the facing: the bar was dropped as the source, the played alpha fell to 0, and the
  // bar, found again at its launch point, was crawled at alpha 0.54 (0.67 in the mirror).
  const char* text =
      "{\"auto\": true, \"name\": \"%s\", \"characters\": [{\"control\": \"user\", \"position\": [%.3f, 0]}], "
      "\"objects\": [{\"type\": \"hurdle\", \"position\": [%.3f, 4.5], \"heading\": %.3f, \"size\": [5.0, 0.45, 0.1]}, "
      "{\"type\": \"bar\", \"position\": [%.3f, 5.850], \"heading\": %.3f, \"size\": [5.0, 0.7, 0.1]}, "
      "{\"type\": \"bar\", \"position\": [%.3f, 7.197], \"heading\": %.3f, \"size\": [5.0, 0.7, 0.1]}], \"goal\": [%.3f, 11.129]}";
  std::vector<Scenario> courses;
  for (const float mirror : {1.0f, -1.0f}) {
    char json[720];
    std::snprintf(json, sizeof json, text, mirror > 0.0f ? "as drawn" : "mirrored", mirror * 0.382f, mirror * 0.040f,
                  mirror * -5.244f, mirror * -0.557f, mirror * -15.790f, mirror * -0.446f, mirror * -10.558f, mirror * -1.179f);
    courses.push_back(parse_scenario(json, "walk along"));
  }
  for (const CourseEvaluation& e : evaluate_courses(courses, builtin_assets(), 2)) {
    INFO(e.name);
    CHECK(e.reached_goal);
    REQUIRE(e.launches.size() == 3);
    CHECK(e.launches[0].action == TargetAction::Jump);
    CHECK(e.launches[1].action == TargetAction::Crawl);
    CHECK(e.launches[1].alpha_at_launch >= 0.85f);
  }
}

TEST_CASE("the next obstacle close beyond the crawl: its end clear of the hands, its usable span lined up with") {
  // A hurdle 1.6 m beyond a bar and 0.9 m to one side, so that its end (its foot on the floor) lies where the
  // crawl's hands reach, 0.2-0.4 m to the side of the body's middle line; and a beam 1.03 m high 1.6 m beyond
  // a narrower bar, 1.1 m to one side and turned 3 degrees from it, so that from the bar's near end the beam
  // could only be ducked under after walking along it (the body stood up under its rail on the way). The user starts in front of those ends. The crawl lines up where the hands
  // clear the foot and where the duck follows straight on.
  const char* hurdle_case =
      "{\"auto\": true, \"name\": \"hurdle end\", \"characters\": [{\"control\": \"user\", \"position\": [1.9, 0]}], "
      "\"objects\": [{\"type\": \"bar\", \"position\": [0, 3], \"size\": [5.85, 0.73, 0.06]}, "
      "{\"type\": \"hurdle\", \"position\": [-0.91, 4.59], \"size\": [5.15, 0.42, 0.09]}], \"goal\": [1.9, 9]}";
  const char* beam_case =
      "{\"auto\": true, \"name\": \"beam aside\", \"characters\": [{\"control\": \"user\", \"position\": [0.1, -0.07], \"heading\": 10.5}], "
      "\"objects\": [{\"type\": \"bar\", \"position\": [0, 3], \"heading\": 10.5, \"size\": [2.93, 0.68, 0.16]}, "
      "{\"type\": \"beam\", \"position\": [-1.13, 4.61], \"heading\": 7.7, \"size\": [3.98, 1.03, 0.08]}], \"goal\": [1.28, 9.88]}";
  const std::vector<CourseEvaluation> runs =
      evaluate_courses({parse_scenario(hurdle_case, "hurdle end"), parse_scenario(beam_case, "beam aside")}, builtin_assets(), 2);
  const TargetAction second[] = {TargetAction::Jump, TargetAction::Duck};
  for (size_t k = 0; k < runs.size(); ++k) {
    const CourseEvaluation& e = runs[k];
    INFO(e.name << ": " << e.clearance.min_object_what);
    CHECK(e.reached_goal);
    REQUIRE(e.launches.size() == 2);
    CHECK(e.launches[0].action == TargetAction::Crawl);
    CHECK(e.launches[1].action == second[k]);
    CHECK(e.clearance.object_frames == 0);
  }
}

TEST_CASE("two opponents beaten before a waypoint: neither steps aside onto it, and the goal is reached") {
  // Random course 10 of seed 99: the user turns toward the opponents coming at it 1 m short of its first
  // waypoint, which it has not passed, and beats both. A beaten opponent stepped aside from the way the user
  // faced (toward whom it punched), and the first one stood 0.4 m from that waypoint: bodies keep apart, so
  // the user circled it for 40 s and never reached it. Stepping aside from the way to the user's next
  // waypoint, they leave it free.
  const Scenario course = builtin_random_course(99, 10);
  REQUIRE(course.objects.size() == 2);
  REQUIRE(course.goal.size() == 3);
  World world(course, builtin_assets());
  world.set_auto(true);
  float nearest_to_waypoint = INFINITY;  // a defeated opponent's root from the user's current waypoint
  world.run_until_done(60.0f, 1.0f, [&](const World& w) {
    const WorldCharacter& user = w.characters()[0];
    if (user.goal.size() < 2) return;  // no waypoint left: the goal itself
    for (const WorldCharacter& c : w.characters()) {
      if (c.control == Control::Opponent && c.defeated)
        nearest_to_waypoint = std::min(nearest_to_waypoint, glm::length(c.position - user.goal.front()));
    }
  });
  CHECK(world.goal_reached());
  // Farther than a body's width plus the goal radius: the user can stand on the waypoint beside it.
  CHECK(nearest_to_waypoint > 1.0f);
  const CourseEvaluation e = evaluate_courses({course}, builtin_assets(), 1)[0];
  CHECK(e.reached_goal);
  CHECK(e.circling_seconds == 0.0f);
}

TEST_CASE("out of a recorded kick that ends turned, the hurdle 1.5 m on stays the source and preparation is kept") {
  // Random course 74 of seed 1 on the daz43 set. The kick's follow-through leaves the pelvis turned; the walk
  // it is left for (kept preparation) is placed by the floor alignment of the two clips and faces 27 degrees
  // farther off, so the hurdle fell just past the kept source's 120 degrees for 0.3 s: nothing was in range,
  // alpha relaxed from 1.0 to 0.21 and rose again. Through the cross-fade the body shown still faces it.
  const auto [assets, course] = set_random_course("daz43", 1, 74);
  REQUIRE(course.objects.size() == 3);
  REQUIRE(course.objects[0].type == ObjectType::Ball);
  REQUIRE(course.objects[1].type == ObjectType::Hurdle);
  const CourseEvaluation e = evaluate_courses({course}, assets, 1)[0];
  INFO(e.description);
  CHECK(e.reached_goal);
  REQUIRE(e.launches.size() == 3);
  CHECK(e.launches[0].action == TargetAction::Kick);
  CHECK(e.launches[1].action == TargetAction::Jump);
  REQUIRE_FALSE(e.kept.empty());
  CHECK(e.kept[0].first == 0);
  CHECK(e.kept[0].second == 1);
  CHECK(e.kept[0].min_alpha >= 0.5f);
}

TEST_CASE("the courses that wove (seed 777, among its first 40) walk to their goals without zigzagging") {
  // On these twelve built-in courses the turn clips went left, right and left again within 3 s (3 to 12
  // reversals each, 173 over the first 40 courses): a turn toward the goal played its whole gait cycle,
  // swung the heading past the goal and the next action turned back. A turn toward the goal now ends once
  // the goal's bearing crosses to the other side.
  const std::vector<Scenario> first40 = make_courses(builtin_course_options(777, false), 40);
  std::vector<Scenario> wove;
  for (int k : {2, 10, 12, 17, 23, 24, 26, 27, 28, 32, 34, 35}) wove.push_back(first40[static_cast<size_t>(k)]);
  const std::vector<CourseEvaluation> runs = evaluate_courses(wove, builtin_assets(), 2);
  for (const CourseEvaluation& e : runs) {
    CAPTURE(e.name);
    CAPTURE(e.turn_reversals);
    CHECK(e.reached_goal);
    CHECK(e.most_reversals_in_window < course_metric::kWeaveReversals);
  }
}

TEST_CASE("a recorded duck whose pelvis turns 80 degrees keeps the hurdle behind its beam as the source, and jumps it prepared") {
  // Random course 75 of seed 1 on cmu31: a hurdle 1.6 m beyond a beam. The recorded duck goes straight
  // under the beam but its pelvis turns up to 80 degrees, and the hurdle fell out of the source's kept
  // angle: the duck ended with nothing ahead, alpha dropped to 0, and the jump launched unprepared out of a
  // turn beside the board, a knee 1.5 cm into it. The source is now also kept ahead of the heading the clip
  // was started facing.
  const auto [assets, course] = set_random_course("cmu31", 1, 75);
  REQUIRE(course.objects.size() == 4);
  REQUIRE(course.objects[2].action == TargetAction::Duck);
  REQUIRE(course.objects[3].action == TargetAction::Jump);
  const CourseEvaluation e = evaluate_courses({course}, assets, 1)[0];
  INFO(e.clearance.min_object_what);
  CHECK(e.reached_goal);
  REQUIRE(e.launches.size() == 4);
  for (const CourseLaunch& l : e.launches) {
    CAPTURE(l.time);
    CHECK(l.alpha_at_launch >= 0.85f);
  }
  CHECK(e.launches[3].object == 3);
  CHECK(e.clearance.object_frames == 0);
}

TEST_CASE("a ball met off to the side is turned to and kicked, not walked past") {
  // Random course 10 of seed 777: out of two hurdles the user walks toward its waypoint with the ball ahead,
  // and comes within the kick's reach of it 51 degrees off the facing, past the 45 degrees a source counts
  // as ahead. Without an arrival the character walked on past it and left it unkicked.
  const Scenario course = builtin_random_course(777, 10);
  REQUIRE(course.objects.size() == 3);
  REQUIRE(course.objects[2].type == ObjectType::Ball);
  check_goal_and_one_prepared_kick(course);
}

TEST_CASE("a ball passed 1.2 m to the side within a metre of its launch distance is turned to and kicked") {
  // Random course 13 of seed 777: after a duck the user walks on with the ball off to its side, never
  // nearer than 0.31 m short of its launch distance, so never within the arrival radius: it walked past
  // and left the ball. A ball within a metre of its launch distance is now faced however it was approached.
  const Scenario course = builtin_random_course(777, 13);
  check_goal_and_one_prepared_kick(course);
}

TEST_CASE("a ball off to one side of the way, the goal beyond on the other: the ball is walked to and kicked") {
  // A ball 3-5.5 m away and 25-55 degrees to one side, the goal 9-14 m away and up to 20 degrees to the
  // other. The policy is rewarded for the goal alone (Eq. 14-17), so it walked toward the goal; a turn
  // toward the ball was soon undone, even with the character prepared and its launch point 1.3 m ahead,
  // and 6 of these 8 balls were left (22 of 24 in a larger draw). Unattended, the user now makes for the
  // ball while it is the source in range, as for an opponent.
  std::mt19937 rng(66);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  std::vector<Scenario> courses;
  for (int k = 0; k < 8; ++k) {
    const float side = k % 2 == 0 ? 1.0f : -1.0f;
    const float ball_bearing = side * (25.0f + 30.0f * unit(rng)) * kPi / 180.0f, ball_distance = 3.0f + 2.5f * unit(rng);
    const float goal_bearing = -side * 20.0f * unit(rng) * kPi / 180.0f, goal_distance = 9.0f + 5.0f * unit(rng);
    const float heading_deg = 40.0f * unit(rng) - 20.0f;
    const std::string text =
        R"({"auto": true, "characters": [{"position": [0, 0], "heading": )" + std::to_string(heading_deg) +
        R"(, "control": "user"}], "objects": [{"type": "ball", "action": "kick", "size": [0.22, 0.22, 0.22], "position": [)" +
        std::to_string(ball_distance * std::sin(ball_bearing)) + ", " + std::to_string(ball_distance * std::cos(ball_bearing)) +
        R"(]}], "goal": [)" + std::to_string(goal_distance * std::sin(goal_bearing)) + ", " +
        std::to_string(goal_distance * std::cos(goal_bearing)) + "]}";
    courses.push_back(parse_scenario(text, "ball to the side " + std::to_string(k)));
  }
  const std::vector<CourseEvaluation> runs = evaluate_courses(courses, builtin_assets(), 2);
  for (size_t k = 0; k < runs.size(); ++k) {
    CAPTURE(k);
    const CourseEvaluation& e = runs[k];
    CHECK(e.reached_goal);
    CHECK(e.objects_unused == 0);
    CHECK(e.launches.size() == 1);
    for (const CourseLaunch& l : e.launches) {
      CHECK(l.action == TargetAction::Kick);
      CHECK(l.alpha_at_launch >= 0.85f);
    }
  }
}

TEST_CASE("an opponent beyond a bar, beam or hurdle waits there while the user crosses it, then they fight") {
  // A bar, beam or hurdle 4-5.5 m ahead, an opponent 5-8 m beyond it and up to 45 degrees to either side,
  // the goal past both. The user made for the opponent and the opponent for the user: they met face to face
  // across the rail, each short of its launch point, and stood there for good: 4 of these 6 never reached
  // the goal, and none crossed the obstacle and then punched. The user now crosses first, and the opponent
  // waits on its side with room for the user's clip to come out.
  std::mt19937 rng(88);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  const char* kinds[] = {R"("type": "bar", "action": "crawl", "size": [4, 0.7, 0.1])",
                         R"("type": "beam", "action": "duck", "size": [4, 1.2, 0.1])",
                         R"("type": "hurdle", "action": "jump", "size": [4, 0.45, 0.1])"};
  const TargetAction crossings[] = {TargetAction::Crawl, TargetAction::Duck, TargetAction::Jump};
  std::vector<Scenario> courses;
  for (int k = 0; k < 6; ++k) {
    const float z = 4.0f + 1.5f * unit(rng), heading_deg = 40.0f * unit(rng) - 20.0f;
    const float bearing = (90.0f * unit(rng) - 45.0f) * kPi / 180.0f, beyond = 5.0f + 3.0f * unit(rng);
    const float opponent_x = beyond * std::sin(bearing), opponent_z = z + beyond * std::cos(bearing);
    const std::string text =
        R"({"auto": true, "characters": [{"position": [0, 0], "heading": 0, "control": "user"}], "objects": [{)" +
        std::string(kinds[k % 3]) + R"(, "position": [0, )" + std::to_string(z) + R"(], "heading": )" + std::to_string(heading_deg) +
        R"(}, {"type": "opponent", "action": "punch_right", "position": [)" + std::to_string(opponent_x) + ", " +
        std::to_string(opponent_z) + R"(], "heading": )" + std::to_string(180.0f + bearing * 180.0f / kPi) +
        R"(}], "goal": [0, )" + std::to_string(z + 9.0f) + "]}";
    courses.push_back(parse_scenario(text, "opponent beyond " + std::to_string(k)));
  }
  check_generated_courses(courses, [&](size_t k, const CourseEvaluation& e) {
    std::vector<TargetAction> launched;  // the user's
    for (const CourseLaunch& l : e.launches) {
      launched.push_back(l.action);
      CHECK(l.alpha_at_launch >= 0.85f);
    }
    const std::vector<TargetAction> expected{crossings[k % 3], TargetAction::PunchRight};
    CHECK(launched == expected);
  });
}

TEST_CASE("started a step from a beam or a bar, the character prepares where it stands before it goes under") {
  // The duck begins 2.5 m before its beam and the crawl 1.1 m before its bar, so a character started
  // 0.7-1.5 m from one may already be past its launch point. It launched at once, unprepared: five of these
  // six at alpha 0.04, the sixth at 0.76. It now stands and prepares first.
  std::mt19937 rng(99);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  const char* kinds[] = {R"("type": "beam", "action": "duck", "size": [4, 1.2, 0.1])",
                         R"("type": "bar", "action": "crawl", "size": [4, 0.7, 0.1])"};
  std::vector<Scenario> courses;
  for (int k = 0; k < 6; ++k) {
    const float z = 0.7f + 0.8f * unit(rng), heading_deg = 30.0f * unit(rng) - 15.0f, obstacle_deg = 30.0f * unit(rng) - 15.0f;
    const std::string text = R"({"auto": true, "characters": [{"position": [0, 0], "heading": )" + std::to_string(heading_deg) +
                             R"(, "control": "user"}], "objects": [{)" + std::string(kinds[k % 2]) + R"(, "position": [0, )" +
                             std::to_string(z) + R"(], "heading": )" + std::to_string(obstacle_deg) + R"(}], "goal": [0, )" +
                             std::to_string(z + 4.0f) + "]}";
    courses.push_back(parse_scenario(text, "a step from it " + std::to_string(k)));
  }
  check_generated_courses(courses, [](size_t k, const CourseEvaluation& e) {
    REQUIRE(e.launches.size() == 1);
    CHECK(e.launches[0].action == (k % 2 == 0 ? TargetAction::Duck : TargetAction::Crawl));
    CHECK(e.launches[0].alpha_at_launch >= 0.85f);
  });
}

TEST_CASE("a hurdle jumped beside a beaten opponent: the jump is not shoved into the board") {
  // Random course 111 of seed 31337: the user beats an opponent, walks along the hurdle behind it to its
  // launch place and launches 0.3 m too near, so the clip is slid back onto its launch point, toward the
  // opponent standing 0.9 m away. Kept apart, the user took the whole shove (it was the one closing in),
  // the slide was undone, and a foot went 8 cm into the board. The one crossing now gives no way.
  const Scenario course = builtin_random_course(31337, 111);
  REQUIRE(course.objects.size() == 3);
  REQUIRE(course.objects[1].type == ObjectType::Hurdle);
  const CourseEvaluation e = evaluate_courses({course}, builtin_assets(), 1)[0];
  INFO(e.clearance.min_object_what);
  CHECK(e.reached_goal);
  int jumps = 0;
  for (const CourseLaunch& l : e.launches) {
    if (l.action != TargetAction::Jump) continue;
    ++jumps;
    CHECK(l.min_clearance >= -clearance_metric::kObjectTolerance);
  }
  CHECK(jumps == 2);
  CHECK(e.clearance.object_frames == 0);
}

TEST_CASE("on a set with no idle clip the user stops at its goal and stands there") {
  // cmu31's takes have no quiet standing: a character stood on the walk, and walked on past its goal.
  const Scenario s = load_scenario(test::repo() + "/assets/scenarios/jump_cmu31.json");
  const auto assets = prepare_world_assets(s, load_scenario_params(s), test::tmp_dir() + "/policy-cache");
  CHECK(assets->set->clips[static_cast<size_t>(assets->idle_node)].role == Role::Idle);
  World world(s, assets);
  world.set_auto(true);
  float reached = -1.0f;
  glm::vec2 one_second_on(0.0f);
  for (int k = 0; k < 60 * 60 && (reached < 0.0f || world.time() < reached + 4.0f); ++k) {
    world.step();
    const WorldCharacter& u = world.characters()[static_cast<size_t>(world.user())];
    if (u.reached_goal && reached < 0.0f) reached = world.time();
    if (reached >= 0.0f && world.time() <= reached + 1.0f) one_second_on = u.position;
  }
  REQUIRE(reached >= 0.0f);
  const WorldCharacter& u = world.characters()[static_cast<size_t>(world.user())];
  CHECK(glm::length(u.position - one_second_on) < 0.05f);  // three seconds standing
  CHECK(glm::length(u.position - s.goal.back()) <= world.params().reward.goal_radius + 0.3f);
}

TEST_CASE("a source straight ahead is walked up to, not swung out from and back") {
  // Balls, hurdles, bars and beams 4-7 m ahead, up to 0.3 m to either side, the character starting up to
  // 15 degrees off them. The policy values a turn away from a source dead ahead within a few per cent of
  // walking on; chosen, its gait cycle swung the approach out past 45 degrees and back (10 of these 12
  // without RuntimeParams::keep_source_ahead), and a turn toward a source a few degrees off overshot it
  // as far.
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  const char* kinds[] = {R"("type": "ball", "action": "kick", "size": [0.22, 0.22, 0.22])",
                         R"("type": "hurdle", "action": "jump", "size": [1.2, 0.45, 0.1])",
                         R"("type": "bar", "action": "crawl", "size": [1.6, 0.6, 0.1])",
                         R"("type": "beam", "action": "duck", "size": [1.6, 1.2, 0.1])"};
  for (int k = 0; k < 12; ++k) {
    const float ahead = 4.0f + 3.0f * unit(rng), side = 0.6f * unit(rng) - 0.3f, heading_deg = 30.0f * unit(rng) - 15.0f;
    const bool ball = k % 4 == 0;
    const std::string text = R"({"auto": true, "characters": [{"position": [0, 0], "heading": )" + std::to_string(heading_deg) +
                             R"(, "control": "user"}], "objects": [{)" + kinds[k % 4] + R"(, "position": [)" +
                             std::to_string(side) + ", " + std::to_string(ahead) + R"(]}], "goal": [)" + std::to_string(side) +
                             ", " + std::to_string(ahead + (ball ? 0.0f : 2.0f)) + "]}";
    World world(parse_scenario(text, "straight ahead"), builtin_assets());
    const glm::vec2 object(side, ahead);
    float widest = 0.0f;  // the object's largest bearing off the facing, until a metre short of it
    for (int tick = 0; tick < 20 * 60 && world.launches().empty(); ++tick) {
      world.step();
      const WorldCharacter& c = world.characters()[static_cast<size_t>(world.user())];
      if (object.y - c.position.y > 1.0f) widest = std::max(widest, std::fabs(bearing_to(c.position, c.heading, object)));
    }
    CAPTURE(text);
    CHECK(widest * 180.0f / kPi <= std::fabs(heading_deg) + 30.0f);
    REQUIRE(world.launches().size() == 1);
    CHECK(world.launches()[0].alpha_at_launch >= 0.85f);
  }
}

TEST_CASE("a goal steered to the side is turned to, though a source lies straight ahead") {
  // A ball 3 m ahead and the goal 6 m to the right (a user steering away from it): the turns toward the
  // goal take the ball off the facing, and are still chosen (only a turn that leaves both the source and
  // the goal further off is passed over).
  const Scenario s = parse_scenario(
      R"({"characters": [{"position": [0, 0], "heading": 0, "control": "user"}],
          "objects": [{"type": "ball", "action": "kick", "size": [0.22, 0.22, 0.22], "position": [0, 3]}],
          "goal": [-6, 1]})",
      "goal to the side");
  World world(s, builtin_assets());
  run(world, 3.0f);
  const WorldCharacter& c = world.characters()[static_cast<size_t>(world.user())];
  CHECK(std::fabs(bearing_to(c.position, c.heading, {-6.0f, 1.0f})) * 180.0f / kPi < 30.0f);
  run(world, 6.0f);
  CHECK(world.goal_reached());
}

TEST_CASE("the fight's user walks straight up to the opponent 9 m ahead, not out and back") {
  // The first opponent is beyond RuntimeParams::preparation_range at the start, but it is the source and
  // lies ahead: a turn away from it is passed over there too. Before, the user turned 78 degrees off to the
  // right and back in its first 4 s.
  World world(load_scenario(test::repo() + "/assets/scenarios/fight.json"), builtin_assets());
  float widest = 0.0f;
  while (world.time() < 20.0f && launch_of(world, TargetAction::PunchRight) == nullptr) {
    world.step();
    const WorldCharacter& c = world.characters()[static_cast<size_t>(world.user())];
    if (!c.in_target) widest = std::max(widest, std::fabs(c.heading));
  }
  REQUIRE(launch_of(world, TargetAction::PunchRight) != nullptr);
  CHECK(widest * 180.0f / kPi < 20.0f);
}
