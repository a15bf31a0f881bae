// A ball on the user's way to an opponent that comes at it: the ball is kicked first, the opponent waits
// for the kick, then the two meet (World::ball_before_opponent, World::waiting_for_kick); with an obstacle
// between them too, a ball before the obstacle is kicked before it is crossed.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <string>

#include "engine/world/clearance.h"
#include "engine/world/world.h"
#include "tests/world/builtin_assets.h"

using namespace prep;

namespace {

// The user at the origin, turned up to 20 degrees; a ball 1.5-3.5 m ahead, up to 0.8 m aside; an opponent
// 2.2-4 times as far, up to 30 degrees aside, facing the user; the goal 2-5 m beyond the opponent.
std::string ball_then_opponent_course(std::mt19937& rng) {
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  const float ball_z = 1.5f + 2.0f * u(rng), ball_x = (u(rng) - 0.5f) * 1.6f;
  const float opponent_distance = (2.2f + 1.8f * u(rng)) * ball_z;
  const float bearing_deg = (u(rng) - 0.5f) * 60.0f, bearing = bearing_deg * 3.14159265f / 180.0f;
  const char* punch = u(rng) < 0.5f ? "punch_left" : "punch_right";
  const float goal_x = (u(rng) - 0.5f) * 6.0f, goal_z = opponent_distance + 2.0f + 3.0f * u(rng);
  const float heading = (u(rng) - 0.5f) * 40.0f;
  char text[1024];
  std::snprintf(text, sizeof text,
                "{\"auto\": true, \"characters\": [{\"position\": [0, 0], \"heading\": %.2f, \"control\": \"user\"}], "
                "\"objects\": [{\"type\": \"ball\", \"position\": [%.3f, %.3f], \"size\": [0.22, 0.22, 0.22]}, "
                "{\"type\": \"opponent\", \"action\": \"%s\", \"position\": [%.3f, %.3f], \"heading\": %.2f}], "
                "\"goal\": [%.3f, %.3f]}",
                heading, ball_x, ball_z, punch, opponent_distance * std::sin(bearing), opponent_distance * std::cos(bearing),
                180.0f + bearing_deg, goal_x, goal_z);
  return text;
}

// The user at the origin; a ball 2-3.5 m ahead, 0.6-1.6 m to one side; an obstacle 5-6.5 m ahead turned up
// to 10 degrees either way; an opponent 3-4.5 m beyond it, facing the user; the goal 2-4 m past the opponent.
std::string ball_obstacle_then_opponent(std::mt19937& rng) {
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  const char* types[] = {"beam", "bar", "hurdle"};
  const int type = static_cast<int>(u(rng) * 2.999f);
  const float height = type == 0 ? 1.3f : type == 1 ? 0.72f : 0.48f;
  const float side = u(rng) < 0.5f ? -1.0f : 1.0f;
  const float ball_z = 2.0f + 1.5f * u(rng), ball_x = side * (0.6f + u(rng));
  const float obstacle_z = 5.0f + 1.5f * u(rng), obstacle_heading = (u(rng) - 0.5f) * 20.0f;
  const float opponent_z = obstacle_z + 3.0f + 1.5f * u(rng);
  const char* punch = u(rng) < 0.5f ? "punch_left" : "punch_right";
  char text[1400];
  std::snprintf(text, sizeof text,
                "{\"auto\": true, \"characters\": [{\"position\": [0, 0], \"heading\": 0, \"control\": \"user\"}], "
                "\"objects\": [{\"type\": \"ball\", \"position\": [%.3f, %.3f], \"size\": [0.22, 0.22, 0.22]}, "
                "{\"type\": \"%s\", \"position\": [0.0, %.3f], \"heading\": %.2f, \"size\": [2.0, %.2f, 0.06]}, "
                "{\"type\": \"opponent\", \"action\": \"%s\", \"position\": [0.2, %.3f], \"heading\": 180}], "
                "\"goal\": [0.5, %.3f]}",
                ball_x, ball_z, types[type], obstacle_z, obstacle_heading, height, punch, opponent_z,
                opponent_z + 2.0f + 2.0f * u(rng));
  return text;
}

// The user at the origin; an opponent 4-5 m to one side and 8-9 m ahead, coming at it; a ball 4.8-5.6 m
// ahead, 0.2-1 m to the other side (farther than halfway to the opponent: the fight comes first); the goal
// 11-12 m ahead.
std::string opponent_aside_then_ball(std::mt19937& rng) {
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  const float side = u(rng) < 0.5f ? -1.0f : 1.0f;
  const float opponent_x = side * (4.0f + u(rng)), opponent_z = 8.0f + u(rng);
  const float facing_user = std::atan2(-opponent_x, -opponent_z) * 180.0f / 3.14159265f;
  const float ball_x = -side * (0.2f + 0.8f * u(rng)), ball_z = 4.8f + 0.8f * u(rng);
  const char* punch = u(rng) < 0.5f ? "punch_left" : "punch_right";
  char text[1024];
  std::snprintf(text, sizeof text,
                "{\"auto\": true, \"characters\": [{\"position\": [0, 0], \"heading\": 0, \"control\": \"user\"}], "
                "\"objects\": [{\"type\": \"ball\", \"position\": [%.3f, %.3f], \"size\": [0.22, 0.22, 0.22]}, "
                "{\"type\": \"opponent\", \"action\": \"%s\", \"position\": [%.3f, %.3f], \"heading\": %.2f}], "
                "\"goal\": [0.0, %.3f]}",
                ball_x, ball_z, punch, opponent_x, opponent_z, facing_user, 11.0f + u(rng));
  return text;
}

}  // namespace

