#include <doctest/doctest.h>

#include <cmath>
#include <cstdint>
#include <initializer_list>
#include <memory>
#include <random>
#include <vector>
#include <algorithm>
#include <stdexcept>

#include "engine/control/controller.h"
#include "engine/control/sarsa.h"
#include "engine/control/state.h"
#include "hand_made.h"

using namespace prep;

namespace {

// A Q table that ranks `ranked` (action indices) in every state, the first highest; every other action 0.
std::vector<float> ranking(const StateSpace& states, const ActionSpace& actions, std::initializer_list<int> ranked) {
  std::vector<float> q(static_cast<size_t>(states.size()) * static_cast<size_t>(actions.size()), 0.0f);
  for (int s = 0; s < states.size(); ++s) {
    float value = static_cast<float>(ranked.size());
    for (int a : ranked) q[static_cast<size_t>(s) * static_cast<size_t>(actions.size()) + static_cast<size_t>(a)] = value--;
  }
  return q;
}

}  // namespace

TEST_CASE("the Gaussian alpha filter answers a step like erf(t / (sigma sqrt 2))") {
  const float sigma = 0.25f, dt = 1.0f / 60.0f;
  AlphaFilter f(sigma, dt);
  CHECK(f.taps() == static_cast<int>(std::ceil(3 * sigma / dt)) + 1);
  f.reset(0.0f);
  float y = 0.0f;
  for (int k = 0; k < f.taps() + 5; ++k) {
    y = f.push(1.0f);
    // After k + 1 samples of 1 the output is the share of the kernel's weight on the last k + 1 ticks,
    // about the half-normal CDF at t = (k + 0.5) dt.
    const float t = (static_cast<float>(k) + 0.5f) * dt;
    CHECK(y == doctest::Approx(std::erf(t / (sigma * std::sqrt(2.0f)))).epsilon(0.03));
    if (k > 0) CHECK(y >= 0.0f);
  }
  CHECK(y == doctest::Approx(1.0));
  // Monotone, smooth rise: after sigma about 68%.
  f.reset(0.0f);
  for (int k = 0; k < static_cast<int>(sigma / dt); ++k) y = f.push(1.0f);
  CHECK(y == doctest::Approx(0.68).epsilon(0.05));
  // A zero sigma passes alpha straight through.
  AlphaFilter none(0.0f, dt);
  none.reset(0.2f);
  CHECK(none.push(0.8f) == doctest::Approx(0.8));
}

TEST_CASE("the alpha filter's ring walk gives the same floats as the weighted sum taken tap by tap") {
  // The filter as the paper's Gaussian reads: sum over k of w_k alpha(t - k dt), divided by the sum of the
  // weights used, each k's sample found by index arithmetic. push() walks the ring in two runs instead,
  // and skips the sum when the window holds one level throughout and held it the push before: the levels
  // here come in runs, longer and shorter than the window, and the reset is followed by its own level.
  for (const float sigma : {0.25f, 0.1f, 0.0f}) {
    CAPTURE(sigma);
    const float dt = 1.0f / 60.0f;
    AlphaFilter f(sigma, dt);
    const int n = f.taps();
    std::vector<float> w(static_cast<size_t>(n)), ring(static_cast<size_t>(n), 0.0f);
    for (int k = 0; k < n; ++k) {
      const float t = static_cast<float>(k) * dt;
      w[static_cast<size_t>(k)] = sigma > 0.0f ? std::exp(-t * t / (2.0f * sigma * sigma)) : 1.0f;
    }
    int head = 0, count = 0;
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> level(0.0f, 1.0f);
    std::uniform_int_distribution<int> run_length(1, 3 * n + 2);
    float a = 0.0f;
    int run_left = 0, skipped = 0;
    for (int tick = 0; tick < 6000; ++tick) {
      if (tick == 1000 || tick == 4000) {  // a reset part way: the ring filled with one level
        f.reset(0.4f);
        std::fill(ring.begin(), ring.end(), 0.4f);
        count = n;
        a = 0.4f;
        run_left = run_length(rng);
      }
      if (run_left-- <= 0) {
        a = tick % 3 == 0 ? level(rng) : static_cast<float>(tick % 2);  // a level, or full or none
        run_left = run_length(rng);
      }
      skipped += count == n && run_left > 0;
      head = (head + 1) % n;
      ring[static_cast<size_t>(head)] = a;
      if (count < n) ++count;
      float sum = 0.0f, weight = 0.0f;
      for (int k = 0; k < count; ++k) {
        sum += w[static_cast<size_t>(k)] * ring[static_cast<size_t>((head - k + n) % n)];
        weight += w[static_cast<size_t>(k)];
      }
      REQUIRE(f.push(a) == sum / weight);
    }
    CHECK(skipped > 1000);  // long runs were held
  }
}

