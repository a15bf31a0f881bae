// Kicked balls bounce off what they meet instead of passing through it (rolling_balls.cpp): an obstacle's
// posts, legs, feet and low board, and the bodies of characters other than the kicker.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "engine/motion/body_volumes.h"
#include "engine/motion/kinematics.h"
#include "engine/world/clearance.h"
#include "engine/world/object_solids.h"
#include "engine/world/world.h"
#include "tests/world/builtin_assets.h"

using namespace prep;

namespace {

constexpr float kBallDiameterOfTest = 0.22f;

// How deep a ball lies in an object's solids (0: clear of them).
float ball_depth_in_object(const WorldObject& ball, const WorldObject& other) {
  const float r = 0.5f * kBallDiameterOfTest;
  const glm::vec3 local = to_object_frame(glm::vec3(ball.position.x, r, ball.position.z), {other.position.x, other.position.z},
                                          other.spec.heading);
  float depth = 0.0f;
  for (const ObjectSolid& s : object_solids(other.spec.type, other.spec.size)) {
    const glm::vec3 half = s.sphere ? glm::vec3(0.5f * s.extents.x) : 0.5f * s.extents;
    const glm::vec3 p = local - s.centre;
    const float distance = s.sphere ? glm::length(p) - 0.5f * s.extents.x
                                    : glm::length(glm::max(glm::abs(p) - half, glm::vec3(0.0f))) +
                                          std::min(0.0f, std::max({std::abs(p.x) - half.x, std::abs(p.y) - half.y, std::abs(p.z) - half.z}));
    depth = std::max(depth, r - distance);
  }
  return depth;
}

std::string ball_course_text(float ball_z, const std::string& obstacle, glm::vec2 goal) {
  char buffer[1024];
  std::snprintf(buffer, sizeof buffer,
                "{\"auto\": true, \"characters\": [{\"position\": [0, 0], \"control\": \"user\"}], \"objects\": ["
                "{\"type\": \"ball\", \"position\": [0, %.3f], \"size\": [%.2f, %.2f, %.2f]}%s], \"goal\": [%.3f, %.3f]}",
                ball_z, kBallDiameterOfTest, kBallDiameterOfTest, kBallDiameterOfTest, obstacle.c_str(), goal.x, goal.y);
  return buffer;
}

// The ball's velocity on the tick it is struck (zero if it never is within 20 s).
glm::vec2 kick_velocity(World& world) {
  for (int tick = 0; tick < 60 * 20; ++tick) {
    world.step();
    if (glm::length(world.objects()[0].velocity) > 0.0f) return world.objects()[0].velocity;
  }
  return glm::vec2(0.0f);
}

// A course of one ball 2-3 m ahead of the user and one obstacle turned up to 35 degrees, with the part the
// ball is to roll into placed on the ball's way 1.5-3.5 m beyond it: a bar's or beam's post, a hurdle's leg
// and foot (a hurdle the ball rolls under), or a hurdle's board lower than the ball's top. The way is the
// one the same course without the obstacle kicks the ball along (the obstacle lies beyond the ball, so the
// approach and the kick are the same); the goal lies beyond.
struct KickCourse {
  std::string text;
  std::string kind;
  bool board_blocks = false;  // a hurdle whose board's underside is lower than the ball's top
};
KickCourse kick_course(std::mt19937& rng, int k) {
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  const char* kinds[] = {"bar", "beam", "hurdle", "hurdle"};
  KickCourse c;
  c.kind = kinds[k % 4];
  const float ball_z = 2.0f + u(rng), beyond = 1.5f + 2.0f * u(rng);
  const float width = 0.9f + 0.8f * u(rng);
  const float heading_deg = (u(rng) - 0.5f) * 70.0f;
  const float side = u(rng) < 0.5f ? -1.0f : 1.0f;
  const glm::vec2 goal(side * 1.0f, ball_z + beyond + 4.0f);
  World probe(parse_scenario(ball_course_text(ball_z, "", goal), "kick-line"), test::builtin_assets());
  const glm::vec2 kick = kick_velocity(probe);
  const glm::vec2 way = glm::length(kick) > 0.0f ? glm::normalize(kick) : glm::vec2(0.0f, 1.0f);
  const glm::vec2 met = glm::vec2(0.0f, ball_z) + beyond * way;  // where the part is to stand
  float height = 0.0f, along = 0.0f;  // the part's offset along the obstacle's width from its middle
  if (c.kind == "bar") {
    height = 0.6f + 0.2f * u(rng);
    along = side * 0.5f * (width + kPostWidth);
  } else if (c.kind == "beam") {
    height = 1.15f + 0.2f * u(rng);
    along = side * 0.5f * (width + kPostWidth);
  } else if (k % 8 == 2) {
    height = 0.5f + 0.1f * u(rng);  // the ball rolls under the board: its leg and foot in the way
    along = side * 0.5f * width;
  } else {
    height = 0.26f + 0.06f * u(rng);  // the board lower than the ball's top, in its way
    along = (u(rng) - 0.5f) * 0.4f * width;
    c.board_blocks = true;
  }
  const float h = heading_deg * 3.14159265f / 180.0f;
  const glm::vec2 at = met - along * glm::vec2(std::cos(h), -std::sin(h));  // the object's X axis on the floor
  char obstacle[512];
  std::snprintf(obstacle, sizeof obstacle, ", {\"type\": \"%s\", \"position\": [%.3f, %.3f], \"heading\": %.2f, \"size\": [%.3f, %.3f, %.3f]}",
                c.kind.c_str(), at.x, at.y, heading_deg, width, height, c.kind == "hurdle" ? 0.03f : 0.08f);
  c.text = ball_course_text(ball_z, obstacle, goal);
  return c;
}

}  // namespace

