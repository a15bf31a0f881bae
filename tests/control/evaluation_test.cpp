#include <doctest/doctest.h>

#include <cmath>
#include <stdexcept>
#include <vector>

#include "engine/control/arrival.h"
#include "engine/control/controller.h"
#include "engine/control/evaluation.h"
#include "engine/control/sarsa.h"
#include "hand_made.h"

using namespace prep;

namespace {

// A hand-written policy over the default quantization: steer toward the goal's bearing bin (walk when it
// is ahead, else turn its way) at one fixed alpha level. Its Q table is 1 for that action, 0 elsewhere.
std::vector<float> steering_q(const StateSpace& states, const ActionSpace& actions, int level) {
  std::vector<float> q(static_cast<size_t>(states.size()) * static_cast<size_t>(actions.size()), 0.0f);
  const int half = states.theta_g_bins() / 2;
  for (int s = 0; s < states.size(); ++s) {
    const StateBins b = states.decode(s);
    const int motion = b.theta_g == 0 ? 0 : b.theta_g <= half ? 1 : 2;  // walk, turn_left, turn_right
    q[static_cast<size_t>(s) * static_cast<size_t>(actions.size()) + static_cast<size_t>(actions.index({motion, level}))] = 1.0f;
  }
  return q;
}

}  // namespace

TEST_CASE("the arrival radius is the stopping distance of the top moving level, from the filter and Eq. 3-4") {
  const Params params;
  const auto world = test::hand_made_world(params);
  const ArrivalModel arrival(world.table, params.quantization.alpha_step, params.runtime);
  CHECK(arrival.approach_level() == doctest::Approx(0.8));
  // The fastest core motion at 0.8: the hand-made walk, 1.5 m/s x (1 - w_r(0.8)).
  const float w08 = world.table.curve.weight(0.8f);
  CHECK(arrival.approach_speed() == doctest::Approx(1.5f * (1.0f - w08)).epsilon(1e-3));
  // Replayed here by hand: the filter from 0.8 pushed with 1s, the stride (1 - w_r) of what comes out.
  AlphaFilter f(params.runtime.alpha_sigma_s, params.runtime.fixed_dt);
  f.reset(0.8f);
  float distance = 0.0f, to_launch_alpha = 0.0f;
  for (int k = 0; k < 200 && f.value() < 1.0f; ++k) {
    const float a = f.push(1.0f);
    distance += (1.0f - world.table.curve.weight(a)) * 1.5f * params.runtime.fixed_dt;
    if (a < params.runtime.launch_alpha) to_launch_alpha += params.runtime.fixed_dt;
  }
  CHECK(arrival.glide_distance() == doctest::Approx(distance).epsilon(1e-4));
  CHECK(arrival.glide_time() == doctest::Approx(to_launch_alpha).epsilon(1e-4));
  CHECK(arrival.stop_time() == doctest::Approx(std::ceil(3 * params.runtime.alpha_sigma_s / params.runtime.fixed_dt) *
                                               params.runtime.fixed_dt).epsilon(0.02));
  CHECK(arrival.glide_distance() > 0.05f);
  CHECK(arrival.glide_distance() < 0.3f);
  // A source walking in at 1 m/s adds what it covers while the character gets ready.
  CHECK(arrival.radius(1.0f) == doctest::Approx(arrival.glide_distance() + arrival.glide_time()).epsilon(1e-5));
  CHECK(arrival.radius(-1.0f) == doctest::Approx(arrival.glide_distance()));
  RuntimeParams bad = params.runtime;
  bad.launch_alpha = 1.5f;
  CHECK_THROWS_AS(ArrivalModel(world.table, 0.2f, bad), std::invalid_argument);
}

TEST_CASE("evaluation measures the approach: a dash arrives unprepared, a prepared walk arrives at launch_alpha") {
  const Params params;
  const auto world = test::hand_made_world(params);
  const StateSpace states(params.quantization, world.table.motions);
  const ActionSpace actions(states.motions(), states.alpha_levels());
  // Straight at the goal at alpha 0: it always gets there, but nothing prepares it, so the forcing on
  // arrival has no time to raise alpha before the launch point passes (arrival.h).
  const PolicyEvaluation dash = evaluate_policy(test::hand_made_policy(params, world, steering_q(states, actions, 0)), params, 300, 5);
  CHECK(dash.goal_reached_ratio > 0.6);  // a wide turn (1.2 m radius) sometimes orbits a goal close by
  CHECK(dash.median_level_at_arrival == doctest::Approx(0.0));
  CHECK(dash.median_alpha_at_source < 0.5);
  CHECK(dash.alpha_at_1m_ratio < 0.05);
  // The same steering at the top moving level: the launch comes at launch_alpha (0.9), prepared at 1 m.
  const PolicyEvaluation prepared = evaluate_policy(test::hand_made_policy(params, world, steering_q(states, actions, 4)), params, 300, 5);
  CHECK(prepared.goal_reached_ratio > 0.95);
  CHECK(prepared.median_level_at_arrival == doctest::Approx(0.8));
  CHECK(prepared.median_alpha_at_source >= params.runtime.launch_alpha);
  CHECK(prepared.median_alpha_at_source < 0.95);
  CHECK(prepared.alpha_at_1m_ratio > 0.95);
  CHECK(prepared.median_alpha_at_1m == doctest::Approx(0.8).epsilon(0.01));
  CHECK(prepared.median_seconds_to_goal > 2.0 * dash.median_seconds_to_goal);  // Eq. 3-4 slow it down
  // A table that prefers alpha 1 everywhere: the top level is the forcing's alone (forced_top_level), so
  // the controller never chooses it, and the character still moves.
  const auto at_one = test::hand_made_policy(params, world, steering_q(states, actions, 5));
  Controller c(at_one, params);
  c.reset(0, 0);
  ControlInput in;
  in.goal = in.source = {0.0f, 3.0f};
  CHECK(c.decide(in).alpha_level < states.top_alpha_level());
}

TEST_CASE("a trained policy with the paper's constants reaches the goal prepared (small quantization)") {
  Params params = test::small_params();
  const auto world = test::hand_made_world(params);
  const Environment env = test::make_environment(params, world.table);
  const TrainingResult r = train_sarsa(env, params.sarsa);
  CHECK(r.converged);
  const PolicyEvaluation e = evaluate_policy(test::hand_made_policy(params, world, r.q), params, 300, 9);
  CHECK(e.goal_reached_ratio >= 0.9);
  CHECK(e.median_level_at_arrival == doctest::Approx(0.8));  // the top level that moves
  CHECK(e.median_alpha_at_source >= params.runtime.launch_alpha);
  CHECK(e.alpha_at_1m_ratio > 0.5);
  // The untrained table (all zero) walks straight ahead at alpha 0 and rarely meets the goal.
  const PolicyEvaluation untrained = evaluate_policy(test::hand_made_policy(params, world, std::vector<float>(r.q.size(), 0.0f)), params, 300, 9);
  CHECK(untrained.goal_reached_ratio < 0.3);
}