TEST_CASE("the runtime controller takes the greedy action and feeds its alpha back (Eq. 13)") {
  Params params = test::small_params();
  const auto world = test::hand_made_world(params);
  const Environment env = test::make_environment(params, world.table);
  const TrainingResult r = train_sarsa(env, params.sarsa);
  const auto policy = test::hand_made_policy(params, world, r.q);
  Controller c(policy, params);
  c.reset(3, 0);
  ControlInput in;
  in.position = {1.0f, 2.0f};
  in.heading = 0.4f;
  in.goal = in.source = {3.0f, 5.0f};
  const ControlDecision d = c.decide(in);
  const Situation s = make_situation(in.position, in.heading, in.goal, in.source, 0, 3);
  CHECK(d.state == env.quantize(s));
  CHECK(d.action == greedy_action(env, r.q.data() + static_cast<size_t>(d.state) * env.actions().size(), 3));
  CHECK(c.alpha_level() == d.alpha_level);
  CHECK(c.motion() == d.motion);
  const float a1 = c.tick();
  CHECK(a1 <= d.alpha + 1e-6f);

  ControllerBank bank;
  bank.add(policy);
  CHECK(bank.for_curve(world.table.curve).get() == policy.get());
  CHECK(bank.for_curve(RootCurve{1.0f, 1.0f, false}).get() == nullptr);
  CHECK_THROWS_AS(bank.add(policy), std::invalid_argument);
}

TEST_CASE("at run time the state's alpha is forced to 1 within the source radius, as in training") {
  const Params params;
  const auto world = test::hand_made_world(params);
  const StateSpace states(params.quantization, world.table.motions);
  const ActionSpace actions(states.motions(), states.alpha_levels());
  std::vector<float> q(static_cast<size_t>(states.size()) * static_cast<size_t>(actions.size()), 0.0f);
  for (int s = 0; s < states.size(); ++s) q[static_cast<size_t>(s) * actions.size() + static_cast<size_t>(actions.index({0, 4}))] = 1.0f;
  Controller c(test::hand_made_policy(params, world, q), params);
  c.reset(0, 2);
  ControlInput in;
  in.goal = {0.0f, 5.0f};
  in.source = {0.0f, 1.5f};  // outside the 1 m radius: the state keeps its alpha (level 2)
  ControlDecision d = c.decide(in);
  CHECK_FALSE(d.at_source);
  CHECK(states.decode(d.state).alpha == 2);
  CHECK(d.alpha_level == 4);
  in.source = {0.0f, 0.9f};  // inside: decided in the state whose alpha is 1
  d = c.decide(in);
  CHECK(d.at_source);
  CHECK(states.decode(d.state).alpha == states.top_alpha_level());
  CHECK(d.alpha_level == 4);  // and it plays the action's level (Eq. 13)
  CHECK(c.alpha_of_level(c.alpha_level()) == doctest::Approx(0.8));
  // Within the goal radius nothing was learned (episodes end there): the action playing is kept.
  c.reset(1, 3);
  in.goal = {0.0f, 0.3f};
  d = c.decide(in);
  CHECK(d.at_goal);
  CHECK(d.state == -1);
  CHECK(d.motion == 1);
  CHECK(d.alpha_level == 3);
  // Arrived: the played alpha is 1, the filter rises from where it was to exactly 1 after its last tap.
  c.reset(0, 4);
  c.set_arrived(true);
  CHECK(c.alpha_level() == states.top_alpha_level());
  float a = c.tick();
  CHECK(a > 0.8f);
  CHECK(a < 0.85f);
  for (int k = 0; k < 60; ++k) a = c.tick();
  CHECK(a == doctest::Approx(1.0));
  c.reset(0, 0);
  CHECK_FALSE(c.arrived());
  CHECK(c.tick() == doctest::Approx(0.0));
}

