#include <doctest/doctest.h>

#include <cmath>

#include "engine/util/error.h"
#include "hand_made.h"
#include "tests/support/angles.h"

using namespace prep;

namespace {
float eq1(float alpha, float C, float c) { return c * std::sqrt(1.0f - std::pow(1.0f - alpha, C)); }
using test::kPi;
}  // namespace

TEST_CASE("an action of a straight walk: one gait cycle, shortened by (1 - w_r) as alpha rises") {
  const Params params;
  REQUIRE(params.quantization.footsteps_per_action == 2);
  const auto world = test::hand_made_world(params);
  const ActionTable& t = world.table;
  REQUIRE(t.motions == 4);
  REQUIRE(t.alpha_levels == 6);
  CHECK(t.motion_roles[0] == "walk");
  // 1.5 m/s over a 1 s loop without contacts: one gait cycle, so one action is the whole loop.
  const ActionEffect& still = t.at(0);
  CHECK(still.forward == doctest::Approx(1.5).epsilon(1e-4));
  CHECK(still.left == doctest::Approx(0.0).epsilon(1e-4));
  CHECK(still.turn == doctest::Approx(0.0));
  CHECK(still.duration == doctest::Approx(1.0));
  CHECK(still.inv_chord2 == doctest::Approx(1.0 / (1.5 * 1.5)).epsilon(1e-4));
  for (int l = 1; l < 6; ++l) {
    const float alpha = 0.2f * l;
    const float w_r = eq1(alpha, 0.5f, 1.0f);
    CHECK(t.at(l).forward == doctest::Approx(1.5f * (1.0f - w_r)).epsilon(1e-4));  // Eq. 3-4
    CHECK(t.at(l).forward < t.at(l - 1).forward);
  }
  CHECK(t.at(5).forward == doctest::Approx(0.0));  // fully prepared: w_r = 1, no travel
  CHECK(t.at(5).inv_chord2 == 0.0f);
  CHECK(t.at(3 * 6 + 0).forward == doctest::Approx(0.6).epsilon(1e-4));  // walk_slow
  // One footstep per action: half the loop.
  const ActionEffect step = action_effect(world.clips[0], 0.0f, 1, "hand-made");
  CHECK(step.forward == doctest::Approx(0.75).epsilon(1e-4));
  CHECK(step.duration == doctest::Approx(0.5));
  // More footsteps than the loop holds: the whole loop.
  CHECK(action_effect(world.clips[0], 0.0f, 8, "hand-made").duration == doctest::Approx(1.0));
}

TEST_CASE("a turning motion keeps its turn when prepared and moves along its arc") {
  const Params params;
  const auto world = test::hand_made_world(params);
  const ActionTable& t = world.table;
  // turn_left: 1.2 m/s at 1 rad/s, radius 1.2 m; the 1 s action turns 1 rad.
  const ActionEffect& e = t.at(1 * 6 + 0);
  CHECK(e.turn == doctest::Approx(1.0).epsilon(1e-4));
  CHECK(e.forward == doctest::Approx(1.2 * std::sin(1.0)).epsilon(1e-3));
  CHECK(e.left == doctest::Approx(1.2 * (1 - std::cos(1.0))).epsilon(1e-3));
  CHECK(e.cos_turn == doctest::Approx(std::cos(1.0)).epsilon(1e-4));
  const ActionEffect& right = t.at(2 * 6 + 0);
  CHECK(right.turn == doctest::Approx(-1.0).epsilon(1e-4));
  CHECK(right.left == doctest::Approx(-e.left).epsilon(1e-3));
  const ActionEffect& prepared = t.at(1 * 6 + 5);
  CHECK(prepared.turn == doctest::Approx(1.0).epsilon(1e-4));  // heading follows the locomotion
  CHECK(std::fabs(prepared.forward) < 1e-6f);
}

TEST_CASE("an action is measured along the travel, not along the swaying pelvis") {
  // Straight ahead along heading 0.3 at 1.2 m/s while the pelvis yaws 0.07 rad either way once per loop,
  // at its extreme when the loop starts: a frame taken from the first frame's yaw would see a drift of
  // 1.2 sin(0.07) = 0.084 m to the side.
  MotionClip clip = test::hand_made_clip("walk", Role::Walk, 1.2f, 0.0f);
  for (size_t k = 0; k < clip.clip.frames.size(); ++k) {
    const float yaw = 0.3f + 0.07f * std::cos(2.0f * kPi * static_cast<float>(k) / 30.0f);
    clip.clip.frames[k].rotations[0] = glm::angleAxis(yaw, glm::vec3(0.0f, 1.0f, 0.0f));
  }
  const ActionEffect e = action_effect(clip, 0.0f, 2, "sway");
  CHECK(std::fabs(e.left) < 0.01f);
  CHECK(e.forward == doctest::Approx(1.2).epsilon(0.01));
  CHECK(std::fabs(e.turn) < 1e-4f);  // the loop ends at the phase it began
}

TEST_CASE("the linear blend scales the stride by 1 - alpha") {
  const Params params;
  const auto world = test::hand_made_world(params, RootCurve{1.0f, 1.0f, true});
  CHECK(world.table.at(2).forward == doctest::Approx(1.5 * 0.6).epsilon(1e-4));
}

TEST_CASE("a core motion without a loop range is refused, naming the source") {
  MotionClip clip = test::hand_made_clip("walk", Role::Walk, 1.0f, 0.0f);
  clip.cyclic = false;
  CHECK_THROWS_WITH_AS(action_effect(clip, 0.0f, 2, "set.json"), doctest::Contains("set.json"), InputError);
  MotionClip short_loop = test::hand_made_clip("walk", Role::Walk, 1.0f, 0.0f);
  short_loop.loop_last = 1;
  CHECK_THROWS_AS(action_effect(short_loop, 0.0f, 2, "set.json"), InputError);
}

TEST_CASE("core motions are named by role (the first cyclic clip of it) or by clip name") {
  MotionSet set;
  set.name = "hand-made";
  set.clips.push_back(test::hand_made_clip("walk", Role::Walk, 1.2f, 0.0f));
  set.clips.push_back(test::hand_made_clip("walk_slow", Role::Walk, 0.6f, 0.0f));
  set.clips.push_back(test::hand_made_clip("turn_left", Role::TurnLeft, 0.3f, 1.0f));
  set.clips.push_back(test::hand_made_clip("kick", Role::Kick, 0.0f, 0.0f));
  set.clips.back().cyclic = false;
  QuantizationParams q;
  q.core_roles = {"walk", "walk_slow", "turn_left"};
  const auto core = core_clips(set, q);
  REQUIRE(core.size() == 3);
  CHECK(core[0] == &set.clips[0]);
  CHECK(core[1] == &set.clips[1]);
  CHECK(core[2] == &set.clips[2]);
  q.core_roles = {"walk", "turn_right"};  // a role the set has no clip of
  CHECK_THROWS_WITH_AS(core_clips(set, q), doctest::Contains("turn_right"), InputError);
  q.core_roles = {"walk", "jog"};  // neither a role nor a clip
  CHECK_THROWS_WITH_AS(core_clips(set, q), doctest::Contains("neither a role nor a clip"), InputError);
  q.core_roles = {"walk", "kick"};  // a target role
  CHECK_THROWS_WITH_AS(core_clips(set, q), doctest::Contains("not a locomotion"), InputError);
  q.core_roles = {"walk", "walk"};  // the same clip twice
  CHECK_THROWS_WITH_AS(core_clips(set, q), doctest::Contains("named twice"), InputError);
}
