#include <doctest/doctest.h>

#include <cmath>

#include "engine/control/reward.h"
#include "tests/support/angles.h"

using namespace prep;

namespace {
using test::kPi;
}

TEST_CASE("Eq. 14-17 at a hand-computed state") {
  const RewardParams p;  // theta_norm 180 deg, d_norm 1 m, C_alpha 2, weights 0.1 / 0.3 / 0.6
  // The goal 45 degrees off after the action, 0.5 m closer, alpha raised from 0.2 to 0.6.
  const RewardTerms t = reward_terms(kPi / 4, 1.6f, 1.1f, 0.2f, 0.6f, false, p);
  CHECK(t.facing == doctest::Approx(0.75));                      // 1 - 45/180
  CHECK(t.approach == doctest::Approx(0.75));                    // (1 + 1.6 - 1.1) / 2
  CHECK(t.steadiness == doctest::Approx(0.84));                  // 1 - 0.4^2
  CHECK(t.total == doctest::Approx(0.1 * 0.75 + 0.3 * 0.75 + 0.6 * 0.84));  // 0.804
  CHECK(t.total == doctest::Approx(0.804));
}

TEST_CASE("Eq. 14-16 extremes") {
  const RewardParams p;
  CHECK(reward_facing(0.0f, p) == doctest::Approx(1.0));
  CHECK(reward_facing(-kPi, p) == doctest::Approx(0.0));
  CHECK(reward_approach(2.0f, 2.0f, p) == doctest::Approx(0.5));  // standing still
  CHECK(reward_approach(2.0f, 1.0f, p) == doctest::Approx(1.0));  // d_norm closer
  CHECK(reward_approach(1.0f, 2.0f, p) == doctest::Approx(0.0));  // d_norm away
  CHECK(reward_steadiness(0.4f, 0.4f, p) == doctest::Approx(1.0));
  CHECK(reward_steadiness(0.0f, 1.0f, p) == doctest::Approx(0.0));
}

TEST_CASE("at the source alpha jumps to 1: both changes of the played alpha are penalised") {
  const RewardParams p;
  // From 0.6, playing 0.8, then forced to 1: 1 - 0.2^2 - 0.2^2.
  CHECK(reward_steadiness_at_source(0.6f, 0.8f, p) == doctest::Approx(0.92));
  // Arriving prepared costs nothing; the literal state-to-state penalty |1 - 0.6|^2 is never exceeded.
  CHECK(reward_steadiness_at_source(1.0f, 1.0f, p) == doctest::Approx(1.0));
  for (float a = 0.6f; a <= 1.0f; a += 0.1f)
    CHECK(reward_steadiness_at_source(0.6f, a, p) >= reward_steadiness(0.6f, 1.0f, p) - 1e-6f);
  // Dashing in at alpha 0 after preparing is the worst choice.
  CHECK(reward_steadiness_at_source(0.6f, 0.0f, p) < reward_steadiness_at_source(0.6f, 0.8f, p));
}

TEST_CASE("the tabulated reward model equals Eq. 17") {
  const RewardParams p;
  const RewardModel model(p, 6, 0.2f);
  for (int from = 0; from < 6; ++from)
    for (int to = 0; to < 6; ++to)
      for (bool source : {false, true}) {
        const RewardTerms t = reward_terms(1.0f, 1.5f, 1.2f, 0.2f * from, 0.2f * to, source, p);
        CHECK(model(1.0f, 1.5f, 1.2f, from, to, source) == doctest::Approx(t.total).epsilon(1e-5));
      }
  CHECK(model.max_reward() == doctest::Approx(1.0));
  CHECK(goal_value(p, 0.3f) == doctest::Approx(1.0 / 0.7));
}
