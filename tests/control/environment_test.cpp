#include <doctest/doctest.h>

#include <cmath>
#include <stdexcept>

#include "engine/control/actions.h"
#include "hand_made.h"
#include "tests/support/angles.h"

using namespace prep;

namespace {
using test::kPi;
}

TEST_CASE("fast_atan2 matches atan2 everywhere") {
  for (int i = 0; i < 3600; ++i) {
    const float a = -kPi + (2 * kPi) * (i + 0.5f) / 3600;
    for (float r : {0.01f, 1.0f, 50.0f}) {
      const float y = r * std::sin(a), x = r * std::cos(a);
      CHECK(std::fabs(fast_atan2(y, x) - std::atan2(y, x)) < 2e-5f);
    }
  }
  CHECK(fast_atan2(0.0f, 0.0f) == 0.0f);
}

TEST_CASE("situations from world positions: bearings positive to the left") {
  // Facing +X (heading pi/2): a goal 2 m along +X is ahead; +Z is to the right.
  const Situation s = make_situation({1, 1}, kPi / 2, {3, 1}, {1, 3}, 0, 0);
  CHECK(s.d_g == doctest::Approx(2.0));
  CHECK(s.theta_g == doctest::Approx(0.0).epsilon(1e-4));
  CHECK(s.d_i == doctest::Approx(2.0));
  CHECK(s.theta_i == doctest::Approx(-kPi / 2).epsilon(1e-4));
}

TEST_CASE("a step moves the character by the action's effect and pays Eq. 17") {
  const Params params;
  const auto world = test::hand_made_world(params);
  const Environment env = test::make_environment(params, world.table);
  Situation s = make_situation({0, 0}, 0.0f, {0, 3}, {3, 0}, 1, 3);
  const float d_before = s.d_g;
  const int walk_alpha_02 = env.actions().index({0, 1});
  const StepOutcome out = env.step(s, walk_alpha_02);
  const float stride = world.table.at(walk_alpha_02).forward;
  CHECK(s.d_g == doctest::Approx(3.0f - stride).epsilon(1e-4));
  CHECK(s.theta_g == doctest::Approx(0.0).epsilon(1e-4));
  CHECK_FALSE(out.at_goal);
  CHECK_FALSE(out.at_source);
  CHECK(s.alpha_level == 1);  // Eq. 13
  CHECK(s.motion == 0);
  const RewardTerms t = reward_terms(0.0f, d_before, s.d_g, 0.2f, 0.2f, false, params.reward);
  CHECK(out.reward == doctest::Approx(t.total).epsilon(1e-5));

  // Turning left brings a goal on the left toward straight ahead.
  Situation left = make_situation({0, 0}, 0.0f, {2, 0}, {2, 0}, 0, 3);
  CHECK(left.theta_g == doctest::Approx(kPi / 2).epsilon(1e-4));
  env.step(left, env.actions().index({1, 0}));
  CHECK(left.theta_g < kPi / 2 - 0.3f);
}

TEST_CASE("reaching the source forces alpha to 1 and reaching the goal ends the episode") {
  const Params params;
  const auto world = test::hand_made_world(params);
  const Environment env = test::make_environment(params, world.table);
  REQUIRE(params.reward.source_radius == doctest::Approx(1.0));
  // Source 2 m ahead, goal 4 m ahead: a walk action at alpha 0 (1.5 m) ends 0.5 m from the source.
  Situation s = make_situation({0, 0}, 0.0f, {0, 4}, {0, 2.0f}, 2, 0);
  const StepOutcome out = env.step(s, env.actions().index({0, 0}));
  CHECK(out.at_source);
  CHECK_FALSE(out.at_goal);
  CHECK(s.alpha_level == env.states().top_alpha_level());
  CHECK(out.reward == doctest::Approx(reward_terms(0.0f, 4.0f, 2.5f, 0.4f, 0.0f, true, params.reward).total).epsilon(1e-5));
  // Still within the radius after a short action at 0.8: forced again, both changes of alpha penalised.
  const StepOutcome inside = env.step(s, env.actions().index({0, 4}));
  CHECK(inside.at_source);
  CHECK(s.alpha_level == env.states().top_alpha_level());
  CHECK(inside.reward == doctest::Approx(reward_terms(0.0f, 2.5f, s.d_g, 1.0f, 0.8f, true, params.reward).total).epsilon(1e-5));
  // Past the source and out of its radius: Eq. 13 as usual.
  Situation away = make_situation({0, 0}, 0.0f, {0, 3}, {0, -0.7f}, 5, 0);
  const StepOutcome leaving = env.step(away, env.actions().index({0, 2}));
  CHECK_FALSE(leaving.at_source);
  CHECK(away.alpha_level == 2);
}

