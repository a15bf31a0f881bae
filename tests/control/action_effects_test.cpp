#include <doctest/doctest.h>

#include <cmath>

#include "engine/util/error.h"
#include "hand_made.h"

using namespace prep;

namespace {
float eq1(float alpha, float C, float c) { return c * std::sqrt(1.0f - std::pow(1.0f - alpha, C)); }
}  // namespace

TEST_CASE("a footstep of a straight walk: half the cycle's travel, shortened by (1 - w_r) as alpha rises") {
  const Params params;
  const auto world = test::hand_made_world(params);
  const ActionTable& t = world.table;
  REQUIRE(t.motions == 4);
  REQUIRE(t.alpha_levels == 6);
  CHECK(t.motion_roles[0] == "walk");
  // 1.2 m/s over a 1 s loop: a footstep is 0.5 s and 0.6 m.
  const ActionEffect& still = t.at(0);
  CHECK(still.forward == doctest::Approx(0.6).epsilon(1e-4));
  CHECK(still.left == doctest::Approx(0.0).epsilon(1e-4));
  CHECK(still.turn == doctest::Approx(0.0));
  CHECK(still.duration == doctest::Approx(0.5));
  for (int l = 1; l < 6; ++l) {
    const float alpha = 0.2f * l;
    const float w_r = eq1(alpha, 0.5f, 1.0f);
    CHECK(t.at(l).forward == doctest::Approx(0.6f * (1.0f - w_r)).epsilon(1e-4));  // Eq. 3-4
    CHECK(t.at(l).forward < t.at(l - 1).forward);
  }
  CHECK(t.at(5).forward == doctest::Approx(0.0));  // fully prepared: w_r = 1, no travel
}

TEST_CASE("a turning motion keeps its turn when prepared and moves along its arc") {
  const Params params;
  const auto world = test::hand_made_world(params);
  const ActionTable& t = world.table;
  // turn_left: 0.3 m/s at 1 rad/s, radius 0.3 m; half a second turns 0.5 rad.
  const ActionEffect& e = t.at(1 * 6 + 0);
  CHECK(e.turn == doctest::Approx(0.5).epsilon(1e-4));
  CHECK(e.forward == doctest::Approx(0.3 * std::sin(0.5)).epsilon(1e-3));
  CHECK(e.left == doctest::Approx(0.3 * (1 - std::cos(0.5))).epsilon(1e-3));
  CHECK(e.cos_turn == doctest::Approx(std::cos(0.5)).epsilon(1e-4));
  const ActionEffect& right = t.at(2 * 6 + 0);
  CHECK(right.turn == doctest::Approx(-0.5).epsilon(1e-4));
  CHECK(right.left == doctest::Approx(-e.left).epsilon(1e-3));
  const ActionEffect& prepared = t.at(1 * 6 + 5);
  CHECK(prepared.turn == doctest::Approx(0.5).epsilon(1e-4));  // heading follows the locomotion
  CHECK(std::fabs(prepared.forward) < 1e-6f);
  CHECK(t.at(3 * 6 + 2).forward == doctest::Approx(0.0));  // idle
}

TEST_CASE("the linear blend scales the stride by 1 - alpha") {
  const Params params;
  const auto world = test::hand_made_world(params, RootCurve{1.0f, 1.0f, true});
  CHECK(world.table.at(2).forward == doctest::Approx(0.6 * 0.6).epsilon(1e-4));
}

TEST_CASE("a core motion without a loop range is refused, naming the source") {
  MotionClip clip = test::hand_made_clip("walk", Role::Walk, 1.0f, 0.0f);
  clip.cyclic = false;
  CHECK_THROWS_WITH_AS(footstep_effect(clip, 0.0f, "set.json"), doctest::Contains("set.json"), InputError);
  MotionClip short_loop = test::hand_made_clip("walk", Role::Walk, 1.0f, 0.0f);
  short_loop.loop_last = 1;
  CHECK_THROWS_AS(footstep_effect(short_loop, 0.0f, "set.json"), InputError);
}
