#include "engine/world/courses.h"

#include <doctest/doctest.h>

#include <cmath>
#include <set>
#include <stdexcept>

#include <glm/geometric.hpp>

#include "engine/library/generated.h"
#include "tests/support/angles.h"

using namespace prep;

namespace {

using test::kPi;

glm::vec2 forward_of(float heading) { return {std::sin(heading), std::cos(heading)}; }
glm::vec2 left_of(float heading) { return {std::cos(heading), -std::sin(heading)}; }
float wrap(float a) { return std::remainder(a, 2.0f * kPi); }
bool is_across(ObjectType t) { return t == ObjectType::Bar || t == ObjectType::Beam || t == ObjectType::Hurdle; }

// The footprint of an object as the generator documents it: width x depth, a ball's size, an opponent's 0.6 m.
glm::vec2 half_extent(const ScenarioObject& o) {
  return o.type == ObjectType::Opponent ? glm::vec2(0.3f) : glm::vec2(0.5f * o.size.x, 0.5f * o.size.z);
}
bool inside(const ScenarioObject& o, glm::vec2 p) {
  const glm::vec2 d = p - o.position, h = half_extent(o);
  return std::fabs(glm::dot(d, left_of(o.heading))) <= h.x && std::fabs(glm::dot(d, forward_of(o.heading))) <= h.y;
}
// Points covering an object's footprint (a 9 x 5 grid over it, its edges included).
std::vector<glm::vec2> samples(const ScenarioObject& o) {
  std::vector<glm::vec2> out;
  const glm::vec2 h = half_extent(o);
  for (int i = 0; i <= 8; ++i)
    for (int k = 0; k <= 4; ++k)
      out.push_back(o.position + (-h.x + h.x * i / 4.0f) * left_of(o.heading) + (-h.y + h.y * k / 2.0f) * forward_of(o.heading));
  return out;
}

// Where the route crosses an across obstacle's axis: the leg index and the parameter along the axis (m
// from its middle); leg -1 when no leg crosses it. Counts the crossings.
struct Crossing {
  int leg = -1, count = 0;
  float along = 0;
};
Crossing crossing_of(const ScenarioObject& o, const std::vector<glm::vec2>& route) {
  Crossing c;
  const glm::vec2 axis = left_of(o.heading);
  for (size_t k = 0; k + 1 < route.size(); ++k) {
    const glm::vec2 a = route[k], b = route[k + 1];
    const float da = glm::dot(a - o.position, forward_of(o.heading)), db = glm::dot(b - o.position, forward_of(o.heading));
    if ((da > 0) == (db > 0)) continue;
    const glm::vec2 p = a + (b - a) * (da / (da - db));
    const float along = glm::dot(p - o.position, axis);
    if (std::fabs(along) > 0.5f * o.size.x) continue;
    ++c.count;
    c.leg = static_cast<int>(k);
    c.along = along;
  }
  return c;
}

bool same(const Scenario& a, const Scenario& b) {
  if (a.name != b.name || a.description != b.description || a.goal != b.goal || a.objects.size() != b.objects.size() ||
      a.characters.size() != b.characters.size())
    return false;
  for (size_t k = 0; k < a.objects.size(); ++k) {
    const ScenarioObject &x = a.objects[k], &y = b.objects[k];
    if (x.type != y.type || x.action != y.action || x.position != y.position || x.heading != y.heading || x.size != y.size) return false;
  }
  return a.characters[0].position == b.characters[0].position && a.characters[0].heading == b.characters[0].heading;
}

}  // namespace

TEST_CASE("random courses: the same (seed, index) gives the same course, another seed another") {
  CourseOptions o;
  o.seed = 7;
  const std::vector<Scenario> five = make_courses(o, 5);
  REQUIRE(five.size() == 5);
  for (int k = 0; k < 5; ++k) {
    CAPTURE(k);
    CHECK(same(five[static_cast<size_t>(k)], make_course(o, k)));  // per index, whatever N
    CHECK(five[static_cast<size_t>(k)].name == "random-7-" + std::to_string(k));
  }
  CHECK_FALSE(same(five[0], five[1]));
  CourseOptions other = o;
  other.seed = 8;
  CHECK_FALSE(same(make_course(other, 0), five[0]));
  CHECK_THROWS_AS(make_courses(o, 0), std::invalid_argument);
  CHECK_THROWS_AS(make_courses(o, -3), std::invalid_argument);
}

