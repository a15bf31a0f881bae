#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <vector>

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

namespace {
// The greedy choice written the plain way: the first allowed action holding the largest allowed value (by
// `>`, so a NaN never wins). greedy_action must agree with it exactly.
int greedy_by_scan(const float* row, std::uint64_t allowed, int n) {
  int best = -1;
  for (int a = 0; a < n; ++a)
    if ((allowed >> a & 1u) && (best < 0 || row[a] > row[best] || std::isnan(row[best]))) best = a;
  return best;
}
}  // namespace

TEST_CASE("greedy_action picks the first allowed action holding the allowed maximum, for every row width") {
  Rng rng(7);
  const float specials[] = {0.0f, -0.0f, 1.0f, -1.0f, std::numeric_limits<float>::infinity(),
                            -std::numeric_limits<float>::infinity(), std::nanf("")};
  std::vector<float> row(64);
  int with_ties = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    const int n = 1 + rng.below(64);
    std::uint64_t allowed = 0;
    while (allowed == 0)
      for (int a = 0; a < n; ++a) allowed |= static_cast<std::uint64_t>(rng.uniform() < 0.7f) << a;
    // Few distinct values, so ties (also +0 against -0) and specials are common.
    for (int a = 0; a < n; ++a)
      row[static_cast<size_t>(a)] = rng.uniform() < 0.1f ? specials[rng.below(7)] : static_cast<float>(rng.below(4)) * 0.25f;
    const int expected = greedy_by_scan(row.data(), allowed, n);
    if (std::isnan(row[static_cast<size_t>(expected)])) continue;  // only NaN allowed: no maximum (checked below)
    CAPTURE(n);
    CAPTURE(trial);
    REQUIRE(greedy_action(row.data(), allowed, n) == expected);
    int holders = 0;
    for (int a = 0; a < n; ++a) holders += (allowed >> a & 1u) && row[static_cast<size_t>(a)] == row[static_cast<size_t>(expected)];
    with_ties += holders > 1;
  }
  CHECK(with_ties > 1000);
  // Every allowed value NaN: the lowest allowed action.
  std::fill(row.begin(), row.end(), std::nanf(""));
  CHECK(greedy_action(row.data(), 0b101000, 24) == 3);
}

TEST_CASE("the training step's bearings and distances are fast_atan2's and sqrt's bit for bit") {
  // update_polar takes the goal's and the source's together (four lanes, no branches where SSE2 is there);
  // it must give the scalar values exactly, signed zeros, the origin and non-finite input included.
  Rng rng(11);
  const float specials[] = {0.0f, -0.0f, 1.0f, -1.0f, 1e-30f, -1e-30f, 3.0f, -3.0f,
                            std::numeric_limits<float>::infinity(), -std::numeric_limits<float>::infinity(), std::nanf("")};
  auto component = [&] {
    return rng.uniform() < 0.2f ? specials[rng.below(11)] : rng.uniform(-10.0f, 10.0f);
  };
  auto same = [](float a, float b) { return std::memcmp(&a, &b, sizeof(float)) == 0 || (std::isnan(a) && std::isnan(b)); };
  int diagonal = 0;
  for (int trial = 0; trial < 100000; ++trial) {
    Situation s;
    s.goal_left = component();
    s.goal_forward = trial % 7 == 0 ? s.goal_left : component();  // the octant boundary |left| = |forward|
    s.source_left = component();
    s.source_forward = trial % 5 == 0 ? -s.source_left : component();
    diagonal += std::fabs(s.goal_left) == std::fabs(s.goal_forward);
    s.update_polar();
    CAPTURE(trial);
    REQUIRE(same(s.theta_g, fast_atan2(s.goal_left, s.goal_forward)));
    REQUIRE(same(s.theta_i, fast_atan2(s.source_left, s.source_forward)));
    REQUIRE(same(s.d_g, std::sqrt(s.goal_left * s.goal_left + s.goal_forward * s.goal_forward)));
    REQUIRE(same(s.d_i, std::sqrt(s.source_left * s.source_left + s.source_forward * s.source_forward)));
  }
  CHECK(diagonal > 10000);
}

TEST_CASE("the training step's state index is the bins' index exactly, bin edges and odd input included") {
  // Environment::quantize takes the four bins together (StateSpace::index_of); it must agree with
  // d_g_bin ... theta_i_bin everywhere: on bin edges, beyond the last distance bin, for bearings a turn or
  // more off, negative distances, signed zeros, infinities and NaN.
  for (const Params& params : {Params{}, test::small_params()}) {
    const StateSpace states(params.quantization, 4);
    Rng rng(5);
    const float odd[] = {0.0f, -0.0f, -1.0f, 1e9f, -1e9f, 7.0f, -7.0f, 3.14159265f, -3.14159265f,
                         std::numeric_limits<float>::infinity(), -std::numeric_limits<float>::infinity(), std::nanf("")};
    auto distance = [&] {
      if (rng.uniform() < 0.1f) return odd[rng.below(12)];
      if (rng.uniform() < 0.3f) return static_cast<float>(rng.below(states.d_g_bins() + 2)) * states.d_step();  // an edge
      return rng.uniform(0.0f, 1.5f * states.d_step() * static_cast<float>(states.d_g_bins()));
    };
    auto bearing = [&](float step) {
      if (rng.uniform() < 0.1f) return odd[rng.below(12)];
      if (rng.uniform() < 0.3f) return (static_cast<float>(rng.below(17)) - 8.5f) * step;  // an edge
      return rng.uniform(-3.14159265f, 3.14159265f);
    };
    int fast = 0;
    for (int trial = 0; trial < 100000; ++trial) {
      const int alpha = rng.below(states.alpha_levels()), motion = rng.below(states.motions());
      const float d_g = distance(), d_i = distance();
      const float theta_g = bearing(states.theta_g_step()), theta_i = bearing(states.theta_i_step());
      const int expected = states.index({alpha, motion, states.d_g_bin(d_g), states.theta_g_bin(theta_g),
                                         states.d_i_bin(d_i), states.theta_i_bin(theta_i)});
      CAPTURE(trial);
      REQUIRE(states.index_of(alpha, motion, d_g, theta_g, d_i, theta_i) == expected);
      fast += std::fabs(theta_g) < 3.2f && std::fabs(theta_i) < 3.2f;
    }
    CHECK(fast > 50000);
  }
}
