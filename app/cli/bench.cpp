// prep bench: the speed figures (engine/world/benchmark.h measures; this prints): SARSA steps per
// second, synthesis microseconds per character-frame with and without the balance optimizer (the built-in
// library and the 43-joint daz43 set), a crowd of 1 to 20,000 characters with controller and full synthesis
// at 60 Hz on both cores (with the machine's own pauses of a busy thread, timed before it), graph build time,
// start-up to the first synthesized frame, peak memory; then each
// aim (app/cli/bench_aims.h) with its figure and whether it was met.
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>
#include <vector>

#include "app/cli/bench_aims.h"
#include "app/cli/command.h"
#include "engine/library/builtin.h"
#include "engine/util/files.h"
#include "engine/world/benchmark.h"
#include "engine/world/host_pauses.h"
#include "engine/world/policy_cache.h"

namespace {

struct Options {
  bool json = false;
  std::vector<int> crowd{1, 10, 100, 1000, 4000, 8000, 12000, 20000};
  int frames = 600, warmup = 30, threads = 2;
  int synthesis_characters = 1000, synthesis_frames = 60;
  double pause_probe_seconds = 5.0;
  long long sarsa_steps = 20000000;
  std::string scenario = "assets/scenarios/kick.json";
  std::string cache;
};

std::string repo_path(const std::string& p) { return !p.empty() && p.front() == '/' ? p : prep::source_dir() + "/" + p; }

void run(const Options& o) {
  const std::string cache = o.cache.empty() ? prep::default_policy_cache_dir() : o.cache;
  auto say = [&](const std::string& s) {
    if (!o.json) std::cerr << s << std::flush;
  };
  nlohmann::json j;
  j["hardware_threads"] = std::thread::hardware_concurrency();

  // Start-up first, while nothing is loaded: motions, graph, T_p, synthesizer, cached policy, world, one tick.
  say("start-up ... ");
  const prep::StartupBenchmark start = prep::benchmark_startup(repo_path("assets/scenarios/obstacles.json"), cache);
  j["startup_ms"] = start.ms;
  j["startup_policy_trained"] = start.policy_trained;
  say(std::to_string(start.ms) + " ms\n");

  const prep::Params paper;  // the paper's configuration: 19,200 states
  const auto builtin = std::make_shared<const prep::MotionSet>(prep::make_builtin_motion_set(paper));
  std::vector<std::shared_ptr<const prep::MotionSet>> sets{builtin};
  for (const char* manifest : {"assets/manifests/daz43.json", "assets/manifests/cmu31.json"}) {
    try {
      sets.push_back(std::make_shared<const prep::MotionSet>(prep::load_motion_set(repo_path(manifest), paper)));
    } catch (const std::exception& e) {
      std::cerr << "prep bench: skipping " << manifest << ": " << e.what() << "\n";
    }
  }

  say("SARSA ... ");
  const prep::SarsaBenchmark sarsa = prep::benchmark_sarsa(*builtin, paper, o.sarsa_steps);
  j["sarsa"] = {{"states", sarsa.states},
                {"actions", sarsa.actions},
                {"threads", sarsa.threads},
                {"steps", sarsa.steps},
                {"seconds", sarsa.seconds},
                {"steps_per_second", sarsa.steps_per_second},
                {"steps_per_cpu_second", sarsa.steps_per_cpu_second},
                {"converged", sarsa.converged}};
  say(std::to_string(sarsa.steps_per_second / 1e6) + " M steps/s\n");

  j["synthesis"] = nlohmann::json::array();
  for (const auto& set : sets) {
    if (set->name == "cmu31") continue;  // the built-in and the 43-joint daz43 set are the reference points
    for (bool balance : {true, false}) {
      say("synthesis " + set->name + (balance ? " with" : " without") + " balance ... ");
      const prep::SynthesisBenchmark s =
          prep::benchmark_synthesis(*set, paper, balance, o.synthesis_characters, o.synthesis_frames);
      j["synthesis"].push_back({{"set", s.set},
                                {"joints", s.joints},
                                {"balance", s.balance},
                                {"characters", s.characters},
                                {"frames", s.frames},
                                {"us_per_character_frame", s.us_per_character_frame},
                                {"cpu_us_per_character_frame", s.cpu_us_per_character_frame},
                                {"balanced_fraction", s.balanced_fraction},
                                {"mean_balance_steps", s.mean_balance_steps}});
      say(std::to_string(s.us_per_character_frame) + " us\n");
    }
  }

  j["graph_build_ms"] = nlohmann::json::object();
  for (const auto& set : sets) j["graph_build_ms"][set->name] = prep::benchmark_graph_build_ms(*set, paper, 3);

  // The machine alone, on the crowd's threads, before the crowd: how often and how long it stops a busy
  // thread (host_pauses.h), to read the crowd's slowest frames against.
  if (o.pause_probe_seconds > 0.0) {
    say("pauses of the machine ... ");
    const prep::HostPauseProbe p = prep::probe_host_pauses(o.pause_probe_seconds, o.threads);
    j["host_pauses"] = {{"seconds", p.seconds},
                        {"threads", p.threads},
                        {"pieces", p.pieces},
                        {"median_piece_us", p.median_piece_us},
                        {"limit_ms", prep::kPauseMs},
                        {"pauses", p.paused.pauses},
                        {"longest_ms", p.paused.longest_ms},
                        {"paused_ms", p.paused.paused_ms},
                        {"stop_limit_ms", prep::kProbeStopMs},
                        {"stops", p.stopped.pauses},
                        {"stopped_ms", p.stopped.paused_ms}};
    char line[160];
    std::snprintf(line, sizeof line, "%d pauses over %.0f ms, %d stops over %.0f ms, the longest %.1f ms\n", p.paused.pauses,
                  prep::kPauseMs, p.stopped.pauses, prep::kProbeStopMs, p.paused.longest_ms);
    say(line);
  }

  const prep::Scenario scenario = prep::load_scenario(repo_path(o.scenario));
  const auto assets = prep::prepare_world_assets(scenario, prep::load_scenario_params(scenario), cache);
  j["crowd_scenario"] = scenario.name;
  j["crowd"] = nlohmann::json::array();
  for (int n : o.crowd) {
    say("crowd " + std::to_string(n) + " ... ");
    const prep::CrowdBenchmark c = prep::benchmark_crowd(scenario, assets, n, o.threads, o.frames, o.warmup, 1);
    j["crowd"].push_back({{"characters", c.characters},
                          {"threads", c.threads},
                          {"frames", c.frames},
                          {"ms_per_frame", c.ms_per_frame},
                          {"median_ms_per_frame", c.median_ms_per_frame},
                          {"p99_ms_per_frame", c.p99_ms_per_frame},
                          {"max_ms_per_frame", c.max_ms_per_frame},
                          {"paused_frames", c.paused_frames},
                          {"max_unpaused_ms_per_frame", c.max_unpaused_ms_per_frame},
                          {"longest_run_ms", c.longest_run_ms},
                          {"cpu_ms_per_frame", c.cpu_ms_per_frame},
                          {"us_per_character_frame", 1000.0 * c.ms_per_frame / c.characters},
                          {"synthesized_fraction", c.synthesized_fraction},
                          {"balanced_fraction", c.balanced_fraction},
                          {"worst_frame_balanced_fraction", c.worst_frame_balanced_fraction},
                          {"fit_ms_none_balanced", c.fit_ms_none_balanced},
                          {"fit_ms_all_balanced", c.fit_ms_all_balanced},
                          {"kb_per_character", c.kb_per_character},
                          {"entry_fill_ms", c.entry_fill_ms},
                          {"huge_page_mb", c.huge_page_mb},
                          {"huge_page_ms", c.huge_page_ms}});
    say(std::to_string(c.ms_per_frame) + " ms/frame\n");
  }
  j["peak_memory_mb"] = prep::peak_memory_mb();

  const std::vector<prep::cli::Aim> aims = prep::cli::aims_of(j);
  j["aims"] = nlohmann::json::array();
  for (const prep::cli::Aim& a : aims) j["aims"].push_back(a.to_json());
  if (o.json) {
    std::cout << j.dump(2) << "\n";
    return;
  }
  std::printf("\n| figure | value |\n|---|---|\n");
  std::printf("| SARSA (%d states x %d actions, %d threads, %lld steps) | %.1f M steps/s (%.1f M per CPU-second) |\n",
              sarsa.states, sarsa.actions, sarsa.threads, static_cast<long long>(sarsa.steps), sarsa.steps_per_second / 1e6,
              sarsa.steps_per_cpu_second / 1e6);
  for (const auto& s : j["synthesis"])
    std::printf("| synthesis, %s (%d joints), %s balance | %.2f us per character-frame (CPU %.2f) |\n",
                s["set"].get<std::string>().c_str(), s["joints"].get<int>(), s["balance"].get<bool>() ? "with" : "without",
                s["us_per_character_frame"].get<double>(), s["cpu_us_per_character_frame"].get<double>());
  for (const auto& c : j["crowd"]) {
    // Resident memory grows by pages and reuses what a smaller crowd freed: per character it reads true
    // only for large crowds.
    char memory[48] = "";
    if (c["characters"].get<int>() >= 1000) std::snprintf(memory, sizeof memory, "; %.0f KB each", c["kb_per_character"].get<double>());
    std::printf("| crowd of %d (controller + full synthesis, %d threads; balance ran in %.0f%% of frames) | %.2f ms per frame (CPU %.2f per core; median %.2f, 99th percentile %.2f, worst %.2f with %.0f%% balancing; %.2f with none and %.2f with all balancing, fitted; %.1f us per character%s) |\n",
                c["characters"].get<int>(), c["threads"].get<int>(), 100.0 * c["balanced_fraction"].get<double>(),
                c["ms_per_frame"].get<double>(), c["cpu_ms_per_frame"].get<double>(), c["median_ms_per_frame"].get<double>(),
                c["p99_ms_per_frame"].get<double>(), c["max_ms_per_frame"].get<double>(),
                100.0 * c["worst_frame_balanced_fraction"].get<double>(), c["fit_ms_none_balanced"].get<double>(),
                c["fit_ms_all_balanced"].get<double>(), c["us_per_character_frame"].get<double>(), memory);
  }
  for (const auto& c : j["crowd"]) {
    if (c["paused_frames"].get<int>() == 0) continue;
    std::printf("| crowd of %d: frames in which a run of worlds was paused (over %.0f ms) | %d of %d; the slowest frame without a pause %.2f ms |\n",
                c["characters"].get<int>(), prep::kPauseMs, c["paused_frames"].get<int>(), c["frames"].get<int>(),
                c["max_unpaused_ms_per_frame"].get<double>());
  }
  if (j.contains("host_pauses")) {
    const auto& p = j["host_pauses"];
    std::printf("| the machine alone: pauses of a busy thread over %.0f ms (%d threads, %.0f s, pieces of %.0f us) | %d, the longest %.1f ms |\n",
                p["limit_ms"].get<double>(), p["threads"].get<int>(), p["seconds"].get<double>(),
                p["median_piece_us"].get<double>(), p["pauses"].get<int>(), p["longest_ms"].get<double>());
    std::printf("| the machine alone: stops of a busy thread over %.0f ms, pauses included | %d, %.1f ms in all |\n",
                p["stop_limit_ms"].get<double>(), p["stops"].get<int>(), p["stopped_ms"].get<double>());
  }
  for (const auto& [name, ms] : j["graph_build_ms"].items())
    std::printf("| motion graph build, %s | %.1f ms |\n", name.c_str(), ms.get<double>());
  std::printf("| start-up to the first synthesized frame (obstacles, %s policy) | %.0f ms |\n",
              start.policy_trained ? "freshly trained" : "cached", start.ms);
  std::printf("| peak memory (getrusage) | %.0f MB |\n", j["peak_memory_mb"].get<double>());
  std::printf("\n| aim | measured | met |\n|---|---|---|\n");
  for (const prep::cli::Aim& a : aims) {
    if (a.measured) std::printf("| %s %s %g | %.4g | %s |\n", a.figure.c_str(), a.at_most ? "<=" : ">=", a.aim, a.value, a.met() ? "yes" : "no");
    else std::printf("| %s %s %g | not measured | |\n", a.figure.c_str(), a.at_most ? "<=" : ">=", a.aim);
  }
}

prep::cli::RegisterCommand bench_command(
    "bench",
    "Speed figures: SARSA steps/s, synthesis us per character-frame (with and without balance), a crowd of 1 to "
    "20,000 characters (ms per frame, both cores), graph build, start-up, peak memory",
    46, [](CLI::App& app) {
      auto o = std::make_shared<Options>();
      app.add_flag("--json", o->json, "Print one JSON object");
      app.add_option("--crowd", o->crowd, "Crowd sizes (comma-separated, default 1,10,100,1000,4000,8000,12000,20000)")->delimiter(',');
      app.add_option("--frames", o->frames, "Measured frames per crowd size (default 600 = 10 s)");
      app.add_option("--warmup", o->warmup, "Frames stepped before measuring (default 30)");
      app.add_option("--threads", o->threads, "Threads for the crowd (default 2)");
      app.add_option("--synthesis-characters", o->synthesis_characters, "Characters in the synthesis benchmark (default 1000)");
      app.add_option("--synthesis-frames", o->synthesis_frames, "Frames in the synthesis benchmark (default 60)");
      app.add_option("--pause-probe", o->pause_probe_seconds,
                     "Seconds of timing a fixed piece of arithmetic on the crowd's threads before the crowd, to "
                     "count the machine's own pauses of a busy thread (default 5; 0: none)");
      app.add_option("--sarsa-steps", o->sarsa_steps, "SARSA steps at most (default 20,000,000, the paper's)");
      app.add_option("--scenario", o->scenario, "Scenario the crowd is made from (default assets/scenarios/kick.json)");
      app.add_option("--policy-cache", o->cache, "Folder of cached policies (default: $PREP_CACHE_DIR or ~/.cache/prep)");
      app.callback([o] { run(*o); });
    });

}  // namespace