TEST_CASE("actions the caller rules out are passed over for the best of the rest, unless none would be left") {
  const Params params;
  const auto world = test::hand_made_world(params);
  const StateSpace states(params.quantization, world.table.motions);
  const ActionSpace actions(states.motions(), states.alpha_levels());
  // Every state ranks (motion 1, level 2) first, (motion 0, level 3) second.
  const int first = actions.index({1, 2}), second = actions.index({0, 3});
  Controller c(test::hand_made_policy(params, world, ranking(states, actions, {first, second})), params);
  ControlInput in;
  in.goal = {0.0f, 5.0f};
  in.source = {0.0f, 3.0f};
  c.reset(0, 0);
  CHECK(c.decide(in).action == first);
  c.reset(0, 0);
  in.ruled_out = std::uint64_t{1} << first;
  const ControlDecision d = c.decide(in);
  CHECK(d.action == second);
  CHECK(d.motion == 0);
  CHECK(d.alpha_level == 3);
  // Everything ruled out: the rule is set aside and the greedy action stands.
  c.reset(0, 0);
  in.ruled_out = ~std::uint64_t{0};
  CHECK(c.decide(in).action == first);
}

TEST_CASE("a level chosen again keeps the motion playing and never falls: the best level of that motion, whatever is ruled out") {
  const Params params;
  const auto world = test::hand_made_world(params);
  const StateSpace states(params.quantization, world.table.motions);
  const ActionSpace actions(states.motions(), states.alpha_levels());
  // Every state ranks (motion 1, level 2) first, (motion 0, level 3) second, (motion 0, level 1) third.
  const int first = actions.index({1, 2}), second = actions.index({0, 3}), third = actions.index({0, 1});
  Controller c(test::hand_made_policy(params, world, ranking(states, actions, {first, second, third})), params);
  ControlInput in;
  in.goal = {0.0f, 5.0f};
  in.source = {0.0f, 3.0f};
  c.reset(0, 0);
  ControlDecision d = c.decide_level(in);
  CHECK(d.motion == 0);  // motion 1's action ranks first, but motion 0 plays
  CHECK(d.action == second);
  CHECK(d.alpha_level == 3);
  CHECK(c.motion() == 0);
  CHECK(c.alpha_level() == 3);  // the played level follows (Eq. 13)
  // A rule that would pass over the motion playing does not make the level change the motion.
  c.reset(0, 0);
  in.ruled_out = (std::uint64_t{1} << second) | (std::uint64_t{1} << third);
  d = c.decide_level(in);
  CHECK(d.motion == 0);
  CHECK(d.action == second);
  // Playing above the best level of its motion (0.8 against 0.6), the level stays: it never falls.
  c.reset(0, 4);
  in.ruled_out = 0;
  d = c.decide_level(in);
  CHECK(d.motion == 0);
  CHECK(d.alpha_level == 4);
  CHECK(d.action == actions.index({0, 4}));
  CHECK(c.alpha_level() == 4);
  // The source's distance bin, as the state has it (0.4 m bins, the last one open).
  CHECK(c.source_bin(0.39f) == 0);
  CHECK(c.source_bin(1.3f) == 3);
  CHECK(c.source_bin(50.0f) == states.d_i_bins() - 1);
}

TEST_CASE("a filter width changed while running starts from the alpha played and then follows its own width") {
  const Params params;  // sigma 0.25 s at 60 Hz
  const auto world = test::hand_made_world(params);
  const StateSpace states(params.quantization, world.table.motions);
  const ActionSpace actions(states.motions(), states.alpha_levels());
  const auto policy = test::hand_made_policy(params, world, ranking(states, actions, {actions.index({0, 0})}));
  const float dt = params.runtime.fixed_dt;
  // Arrived, the played alpha steps from the level's 0.4 to 1; a few ticks in, the width changes.
  Controller kept(policy, params), changed(policy, params);
  for (Controller* c : {&kept, &changed}) {
    c->reset(0, 2);
    c->set_arrived(true);
    for (int t = 0; t < 6; ++t) c->tick();
  }
  const float before = changed.filtered_alpha();
  REQUIRE(before > 0.45f);
  REQUIRE(before < 0.7f);
  const float sigma = 0.05f;
  changed.set_smoothing(sigma, dt);
  CHECK(changed.filtered_alpha() == before);  // no jump where the width changes
  // From there the step to 1 rises tick for tick as a filter of the new width, started at `before`, answers
  // it: all the way within 3 sigma (10 ticks), where the old width is still far from 1.
  AlphaFilter reference(sigma, dt);
  reference.reset(before);
  for (int t = 0; t < 10; ++t) {
    CHECK(changed.tick() == reference.push(1.0f));
    kept.tick();
  }
  CHECK(changed.filtered_alpha() > 0.99f);
  CHECK(kept.filtered_alpha() < 0.95f);
}
