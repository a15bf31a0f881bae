#include "engine/world/set_course.h"

#include <algorithm>
#include <cstdio>

#include <glm/geometric.hpp>

#include "engine/world/courses.h"
#include "engine/world/floor.h"
#include "engine/world/obstacle_fit.h"

namespace prep {
namespace {

constexpr float kBallBeyondGoal = 2.5f;  // m from the old goal on to the new one, past the ball
constexpr float kBallSize = 0.22f;

std::string where(const ScenarioObject& o) {
  char text[96];
  std::snprintf(text, sizeof text, "the %s at (%.1f, %.1f)", object_type_name(o.type), o.position.x, o.position.y);
  return text;
}

bool passes(const WorldAssets& assets, const ScenarioObject& o) {
  const TargetMotion& t = assets.target(o.action);
  return fit_obstacle(assets.sweeps[static_cast<size_t>(o.action)], t, o.type, o.size).possible;
}

}  // namespace

SetCourse course_for_set(const Scenario& course, const WorldAssets& assets, const std::string& motions) {
  SetCourse out;
  out.scenario = course;
  out.scenario.motions = motions;
  out.scenario.objects.clear();
  const std::vector<glm::vec2> heights = heights_of(assets);
  bool has_ball = false;
  for (const ScenarioObject& o : course.objects) {
    if (assets.target(o.action).clip < 0) {
      out.changes.push_back("left out " + where(o) + ": this set has no " + target_action_name(o.action));
      continue;
    }
    ScenarioObject kept = o;
    if (floor_plane::is_across(o.type) && !passes(assets, o)) {
      const glm::vec2 range = heights[static_cast<size_t>(o.action)];
      if (range.x > range.y) {
        out.changes.push_back("left out " + where(o) + ": the set's " + target_action_name(o.action) + " passes none of its heights");
        continue;
      }
      kept.size.y = std::clamp(o.size.y, range.x, range.y);
      if (!passes(assets, kept)) {
        out.changes.push_back("left out " + where(o) + ": the set's " + target_action_name(o.action) + " cannot pass it");
        continue;
      }
      char text[160];
      std::snprintf(text, sizeof text, ": %s from %.2f m to %.2f m, what the set's %s passes", kept.size.y < o.size.y ? "lowered" : "raised",
                    o.size.y, kept.size.y, target_action_name(o.action));
      out.changes.push_back(where(o) + text);
    }
    has_ball = has_ball || o.type == ObjectType::Ball;
    out.scenario.objects.push_back(kept);
  }

  // A set that kicks gets a ball where the course ended, and the goal a little further on.
  if (!has_ball && assets.target(TargetAction::Kick).clip >= 0 && !out.scenario.goal.empty()) {
    glm::vec2& goal = out.scenario.goal.back();
    glm::vec2 from = out.scenario.characters.empty() ? glm::vec2(0.0f) : out.scenario.characters.front().position;
    if (!out.scenario.objects.empty()) from = out.scenario.objects.back().position;
    const glm::vec2 along = glm::length(goal - from) > 1e-3f ? glm::normalize(goal - from) : glm::vec2(0.0f, 1.0f);
    ScenarioObject ball;
    ball.type = ObjectType::Ball;
    ball.action = TargetAction::Kick;
    ball.position = goal;
    ball.size = glm::vec3(kBallSize);
    out.scenario.objects.push_back(ball);
    goal += along * kBallBeyondGoal;
    out.changes.push_back("added " + where(ball) + ": the set kicks");
  }
  if (out.scenario.objects.empty()) out.changes.push_back("nothing on this course suits this set: the character walks to the goal");
  return out;
}

}  // namespace prep