TEST_CASE("a kicked ball bounces off an obstacle's post, leg, foot or low board instead of rolling through it") {
  std::mt19937 rng(2026);
  int kicked = 0, bounced = 0, deep = 0, through = 0;
  float deepest = 0.0f;
  for (int k = 0; k < 8; ++k) {
    const KickCourse course = kick_course(rng, k);
    CAPTURE(course.text);
    World world(parse_scenario(course.text, "kick-course"), test::builtin_assets());
    const WorldObject& ball = world.objects()[0];
    const WorldObject& obstacle = world.objects()[1];
    const glm::vec2 at(obstacle.position.x, obstacle.position.z);
    const auto local_of_ball = [&] {
      return to_object_frame(glm::vec3(ball.position.x, 0.0f, ball.position.z), at, obstacle.spec.heading);
    };
    const float start_side = local_of_ball().z;
    bool was_kicked = false, turned = false;
    glm::vec2 kicked_velocity(0.0f);
    for (int tick = 0; tick < 60 * 20; ++tick) {
      world.step();
      if (!was_kicked && glm::length(ball.velocity) > 0.0f) {
        was_kicked = true;
        kicked_velocity = ball.velocity;
      }
      if (!was_kicked) continue;
      const float depth = ball_depth_in_object(ball, obstacle);
      deepest = std::max(deepest, depth);
      if (depth > 0.002f) ++deep;
      const glm::vec3 local = local_of_ball();
      // Through the board: on the far side of its plane, between its legs.
      if (course.board_blocks && std::abs(local.x) < 0.5f * obstacle.spec.size.x - 0.1f && local.z * start_side < 0.0f) ++through;
      // Turned by more than 45 degrees from its kick: it met something.
      if (glm::dot(ball.velocity, kicked_velocity) < 0.7071f * glm::length(ball.velocity) * glm::length(kicked_velocity)) turned = true;
    }
    kicked += was_kicked;
    bounced += turned;
  }
  MESSAGE("kicked " << kicked << " of 8, turned aside or back " << bounced << ", ticks deeper than 2 mm " << deep
                    << ", deepest " << deepest * 100.0f << " cm, ticks through a board " << through);
  CHECK(kicked == 8);
  CHECK(bounced == 8);
  CHECK(deep == 0);
  CHECK(through == 0);
}