TEST_CASE("a ball on the way to an opponent is kicked first, the opponent waiting for the kick, then the two meet") {
  std::mt19937 rng(11);
  int kicked_first = 0, waited = 0;
  for (int k = 0; k < 8; ++k) {
    const std::string text = ball_then_opponent_course(rng);
    CAPTURE(text);
    World world(parse_scenario(text, "ball-then-opponent"), test::builtin_assets());
    ClearanceLog log(world);
    const int user = world.user(), opponent = user == 0 ? 1 : 0;
    float struck = -1.0f;  // when the ball left the foot
    bool opponent_stood = false;
    float opponent_from_ball = 0.0f;  // at the strike
    world.run_until_done(40.0f, 1.0f, [&](const World& w) {
      log.observe(w);
      if (struck < 0.0f && glm::length(w.objects()[0].velocity) > 0.0f) {
        struck = w.time();
        const WorldObject& ball = w.objects()[0];
        opponent_from_ball = glm::length(w.characters()[static_cast<size_t>(opponent)].position - glm::vec2(ball.position.x, ball.position.z));
      }
      if (struck < 0.0f && w.characters()[static_cast<size_t>(opponent)].clip == w.assets().idle_node) opponent_stood = true;
    });
    const WorldCharacter& them = world.characters()[static_cast<size_t>(opponent)];
    CHECK(world.goal_reached());
    CHECK(world.objects()[0].used);
    CHECK(them.defeated);
    CHECK(log.summary.object_frames == 0);
    // The user's kick, then its punch; the opponent strikes at nothing before the ball has left the foot.
    float kick = -1.0f, punch = -1.0f, opponent_punch = 1e9f;
    for (const LaunchRecord& r : world.launches()) {
      if (r.character == user && r.action == TargetAction::Kick && kick < 0.0f) kick = r.time;
      if (r.character == user && r.action != TargetAction::Kick && punch < 0.0f) punch = r.time;
      if (r.character == opponent) opponent_punch = std::min(opponent_punch, r.time);
    }
    CHECK(kick >= 0.0f);
    CHECK(punch > kick);
    CHECK(struck > 0.0f);
    CHECK(opponent_punch > struck);
    // It waited out of the kick's way: at least two persons' space from the ball.
    CHECK(opponent_from_ball >= 2.0f * kPersonalSpace);
    kicked_first += kick >= 0.0f && punch > kick;
    waited += opponent_stood;
  }
  MESSAGE(kicked_first << " of 8 balls kicked before the punch; " << waited << " opponents stood waiting for the kick");
  CHECK(waited >= 1);  // the courses include opponents near enough to have to wait (the check above bites)
}

TEST_CASE("a ball before an obstacle between the user and an opponent is kicked before the obstacle is crossed") {
  std::mt19937 rng(3);
  for (int k = 0; k < 6; ++k) {
    const std::string text = ball_obstacle_then_opponent(rng);
    CAPTURE(text);
    World world(parse_scenario(text, "ball-obstacle-then-opponent"), test::builtin_assets());
    ClearanceLog log(world);
    const int user = world.user(), opponent = user == 0 ? 1 : 0;
    world.run_until_done(45.0f, 1.0f, [&](const World& w) { log.observe(w); });
    CHECK(world.goal_reached());
    CHECK(world.characters()[static_cast<size_t>(opponent)].defeated);
    // Kicked, and first: the crossing and the punch come after it.
    CHECK(world.objects()[0].used);
    float kick = -1.0f, crossing = -1.0f;
    for (const LaunchRecord& r : world.launches()) {
      if (r.character != user) continue;
      if (r.action == TargetAction::Kick && kick < 0.0f) kick = r.time;
      if (r.action != TargetAction::Kick && r.action != TargetAction::PunchLeft && r.action != TargetAction::PunchRight &&
          crossing < 0.0f)
        crossing = r.time;
    }
    CHECK(kick >= 0.0f);
    CHECK(crossing > kick);
    CHECK(log.summary.object_frames == 0);
  }
}

TEST_CASE("a ball beside the user after a fight, on its way to the goal, is still kicked") {
  // The fight leaves the user facing where the opponent stood, the ball to its side or behind its facing,
  // though still on its way to the goal.
  std::mt19937 rng(23);
  for (int k = 0; k < 10; ++k) {
    const std::string text = opponent_aside_then_ball(rng);
    CAPTURE(text);
    World world(parse_scenario(text, "opponent-aside-then-ball"), test::builtin_assets());
    ClearanceLog log(world);
    const int opponent = world.user() == 0 ? 1 : 0;
    world.run_until_done(45.0f, 1.0f, [&](const World& w) { log.observe(w); });
    CHECK(world.goal_reached());
    CHECK(world.characters()[static_cast<size_t>(opponent)].defeated);
    CHECK(world.objects()[0].used);
    CHECK(log.summary.object_frames == 0);
  }
}
