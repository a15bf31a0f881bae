// prep evaluate-policy: greedy episodes of a trained policy from random starts (engine/control/evaluation.h).
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "app/cli/command.h"
#include "engine/control/evaluation.h"
#include "engine/control/policy.h"
#include "engine/params/params.h"

namespace {

struct EvalOptions {
  std::string policy, params;
  int episodes = 1000;
  std::uint64_t seed = 12345;
  bool json = false;
};

void run(const EvalOptions& o) {
  const prep::Params params = o.params.empty() ? prep::Params{} : prep::load_params(o.params);
  const auto policy = std::make_shared<const prep::Policy>(prep::load_policy(o.policy, params));  // refuses another configuration
  const prep::PolicyEvaluation e = prep::evaluate_policy(policy, params, o.episodes, o.seed);
  if (o.json) {
    nlohmann::json j;
    j["episodes"] = e.episodes;
    j["goal_reached_ratio"] = e.goal_reached_ratio;
    j["median_steps_to_goal"] = e.median_steps_to_goal;
    j["median_alpha_at_source"] = e.median_alpha_at_source;
    j["alpha_at_1m_ratio"] = e.alpha_at_1m_ratio;
    j["played_alpha_at_1m_ratio"] = e.played_alpha_at_1m_ratio;
    j["median_level_at_arrival"] = e.median_level_at_arrival;
    j["median_alpha_at_1m"] = e.median_alpha_at_1m;
    j["median_seconds_to_goal"] = e.median_seconds_to_goal;
    std::cout << j.dump(2) << "\n";
  } else {
    std::cout << e.episodes << " episodes: goal reached " << 100.0 * e.goal_reached_ratio << "%, median "
              << e.median_steps_to_goal << " steps to the goal, median alpha at the source " << e.median_alpha_at_source
              << " (the policy's level on arrival " << e.median_level_at_arrival << "), alpha >= 0.5 at 1 m in "
              << 100.0 * e.alpha_at_1m_ratio << "% of episodes\n";
  }
}

prep::cli::RegisterCommand evaluate_policy_command(
    "evaluate-policy", "Measure a trained policy over random starts (goal reached, preparation on arrival)", 41,
    [](CLI::App& app) {
      auto o = std::make_shared<EvalOptions>();
      app.add_option("--policy", o->policy, "Policy file from prep train")->required();
      app.add_option("--episodes", o->episodes, "Number of episodes (default 1000)");
      app.add_option("--seed", o->seed, "Seed of the random starts");
      app.add_flag("--json", o->json, "Print a JSON object");
      app.add_option("--params", o->params, "Params JSON file the policy was trained with (default: built-in)");
      app.callback([o] { run(*o); });
    });

}  // namespace
