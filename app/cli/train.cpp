// prep train: trains the behaviour controller (Sec. 6) on a motion set's core locomotion and writes the
// policy, the training curve (average return per state against steps, Fig. 10) as CSV and as a PNG plot.
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>

#include "app/cli/command.h"
#include "engine/control/action_effects.h"
#include "engine/control/environment.h"
#include "engine/control/policy.h"
#include "engine/control/sarsa.h"
#include "engine/library/builtin.h"
#include "engine/motion/motion_set.h"
#include "engine/params/params.h"
#include "engine/util/error.h"
#include "engine/util/files.h"
#include "engine/util/plot.h"

namespace {

struct TrainOptions {
  std::string motions, target = "kick", out = "policy.bin", params;
  std::uint64_t seed = 0;
  bool seed_set = false;
  std::int64_t max_steps = 0;
  bool json = false;
};

// The part of `path` before its extension: "a/policy.bin" -> "a/policy".
std::string stem_of(const std::string& path) {
  const size_t slash = path.find_last_of('/'), dot = path.find_last_of('.');
  return dot != std::string::npos && (slash == std::string::npos || dot > slash) ? path.substr(0, dot) : path;
}

void run(const TrainOptions& o) {
  prep::Params params = o.params.empty() ? prep::Params{} : prep::load_params(o.params);
  if (o.seed_set) params.sarsa.seed = o.seed;
  if (o.max_steps > 0) params.sarsa.max_steps = o.max_steps;
  if (!prep::parse_role(o.target)) throw prep::InputError("--target", "unknown target motion '" + o.target + "'");
  const prep::MotionSet set = o.motions.empty() || o.motions == "builtin" ? prep::make_builtin_motion_set(params)
                                                                          : prep::load_motion_set(o.motions, params);
  // The table comes from the set's clips through the synthesis stride (Eq. 3-4) with this Params' root curve,
  // which is what the target's lower-body blend uses (Sec. 8: one controller per such curve).
  const prep::ActionTable table = prep::tabulate_action_effects(set, params);
  const prep::StateSpace states(params.quantization, table.motions);
  const prep::ActionSpace actions(table.motions, table.alpha_levels, prep::action_levels(params.quantization));
  const prep::Environment env(states, actions, table, params.reward);

  const bool bar = !o.json && ::isatty(STDERR_FILENO);
  prep::TrainingOptions topt;
  topt.curve_every_steps = 250000;  // a point every 250,000 steps: a smooth Fig. 10 for a few percent of time
  auto last_draw = std::chrono::steady_clock::now() - std::chrono::seconds(1);
  if (bar)
    topt.progress = [&](const prep::TrainingProgress& p) {
      const auto now = std::chrono::steady_clock::now();
      if (now - last_draw < std::chrono::milliseconds(100)) return;
      last_draw = now;
      const double f = std::min(1.0, static_cast<double>(p.steps) / static_cast<double>(p.max_steps));
      const int width = 40, filled = static_cast<int>(f * width);
      std::fprintf(stderr, "\r[%s%s] %5.1f%%  %lld steps  policy updates %lld (< %lld converges)",
                   std::string(static_cast<size_t>(filled), '#').c_str(),
                   std::string(static_cast<size_t>(width - filled), '.').c_str(), 100.0 * f,
                   static_cast<long long>(p.steps), static_cast<long long>(p.round_updates),
                   static_cast<long long>(p.update_limit));
      std::fflush(stderr);
    };
  const prep::TrainingResult r = prep::train_sarsa(env, params.sarsa, topt);
  if (bar) std::fprintf(stderr, "\n");

  const prep::Policy policy = prep::make_policy(params, table, actions, r, o.target);
  prep::save_policy(policy, o.out);

  const std::string stem = stem_of(o.out);
  std::ostringstream csv;
  csv << "steps,episodes,average_return_per_state\n";
  prep::PlotSeries curve;
  for (const prep::TrainingPoint& p : r.curve) {
    csv << p.steps << ',' << p.episodes << ',' << p.average_return << '\n';
    curve.x.push_back(static_cast<double>(p.steps) / 1e6);
    curve.y.push_back(p.average_return);
  }
  prep::write_file_atomic(stem + "-curve.csv", csv.str());
  prep::PlotOptions plot;
  plot.title = "Average return per state";
  plot.x_label = "training steps (millions)";
  plot.y_label = "average return per state";
  prep::write_line_plot_png(stem + "-curve.png", {curve}, plot);

  const double sps = r.seconds > 0 ? static_cast<double>(r.steps) / r.seconds : 0.0;
  if (o.json) {
    nlohmann::json j;
    j["states"] = states.size();
    j["actions"] = actions.size();
    j["steps"] = r.steps;
    j["episodes"] = r.episodes;
    j["seconds"] = r.seconds;
    j["steps_per_second"] = sps;
    // The machine is shared: CPU time says what the loop costs whatever else runs (per core).
    j["cpu_seconds"] = r.cpu_seconds;
    j["steps_per_cpu_second"] = r.cpu_seconds > 0 ? static_cast<double>(r.steps) / r.cpu_seconds : 0.0;
    j["converged"] = r.converged;
    j["threads"] = params.sarsa.threads;
    j["policy"] = o.out;
    j["curve_csv"] = stem + "-curve.csv";
    j["curve_png"] = stem + "-curve.png";
    j["final_average_return"] = r.curve.empty() ? 0.0 : r.curve.back().average_return;
    std::cout << j.dump(2) << "\n";
  } else {
    std::cout << "states " << states.size() << ", actions " << actions.size() << ", " << r.steps << " steps in "
              << r.episodes << " episodes, " << r.seconds << " s (" << sps / 1e6 << " M steps/s), "
              << (r.converged ? "converged" : "stopped at --max-steps without converging") << "\n"
              << "policy " << o.out << ", curve " << stem << "-curve.csv and " << stem << "-curve.png\n";
  }
}

prep::cli::RegisterCommand train_command(
    "train", "Train the behaviour controller (SARSA, Sec. 6) and write the policy and its training curve", 40,
    [](CLI::App& app) {
      auto o = std::make_shared<TrainOptions>();
      app.add_option("--motions", o->motions, "Motion set manifest (default: the built-in library)");
      app.add_option("--target", o->target, "Target motion the controller prepares for (a role, default kick)");
      app.add_option("--out", o->out, "Policy file to write (default policy.bin); the curve goes beside it");
      app.add_option_function<std::uint64_t>(
          "--seed", [o](const std::uint64_t& s) { o->seed = s, o->seed_set = true; }, "Random seed (default Params)");
      app.add_option("--max-steps", o->max_steps, "Stop after this many training steps (default Params)");
      app.add_flag("--json", o->json, "Print a JSON summary");
      app.add_option("--params", o->params, "Params JSON file (default: the built-in defaults)");
      app.callback([o] { run(*o); });
    });

}  // namespace