TEST_CASE("random courses: every kind, the clips' obstacle sizes, angles within 30 degrees, nothing overlapping") {
  CourseOptions o;
  o.seed = 1;
  const std::vector<Scenario> courses = make_courses(o, 40);
  std::set<ObjectType> types;
  std::set<TargetAction> actions;
  std::set<size_t> waypoint_counts;
  int turned_starts = 0, close_pairs = 0, far_pairs = 0, angled = 0;
  const library::Obstacle bar = library::obstacle_of("crawl"), beam = library::obstacle_of("duck"), hurdle = library::obstacle_of("jump");
  for (const Scenario& s : courses) {
    CAPTURE(s.name);
    CAPTURE(s.description);
    CHECK(s.auto_launch);
    CHECK(s.motions == "builtin");
    REQUIRE(s.user() == 0);
    REQUIRE_FALSE(s.goal.empty());
    waypoint_counts.insert(s.goal.size() - 1);
    const std::vector<glm::vec2> route = course_route(s);
    CHECK(route.front() == s.characters[0].position);
    const float first_leg = std::atan2(route[1].x - route[0].x, route[1].y - route[0].y);
    turned_starts += std::fabs(wrap(s.characters[0].heading - first_leg)) > kPi / 2;
    for (size_t i = 0; i < s.objects.size(); ++i) {
      const ScenarioObject& obj = s.objects[i];
      CAPTURE(i);
      types.insert(obj.type);
      actions.insert(obj.action);
      CHECK(accepts(obj.type, obj.action));
      if (obj.type == ObjectType::Bar) CHECK(obj.size.y == doctest::Approx(bar.height));
      if (obj.type == ObjectType::Beam) CHECK(obj.size.y == doctest::Approx(beam.height));
      if (obj.type == ObjectType::Hurdle) CHECK(obj.size.y == doctest::Approx(hurdle.height));
      if (obj.type == ObjectType::Bar) CHECK(obj.size.z == doctest::Approx(bar.z_far - bar.z_near));
      if (obj.type == ObjectType::Ball) CHECK(obj.size == glm::vec3(0.22f));
      if (is_across(obj.type)) {
        CHECK(obj.size.x >= 4.5f);
        // The route crosses it once, within 0.8 m of its middle, at most 30 degrees off its normal.
        const Crossing c = crossing_of(obj, route);
        REQUIRE(c.count == 1);
        CHECK(std::fabs(c.along) <= 0.8f + 1e-3f);
        const glm::vec2 leg = route[static_cast<size_t>(c.leg) + 1] - route[static_cast<size_t>(c.leg)];
        const float off = std::fabs(wrap(obj.heading - std::atan2(leg.x, leg.y)));
        CHECK(off <= 30.0f * kPi / 180.0f + 1e-4f);
        angled += off > 15.0f * kPi / 180.0f;
      }
      // No footprint overlaps another, and none covers the start, a waypoint or the goal.
      for (size_t k = 0; k < s.objects.size(); ++k) {
        if (k == i) continue;
        for (glm::vec2 p : samples(obj)) CHECK_FALSE(inside(s.objects[k], p));
      }
      for (glm::vec2 p : route) CHECK_FALSE(inside(obj, p));
      if (i > 0) {
        const float d = glm::length(obj.position - s.objects[i - 1].position);
        close_pairs += d < 3.0f;
        far_pairs += d > 6.0f;
        CHECK(d >= 1.2f);  // 1.5 m along the route at the least, less what the offsets take
      }
    }
  }
  for (ObjectType t : {ObjectType::Ball, ObjectType::Bar, ObjectType::Beam, ObjectType::Hurdle, ObjectType::Opponent}) {
    CAPTURE(object_type_name(t));
    CHECK(types.count(t) == 1);
  }
  CHECK(actions.size() == 6);
  CHECK(waypoint_counts == std::set<size_t>{0, 1, 2});
  CHECK(turned_starts > 0);
  CHECK(close_pairs > 0);
  CHECK(far_pairs > 0);
  CHECK(angled > 0);
}

TEST_CASE("random courses: only the object kinds the motion set can act on") {
  CourseOptions o;
  o.actions = {TargetAction::Jump, TargetAction::Kick};  // what the daz43 set has
  std::set<ObjectType> types;
  for (const Scenario& s : make_courses(o, 20))
    for (const ScenarioObject& obj : s.objects) types.insert(obj.type);
  CHECK(types == std::set<ObjectType>{ObjectType::Hurdle, ObjectType::Ball});

  o.actions = {TargetAction::PunchLeft};
  for (const Scenario& s : make_courses(o, 5)) {
    REQUIRE_FALSE(s.objects.empty());
    for (const ScenarioObject& obj : s.objects) {
      CHECK(obj.type == ObjectType::Opponent);
      CHECK(obj.action == TargetAction::PunchLeft);
    }
  }
  o.actions.clear();
  CHECK_THROWS_AS(make_course(o, 0), std::invalid_argument);
}

TEST_CASE("a random course written as scenario JSON reads back as the same course") {
  CourseOptions o;
  o.seed = 5;
  for (const Scenario& s : make_courses(o, 6)) {
    CAPTURE(s.name);
    const Scenario back = parse_scenario(scenario_json(s), "course.json");
    CHECK(back.name == s.name);
    CHECK(back.description == s.description);
    CHECK(back.auto_launch);
    CHECK(back.motions == s.motions);
    REQUIRE(back.goal.size() == s.goal.size());
    for (size_t k = 0; k < s.goal.size(); ++k) CHECK(glm::length(back.goal[k] - s.goal[k]) < 1e-5f);
    REQUIRE(back.characters.size() == 1);
    CHECK(back.characters[0].heading == doctest::Approx(s.characters[0].heading).epsilon(1e-5));
    REQUIRE(back.objects.size() == s.objects.size());
    for (size_t k = 0; k < s.objects.size(); ++k) {
      CHECK(back.objects[k].type == s.objects[k].type);
      CHECK(back.objects[k].action == s.objects[k].action);
      CHECK(glm::length(back.objects[k].position - s.objects[k].position) < 1e-5f);
      CHECK(back.objects[k].heading == doctest::Approx(s.objects[k].heading).epsilon(1e-5));
      CHECK(glm::length(back.objects[k].size - s.objects[k].size) < 1e-5f);
    }
  }
}