TEST_CASE("a goal the action walks through is reached where the character passes it") {
  const Params params;
  const auto world = test::hand_made_world(params);
  const Environment env = test::make_environment(params, world.table);
  // The goal 0.7 m ahead: the 1.5 m action ends 0.8 m beyond it (outside the 0.4 m radius), but passes it.
  Situation g = make_situation({0, 0}, 0.0f, {0, 0.7f}, {0, 0.7f}, 2, 0);
  const StepOutcome through = env.step(g, env.actions().index({0, 0}));
  CHECK(through.at_goal);
  // The character stops there: Eq. 15 with d_g' = 0 (and Eq. 14 with the bearing at the action's end).
  CHECK(through.reward == doctest::Approx(reward_terms(0.0f, 0.7f, 0.0f, 0.4f, 0.0f, true, params.reward).total).epsilon(1e-5));
  // A goal 0.5 m to the side of the path is passed by, not reached.
  Situation beside = make_situation({0, 0}, 0.0f, {0.5f, 0.7f}, {0, -50.0f}, 0, 0);
  CHECK_FALSE(env.step(beside, env.actions().index({0, 0})).at_goal);
  // An action that does not move reaches only a goal already within the radius (never the case in training).
  Situation still = make_situation({0, 0}, 0.0f, {0, 0.7f}, {0, -50.0f}, 5, 0);
  CHECK_FALSE(env.step(still, env.actions().index({0, 5})).at_goal);
}

TEST_CASE("exploring starts cover every reachable bin, the last one out to twice the range, never at the goal") {
  const Params params;
  REQUIRE(params.sarsa.far_start_range == doctest::Approx(2.0));
  const auto world = test::hand_made_world(params);
  const Environment env = test::make_environment(params, world.table);
  Rng rng(7);
  std::vector<int> dg(5, 0), tg(8, 0), ti(4, 0), alpha(6, 0);
  int same = 0, beyond_range = 0;
  float farthest = 0.0f;
  for (int i = 0; i < 20000; ++i) {
    Situation s;
    env.exploring_start(rng, 0.5f, params.sarsa.far_start_range, s);
    CHECK(s.d_g >= params.reward.goal_radius);
    const StateBins b = env.states().decode(env.quantize(s));
    ++dg[b.d_g];
    ++tg[b.theta_g];
    ++ti[b.theta_i];
    ++alpha[b.alpha];
    if (s.source_left == s.goal_left && s.source_forward == s.goal_forward) ++same;
    if (s.d_g > 2.0f) ++beyond_range;
    farthest = std::max(farthest, std::max(s.d_g, s.d_i));
  }
  CHECK(dg[0] == 0);  // inside the goal radius (0.4 m = the first bin)
  for (int k = 1; k < 5; ++k) CHECK(dg[k] > 4000);
  for (int k = 0; k < 8; ++k) CHECK(tg[k] > 2000);
  for (int k = 0; k < 4; ++k) CHECK(ti[k] > 4000);
  for (int k = 0; k < 6; ++k) CHECK(alpha[k] > 3000);
  CHECK(same == doctest::Approx(10000).epsilon(0.05));
  // The last bin [1.6, 4.0): 5/6 of its starts lie beyond the 2 m of the quantized range.
  CHECK(beyond_range == doctest::Approx(dg[4] * 5.0 / 6.0).epsilon(0.05));
  CHECK(farthest < 4.0f);
  CHECK(farthest > 3.9f);
  // far_start_range 1: the last bin keeps its own width.
  Rng again(7);
  for (int i = 0; i < 2000; ++i) {
    Situation s;
    env.exploring_start(again, 0.5f, 1.0f, s);
    CHECK(s.d_g < 2.0f);
    CHECK(s.d_i < 2.0f);
  }
}

TEST_CASE("Next(m) restricts the actions") {
  const ActionSpace all(4, 6);
  CHECK(all.size() == 24);
  CHECK(all.allowed(2).size() == 24);
  const ActionSpace graph(4, 6, {{0, 1}, {1}, {2, 3}, {0, 1, 2, 3}});
  CHECK(graph.allowed(1).size() == 6);
  CHECK(graph.allowed_mask(1) == (std::uint64_t{0x3F} << 6));
  CHECK(graph.decode(graph.index({3, 4})).alpha_level == 4);
  CHECK_THROWS_AS(ActionSpace(4, 6, {{0}, {}, {1}, {2}}), std::invalid_argument);
  CHECK_THROWS_AS(ActionSpace(5, 13), std::invalid_argument);  // 65 actions
  // The paper's configuration: actions choose among 5 levels (0 .. 0.8), the sixth (1) is the forcing's.
  const Params params;
  REQUIRE(action_levels(params.quantization) == 5);
  const ActionSpace paper(4, 6, action_levels(params.quantization));
  CHECK(paper.size() == 24);               // the table and the Q rows keep all six levels
  CHECK(paper.allowed(0).size() == 20);
  for (int a : paper.allowed(2)) CHECK(paper.decode(a).alpha_level < 5);
  // Rebuilt from a policy file's masks, exactly.
  const ActionSpace again = ActionSpace::from_masks(4, 6, {paper.allowed_mask(0), paper.allowed_mask(1), paper.allowed_mask(2), paper.allowed_mask(3)});
  for (int m = 0; m < 4; ++m) CHECK(again.allowed_mask(m) == paper.allowed_mask(m));
  CHECK_THROWS_AS(ActionSpace::from_masks(4, 6, {0, 1, 1, 1}), std::invalid_argument);
  CHECK_THROWS_AS(ActionSpace::from_masks(4, 6, {std::uint64_t{1} << 30, 1, 1, 1}), std::invalid_argument);
}
