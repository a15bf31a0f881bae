#include <doctest/doctest.h>

#include <cmath>
#include <cstring>
#include <stdexcept>

#include "engine/control/evaluation.h"
#include "engine/control/policy.h"
#include "engine/control/sarsa.h"
#include "hand_made.h"

using namespace prep;

TEST_CASE("the same seed and thread count give the same Q table bit for bit") {
  Params params = test::small_params();
  params.sarsa.threads = 2;
  params.sarsa.max_steps = 150000;
  const auto world = test::hand_made_world(params);
  const Environment env = test::make_environment(params, world.table);
  const TrainingResult a = train_sarsa(env, params.sarsa);
  const TrainingResult b = train_sarsa(env, params.sarsa);
  REQUIRE(a.q.size() == b.q.size());
  CHECK(std::memcmp(a.q.data(), b.q.data(), a.q.size() * sizeof(float)) == 0);
  CHECK(a.steps == b.steps);
  CHECK(a.episodes == b.episodes);
  // ... and so the same policy file, byte for byte.
  const ActionSpace actions(env.states().motions(), env.states().alpha_levels());
  CHECK(serialize_policy(make_policy(params, world.table, actions, a)) == serialize_policy(make_policy(params, world.table, actions, b)));
  params.sarsa.seed = 2;
  const TrainingResult c = train_sarsa(env, params.sarsa);
  CHECK(std::memcmp(a.q.data(), c.q.data(), a.q.size() * sizeof(float)) != 0);
}

TEST_CASE("a small training run converges, its return rises, and its greedy episodes reach the goal") {
  Params params = test::small_params();
  const auto world = test::hand_made_world(params);
  const Environment env = test::make_environment(params, world.table);
  const TrainingResult r = train_sarsa(env, params.sarsa);
  CHECK(r.converged);
  CHECK(r.steps > 0);
  REQUIRE(r.curve.size() >= 2);
  CHECK(r.curve.back().average_return > r.curve.front().average_return);
  // Greedy episodes of the training environment itself, from ahead and from behind.
  for (float bearing : {0.0f, 1.5f, 3.0f}) {
    const Situation start = make_situation({0, 0}, 0.0f, {2.0f * std::sin(bearing), 2.0f * std::cos(bearing)},
                                           {2.0f * std::sin(bearing), 2.0f * std::cos(bearing)}, 0, 0);
    const EpisodeTrace t = greedy_episode(env, r.q, start, 100);
    CAPTURE(bearing);
    CHECK(t.reached_goal);
    CHECK(t.actions.size() >= 2);
  }
}

TEST_CASE("training refuses impossible settings") {
  Params params = test::small_params();
  const auto world = test::hand_made_world(params);
  const Environment env = test::make_environment(params, world.table);
  SarsaParams bad = params.sarsa;
  bad.threads = 0;
  CHECK_THROWS_AS(train_sarsa(env, bad), std::invalid_argument);
  bad = params.sarsa;
  bad.discount = 1.0f;
  CHECK_THROWS_AS(train_sarsa(env, bad), std::invalid_argument);
}