TEST_CASE("a ball kicked at a character standing in its way bounces off its legs instead of rolling through them") {
  // The user punches an opponent that comes at it past a ball, then kicks the ball: the punched opponent
  // has stepped aside next to it, into the ball's way.
  const std::string text =
      "{\"auto\": true, \"characters\": [{\"position\": [-0.729, 0], \"heading\": 19.67, \"control\": \"user\"}], "
      "\"objects\": [{\"type\": \"ball\", \"position\": [-0.167, 5.447], \"size\": [0.22, 0.22, 0.22]}, "
      "{\"type\": \"opponent\", \"action\": \"punch_left\", \"position\": [-2.654, 8.654], \"heading\": 142.2}], "
      "\"goal\": [0.705, 13.506]}";
  World world(parse_scenario(text, "ball-past-opponent"), test::builtin_assets());
  ClearanceLog log(world);
  const WorldObject& ball = world.objects()[0];
  glm::vec2 kicked(0.0f);
  bool turned = false;
  world.run_until_done(40.0f, 1.0f, [&](const World& w) {
    log.observe(w);
    if (kicked == glm::vec2(0.0f)) kicked = ball.velocity;
    if (glm::dot(ball.velocity, kicked) < 0.7071f * glm::length(ball.velocity) * glm::length(kicked)) turned = true;
  });
  const int opponent = 1;
  CAPTURE(log.summary.min_object_what);
  REQUIRE(world.characters()[static_cast<size_t>(opponent)].defeated);
  CHECK(glm::length(kicked) > 0.0f);
  CHECK(turned);
  CHECK(log.summary.object_frames == 0);
  CHECK(log.summary.min_object > -clearance_metric::kObjectTolerance);
}

TEST_CASE("a ball kicked into another lying in its way comes back off it and off its kicker, through neither") {
  // The second ball 1-2 m beyond the first along the way the first is kicked (found without it): the kicked
  // ball comes back off it, at the kicker still in its kick.
  std::mt19937 rng(149);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  int came_back = 0;
  for (int k = 0; k < 4; ++k) {
    const float ball_z = 2.0f + u(rng), beyond = 1.0f + u(rng);
    const glm::vec2 goal((u(rng) - 0.5f) * 2.0f, ball_z + beyond + 4.0f);
    World probe(parse_scenario(ball_course_text(ball_z, "", goal), "kick-line"), test::builtin_assets());
    const glm::vec2 kick = kick_velocity(probe);
    REQUIRE(glm::length(kick) > 0.0f);
    const glm::vec2 second = glm::vec2(0.0f, ball_z) + beyond * glm::normalize(kick);
    char other[256];
    std::snprintf(other, sizeof other, ", {\"type\": \"ball\", \"position\": [%.3f, %.3f], \"size\": [0.22, 0.22, 0.22]}", second.x,
                  second.y);
    const std::string text = ball_course_text(ball_z, other, goal);
    CAPTURE(text);
    World world(parse_scenario(text, "two-balls"), test::builtin_assets());
    ClearanceLog log(world);
    const WorldObject& first = world.objects()[0];
    const WorldObject& lying = world.objects()[1];
    bool back = false, lying_moved_unkicked = false;
    for (int tick = 0; tick < 60 * 6; ++tick) {
      world.step();
      log.observe(world);
      if (glm::dot(first.velocity, kick) < 0.0f) back = true;
      if (!lying.used && glm::length(lying.velocity) > 0.0f) lying_moved_unkicked = true;
    }
    came_back += back;
    CHECK_FALSE(lying_moved_unkicked);  // a ball not yet kicked is held where it was set
    INFO(log.summary.min_object_what);
    CHECK(log.summary.object_frames == 0);
  }
  CHECK(came_back == 4);
}
