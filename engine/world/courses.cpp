#include "engine/world/courses.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <glm/geometric.hpp>

#include "engine/library/generated.h"
#include "engine/world/floor.h"

namespace prep {

namespace {

using floor_plane::forward_of;
using floor_plane::is_across;
using floor_plane::kDegrees;
using floor_plane::kPi;
using floor_plane::left_of;
using floor_plane::wrap_angle;

// SplitMix64 (Steele, Lea and Flood 2014): a tiny generator whose output is fixed by its definition, so a
// course is the same scenario with any compiler and standard library.
class Random {
 public:
  Random(std::uint64_t seed, std::uint64_t index) : state_(seed) {
    state_ = next() ^ (index * 0xD1B54A32D192ED03ull + 0x8CB92BA72F3D8DD7ull);
  }
  std::uint64_t next() {
    std::uint64_t z = (state_ += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  float uniform(float lo, float hi) {  // U(lo, hi), 24 bits
    return lo + (hi - lo) * static_cast<float>(next() >> 40) * (1.0f / 16777216.0f);
  }
  bool chance(float p) { return uniform(0.0f, 1.0f) < p; }
  int below(int n) { return static_cast<int>(next() % static_cast<std::uint64_t>(n)); }
  float sign() { return chance(0.5f) ? 1.0f : -1.0f; }

 private:
  std::uint64_t state_;
};

bool has(const std::vector<TargetAction>& actions, TargetAction a) {
  return std::find(actions.begin(), actions.end(), a) != actions.end();
}

// [width, height, depth] of the obstacle a built-in clip was made for; the width is the course's.
glm::vec3 clip_obstacle(const char* clip_name) {
  const library::Obstacle o = library::obstacle_of(clip_name);
  return {0.0f, o.height, o.z_far - o.z_near};
}
struct ObstacleSizes {
  glm::vec3 bar = clip_obstacle("crawl"), beam = clip_obstacle("duck"), hurdle = clip_obstacle("jump");
};
const ObstacleSizes& obstacle_sizes() {
  static const ObstacleSizes sizes;  // generating the clips takes a moment: once per process
  return sizes;
}

constexpr float kOpponentFootprint = 0.6f;
constexpr float kObjectGap = 0.3f;    // m kept between two objects' footprints
constexpr float kPointGap = 1.0f;     // m kept between a footprint and the start, a waypoint or the goal
constexpr int kObjectTries = 20;      // draws of an object's heading and offset before the course is redrawn
constexpr int kCourseTries = 100;

// An object's footprint on the floor: a rectangle of half extents `half` along its axis (left_of(heading),
// an obstacle's width) and its crossing direction (forward_of(heading), its depth).
struct Footprint {
  glm::vec2 centre{0.0f};
  float heading = 0.0f;
  glm::vec2 half{0.0f};
};

Footprint footprint_of(const ScenarioObject& o) {
  Footprint f{o.position, o.heading, {0.5f * o.size.x, 0.5f * o.size.z}};
  if (o.type == ObjectType::Opponent) f.half = glm::vec2(0.5f * kOpponentFootprint);
  return f;
}

// Half the footprint's extent along a unit direction.
float extent_along(const Footprint& f, glm::vec2 axis) {
  return f.half.x * std::fabs(glm::dot(left_of(f.heading), axis)) + f.half.y * std::fabs(glm::dot(forward_of(f.heading), axis));
}

// Separating axes of two rectangles, each grown by `gap` / 2.
bool too_close(const Footprint& a, const Footprint& b, float gap) {
  const glm::vec2 d = b.centre - a.centre;
  for (glm::vec2 axis : {left_of(a.heading), forward_of(a.heading), left_of(b.heading), forward_of(b.heading)})
    if (std::fabs(glm::dot(d, axis)) > extent_along(a, axis) + extent_along(b, axis) + gap) return false;
  return true;
}

bool too_close(const Footprint& f, glm::vec2 p, float gap) {
  const glm::vec2 d = p - f.centre;
  return std::fabs(glm::dot(d, left_of(f.heading))) <= f.half.x + gap && std::fabs(glm::dot(d, forward_of(f.heading))) <= f.half.y + gap;
}

float cross(glm::vec2 a, glm::vec2 b) { return a.x * b.y - a.y * b.x; }

bool segments_cross(glm::vec2 p0, glm::vec2 p1, glm::vec2 q0, glm::vec2 q1) {
  const glm::vec2 r = p1 - p0, s = q1 - q0;
  const float denom = cross(r, s);
  if (std::fabs(denom) < 1e-9f) return false;  // parallel
  const float t = cross(q0 - p0, s) / denom, u = cross(q0 - p0, r) / denom;
  return t >= 0.0f && t <= 1.0f && u >= 0.0f && u <= 1.0f;
}

// The rules of the header: footprints apart, clear of the start, waypoints and goal, each obstacle crossed
// by the route once.
bool course_is_sound(const Scenario& s) {
  const std::vector<glm::vec2> route = course_route(s);
  for (size_t i = 0; i < s.objects.size(); ++i) {
    const Footprint f = footprint_of(s.objects[i]);
    for (glm::vec2 p : route)
      if (too_close(f, p, kPointGap)) return false;
    if (!is_across(s.objects[i].type)) continue;
    const glm::vec2 axis = f.half.x * left_of(f.heading);
    int crossings = 0;
    for (size_t k = 0; k + 1 < route.size(); ++k) crossings += segments_cross(f.centre - axis, f.centre + axis, route[k], route[k + 1]);
    if (crossings != 1) return false;
  }
  return true;
}

// What lies along a course, in order.
enum class Item { Opponent, Ball, Bar, Beam, Hurdle };

// One draw of a course (false: an object found no place; the caller draws the course again).
bool draw_course(const CourseOptions& o, Random& rng, Scenario& s) {
  // The kinds the set can act on.
  std::vector<TargetAction> punches;
  for (TargetAction a : {TargetAction::PunchLeft, TargetAction::PunchRight})
    if (has(o.actions, a)) punches.push_back(a);
  std::vector<Item> kinds;
  if (has(o.actions, TargetAction::Kick)) kinds.push_back(Item::Ball);
  // An obstacle kind whose clip passes none of the heights drawn from (heights_of) is left out.
  auto passable = [&](TargetAction a) {
    const size_t k = static_cast<size_t>(a);
    return has(o.actions, a) && (o.heights.size() <= k || o.heights[k].x <= o.heights[k].y);
  };
  if (passable(TargetAction::Crawl)) kinds.push_back(Item::Bar);
  if (passable(TargetAction::Duck)) kinds.push_back(Item::Beam);
  if (passable(TargetAction::Jump)) kinds.push_back(Item::Hurdle);

  // What the course holds, in order.
  std::vector<Item> items;
  const bool fight = !punches.empty() && (kinds.empty() || rng.chance(0.3f));
  if (fight) items.insert(items.end(), rng.chance(0.65f) ? 1 : 2, Item::Opponent);
  if (!kinds.empty()) {
    const int others = fight ? rng.below(4) : 1 + rng.below(4);
    for (int k = 0; k < others; ++k) items.push_back(kinds[static_cast<size_t>(rng.below(static_cast<int>(kinds.size())))]);
  }

  // The user's start.
  float direction = rng.uniform(-kPi, kPi);  // of the route here
  const bool turned = rng.chance(0.35f);
  const float start_offset = turned ? rng.uniform(-kPi, kPi) : rng.uniform(-20.0f, 20.0f) * kDegrees;
  ScenarioCharacter user;
  user.position = {0.0f, 0.0f};
  user.heading = wrap_angle(direction + start_offset);
  user.control = Control::User;
  s.characters.assign(1, user);

  // The gaps of the route (before each item, and before the goal) and which of them hold a waypoint.
  const size_t gaps = items.size() + 1;
  std::vector<bool> waypoint_in(gaps, false);
  const float w = rng.uniform(0.0f, 1.0f);
  const int waypoints = std::min(static_cast<int>(gaps), w < 0.55f ? 0 : w < 0.85f ? 1 : 2);
  for (int k = 0; k < waypoints;) {
    const size_t g = static_cast<size_t>(rng.below(static_cast<int>(gaps)));
    if (!waypoint_in[g]) waypoint_in[g] = true, ++k;
  }

  glm::vec2 at = user.position;  // the route's point of the last item placed
  std::vector<Footprint> placed;
  // Along the route by a gap: `length`, or through a waypoint; `extra` first (room to turn at the start).
  auto walk_gap = [&](size_t gap, float length, float extra) {
    at += extra * forward_of(direction);
    if (waypoint_in[gap]) {
      at += rng.uniform(2.5f, 4.0f) * forward_of(direction);
      s.goal.push_back(at);
      // The turn's side is drawn before its size: the two operands of one product are unsequenced, and
      // compilers evaluate them in different orders (the same seed must give the same course everywhere).
      const float side = rng.sign();
      direction = wrap_angle(direction + side * rng.uniform(25.0f, 75.0f) * kDegrees);
      length = rng.uniform(3.0f, 5.0f);
    }
    at += length * forward_of(direction);
  };

  const ObstacleSizes& sizes = obstacle_sizes();
  for (size_t i = 0; i < items.size(); ++i) {
    const Item item = items[i];
    float gap;
    if (i == 0) {
      const TargetAction action = item == Item::Ball  ? TargetAction::Kick
                                  : item == Item::Bar ? TargetAction::Crawl
                                  : item == Item::Beam ? TargetAction::Duck
                                                       : TargetAction::Jump;
      const size_t a = static_cast<size_t>(action);
      const float reach = a < o.reach.size() ? std::max(0.0f, o.reach[a]) : 0.0f;
      gap = item == Item::Opponent ? rng.uniform(4.0f, 7.0f) : rng.uniform(3.0f, 6.0f) + reach;
    } else {
      const float r = rng.uniform(0.0f, 1.0f);
      gap = r < 0.35f ? rng.uniform(1.5f, 3.0f) : r < 0.75f ? rng.uniform(3.0f, 6.0f) : rng.uniform(6.0f, 10.0f);
    }
    walk_gap(i, gap, i == 0 && turned ? 2.0f : 0.0f);
    bool fits = false;
    ScenarioObject obj;
    for (int attempt = 0; attempt < kObjectTries && !fits; ++attempt) {
      if (attempt > 0) at += 0.25f * forward_of(direction);
      obj = ScenarioObject{};
      const glm::vec2 side = left_of(direction);
      switch (item) {
        case Item::Opponent:
          obj.type = ObjectType::Opponent;
          obj.action = punches[static_cast<size_t>(rng.below(static_cast<int>(punches.size())))];
          obj.heading = wrap_angle(direction + kPi);
          obj.position = at + rng.uniform(-1.0f, 1.0f) * side;
          break;
        case Item::Ball:
          obj.type = ObjectType::Ball;
          obj.action = TargetAction::Kick;
          obj.size = glm::vec3(kBallDiameter);
          obj.position = at + rng.uniform(-0.2f, 0.2f) * side;
          break;
        case Item::Bar:
        case Item::Beam:
        case Item::Hurdle: {
          obj.type = item == Item::Bar ? ObjectType::Bar : item == Item::Beam ? ObjectType::Beam : ObjectType::Hurdle;
          obj.action = default_action(obj.type);
          obj.size = item == Item::Bar ? sizes.bar : item == Item::Beam ? sizes.beam : sizes.hurdle;
          float max_offset = 0.8f;
          if (o.vary_sizes) {
            const size_t a = static_cast<size_t>(obj.action);
            const glm::vec2 range = a < o.heights.size() ? o.heights[a] : glm::vec2(obj.size.y);
            obj.size = {rng.uniform(2.0f, 6.0f), rng.uniform(range.x, range.y), rng.uniform(0.05f, 0.2f)};
            max_offset = std::clamp(0.5f * obj.size.x - 0.9f, 0.0f, 0.8f);
          } else {
            obj.size.x = rng.uniform(4.5f, 6.0f);
            // The shipped size, brought within what the set's clip can pass.
            const size_t a = static_cast<size_t>(obj.action);
            if (a < o.heights.size() && o.heights[a].x <= o.heights[a].y)
              obj.size.y = std::clamp(obj.size.y, o.heights[a].x, o.heights[a].y);
          }
          obj.heading = wrap_angle(direction + rng.uniform(-30.0f, 30.0f) * kDegrees);
          // The route crosses the obstacle's axis `offset` from its middle.
          obj.position = at + rng.uniform(-max_offset, max_offset) * left_of(obj.heading);
          break;
        }
      }
      const Footprint f = footprint_of(obj);
      fits = std::none_of(placed.begin(), placed.end(), [&](const Footprint& p) { return too_close(p, f, kObjectGap); });
    }
    if (!fits) return false;
    placed.push_back(footprint_of(obj));
    s.objects.push_back(obj);
  }
  walk_gap(items.size(), rng.uniform(2.5f, 5.0f), items.empty() && turned ? 2.0f : 0.0f);
  s.goal.push_back(at);
  return course_is_sound(s);
}

std::string describe(const Scenario& s, const CourseOptions& o, int index) {
  std::string what;
  for (const ScenarioObject& obj : s.objects) {
    what += what.empty() ? "" : ", ";
    what += obj.type == ObjectType::Opponent ? std::string("opponent (") + target_action_name(obj.action) + ")" : object_type_name(obj.type);
  }
  const int waypoints = static_cast<int>(s.goal.size()) - 1;
  return "random course " + std::to_string(index) + " of seed " + std::to_string(o.seed) + ": " + (what.empty() ? "no objects" : what) +
         "; " + std::to_string(waypoints) + (waypoints == 1 ? " waypoint" : " waypoints") + " before the goal";
}

}  // namespace

std::vector<float> reaches_of(const WorldAssets& assets) {
  std::vector<float> reach;
  for (const TargetMotion& t : assets.targets) reach.push_back(t.reach);
  return reach;
}

std::vector<glm::vec2> heights_of(const WorldAssets& assets) {
  std::vector<glm::vec2> out(kTargetActionCount, glm::vec2(0.0f));
  constexpr float kDeepest = 0.2f;
  const struct {
    TargetAction action;
    ObjectType type;
    float lo, hi;
  } kinds[] = {{TargetAction::Crawl, ObjectType::Bar, 0.55f, 0.9f},
               {TargetAction::Duck, ObjectType::Beam, 1.0f, 1.4f},
               {TargetAction::Jump, ObjectType::Hurdle, 0.3f, 0.55f}};
  for (const auto& k : kinds) {
    const TargetMotion& t = assets.target(k.action);
    if (t.clip < 0) continue;
    const ObstacleFit fit = fit_obstacle(assets.sweeps[static_cast<size_t>(k.action)], t, k.type, {1.0f, k.lo, kDeepest});
    if (fit.last < fit.first) continue;  // the clip never comes near its obstacle: nothing to go by
    // The limits the fit allows (obstacle_fit.h), 1 cm inside them.
    const float can = k.type == ObjectType::Hurdle ? fit.clip_height - kFitMargin + max_fit(k.action) - 0.01f
                                                   : fit.clip_height + kFitMargin - max_fit(k.action) + 0.01f;
    out[static_cast<size_t>(k.action)] = k.type == ObjectType::Hurdle ? glm::vec2(k.lo, std::min(k.hi, can))
                                                                      : glm::vec2(std::max(k.lo, can), k.hi);
  }
  return out;
}

std::vector<TargetAction> actions_of(const WorldAssets& assets) {
  std::vector<TargetAction> out;
  for (const TargetMotion& t : assets.targets)
    if (t.clip >= 0) out.push_back(t.action);
  return out;
}

Scenario make_course(const CourseOptions& options, int index) {
  if (index < 0) throw std::invalid_argument("course index must be >= 0");
  const bool any = has(options.actions, TargetAction::Kick) || has(options.actions, TargetAction::Crawl) ||
                   has(options.actions, TargetAction::Duck) || has(options.actions, TargetAction::Jump) ||
                   has(options.actions, TargetAction::PunchLeft) || has(options.actions, TargetAction::PunchRight);
  if (!any) throw std::invalid_argument("random courses: the motion set can act on no object (no target clip)");
  Random rng(options.seed, static_cast<std::uint64_t>(index));
  for (int attempt = 0; attempt < kCourseTries; ++attempt) {
    Scenario s;
    s.name = "random-" + std::to_string(options.seed) + "-" + std::to_string(index);
    s.auto_launch = true;
    s.motions = options.motions;
    s.params_file = options.params_file;
    if (!draw_course(options, rng, s)) continue;
    s.description = describe(s, options, index);
    return s;
  }
  // Each draw succeeds far more often than not; a hundred failures in a row would be a broken rule.
  throw std::logic_error("random courses: no sound course drawn for seed " + std::to_string(options.seed) + ", index " +
                         std::to_string(index));
}

std::vector<Scenario> make_courses(const CourseOptions& options, int count) {
  if (count <= 0) throw std::invalid_argument("the number of random courses must be positive (got " + std::to_string(count) + ")");
  std::vector<Scenario> out;
  out.reserve(static_cast<size_t>(count));
  for (int k = 0; k < count; ++k) out.push_back(make_course(options, k));
  return out;
}

std::vector<glm::vec2> course_route(const Scenario& scenario) {
  std::vector<glm::vec2> route;
  const int user = scenario.user();
  if (user >= 0) route.push_back(scenario.characters[static_cast<size_t>(user)].position);
  route.insert(route.end(), scenario.goal.begin(), scenario.goal.end());
  return route;
}

float polyline_length(const std::vector<glm::vec2>& points) {
  float length = 0.0f;
  for (size_t k = 1; k < points.size(); ++k) length += glm::length(points[k] - points[k - 1]);
  return length;
}

}  // namespace prep
