// prep run: a scenario headless, engine only (no GL): the fixed-step world loop for --seconds, then per
// target motion launched its action, alpha_at_launch and time, and whether the goal was reached. With
// --keys SEED a player at the steering keys (key_player.h) drives the user instead of the scenario's goal
// points, and the run reports how near the bodies came to the objects and to each other.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>

#include "app/cli/command.h"
#include "engine/world/clearance.h"
#include "engine/world/key_player.h"
#include "engine/world/policy_cache.h"
#include "engine/world/world.h"

namespace {

prep::cli::RegisterCommand run_command(
    "run",
    "Run a scenario headless (engine only) and print each target motion launched (action, alpha_at_launch, "
    "time) and whether the goal was reached",
    40, [](CLI::App& app) {
      struct Options {
        std::string scenario;
        float seconds = 30.0f;
        std::string params;
        std::string cache;
        bool json = false;
        float trace = 0.0f;
        long keys = -1;
      };
      auto o = std::make_shared<Options>();
      app.add_option("--scenario", o->scenario, "Scenario JSON (e.g. assets/scenarios/obstacles.json)")->required();
      app.add_option("--seconds", o->seconds, "Simulated seconds (default 30)");
      app.add_option("--params", o->params, "Params JSON (default: the scenario's \"params\", else the defaults)");
      app.add_option("--policy-cache", o->cache, "Folder of cached policies (default: ~/.cache/prep)");
      app.add_flag("--json", o->json, "Print one JSON object");
      app.add_option("--keys", o->keys,
                     "Steer the user with a player at the keys seeded SEED (any of the eight key directions held for a "
                     "while, mostly toward the goal) and report the clearance of the bodies")
          ->check(CLI::NonNegativeNumber);
      app.add_option("--trace", o->trace, "Also print every character's state every TRACE seconds (to stderr; u = the user, o = an opponent)");
      app.callback([o] {
        if (!(o->seconds > 0.0f)) throw std::invalid_argument("--seconds must be positive");
        const prep::Scenario scenario = prep::load_scenario(o->scenario);
        const prep::Params params = o->params.empty() ? prep::load_scenario_params(scenario) : prep::load_params(o->params);
        bool trained = false;
        const std::string cache = o->cache.empty() ? prep::default_policy_cache_dir() : o->cache;
        if (!o->json) std::cerr << "preparing the motion graph and the controller (policy cache: " << cache << ")\n";
        const auto assets = prep::prepare_world_assets(scenario, params, cache, &trained);
        if (!o->json) std::cerr << (trained ? "trained a policy and cached it\n" : "using the cached policy\n");
        if (!o->json)
          std::cerr << "policy: " << assets->policy->steps << " SARSA steps, " << assets->policy->episodes << " episodes"
                    << (assets->policy->converged ? ", converged\n" : ", not converged\n");
        prep::World world(scenario, assets);
        std::optional<prep::KeyPlayer> keys;
        std::optional<prep::ClearanceLog> clearance;
        if (o->keys >= 0) {
          const prep::WorldCharacter& user = world.characters()[static_cast<size_t>(world.user())];
          keys.emplace(static_cast<std::uint64_t>(o->keys), scenario.goal.empty() ? user.position : scenario.goal.back());
          clearance.emplace(world);
        }
        const int ticks = static_cast<int>(std::lround(o->seconds / params.runtime.fixed_dt));
        const int every = o->trace > 0.0f ? std::max(1, static_cast<int>(std::lround(o->trace / params.runtime.fixed_dt))) : 0;
        for (int k = 0; k < ticks; ++k) {
          if (keys) keys->before_tick(world, params.runtime.fixed_dt);
          world.step();
          if (clearance) clearance->observe(world);
          if (every > 0 && world.ticks() % every == 0) {
            for (size_t i = 0; i < world.characters().size(); ++i) {
              const prep::WorldCharacter& u = world.characters()[i];
              std::fprintf(stderr,
                           "t %6.2f %c%zu pos (%6.2f, %6.2f)  heading %7.1f deg  alpha %.2f (chosen %.1f %s)  clip %-12s  "
                           "source %s%s  to launch %.2f m%s\n",
                           world.time(), static_cast<int>(i) == world.user() ? 'u' : 'o', i, u.position.x, u.position.y,
                           u.heading * 57.2957795f, u.alpha, u.chosen_alpha,
                           u.motion >= 0 ? world.assets().policy->table.motion_names[static_cast<size_t>(u.motion)].c_str() : "-",
                           world.assets().set->clips[static_cast<size_t>(u.clip)].clip.name.c_str(),
                           u.has_source ? prep::target_action_name(u.prepared_for) : "-", u.source_ahead ? " (ahead)" : "",
                           u.to_launch, u.arrived ? "  arrived" : "");
            }
          }
        }
        const prep::RunSummary summary = prep::summarize(world);
        if (o->json) {
          std::string text = prep::summary_json(summary, world);
          if (clearance) {
            nlohmann::json j = nlohmann::json::parse(text);
            j["keys_seed"] = o->keys;
            j["clearance"] = prep::clearance_json(clearance->summary);
            text = j.dump(2);
          }
          std::cout << text << "\n";
        } else {
          std::cout << prep::summary_text(summary);
          if (clearance) std::cout << prep::clearance_text(clearance->summary);
        }
      });
    });

}  // namespace
