#include <doctest/doctest.h>

#include <cstring>
#include <stdexcept>

#include "engine/control/evaluation.h"
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
  params.sarsa.seed = 2;
  const TrainingResult c = train_sarsa(env, params.sarsa);
  CHECK(std::memcmp(a.q.data(), c.q.data(), a.q.size() * sizeof(float)) != 0);
}

TEST_CASE("a small training run converges and its greedy policy reaches the goal") {
  Params params = test::small_params();
  const auto world = test::hand_made_world(params);
  const Environment env = test::make_environment(params, world.table);
  const TrainingResult r = train_sarsa(env, params.sarsa);
  CHECK(r.steps > 0);
  CHECK(r.curve.size() >= 2);
  CHECK(r.curve.back().average_return > r.curve.front().average_return);
  const PolicyEvaluation e = evaluate_policy(env, r.q, 200, 99, params.sarsa.max_episode_steps, params.sarsa.discount);
  CHECK(r.converged);
  CHECK(e.goal_reached_ratio >= 0.75);
  // An untrained table (all zero) walks straight ahead at alpha 0 and rarely finds the goal.
  const PolicyEvaluation untrained = evaluate_policy(env, std::vector<float>(r.q.size(), 0.0f), 200, 99,
                                                     params.sarsa.max_episode_steps, params.sarsa.discount);
  CHECK(untrained.goal_reached_ratio < 0.3);
  CHECK(e.median_steps_to_goal > 2);
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
