#include "engine/world/benchmark.h"

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <functional>
#include <numeric>
#include <random>

#include "engine/control/action_effects.h"
#include "engine/control/environment.h"
#include "engine/control/sarsa.h"
#include "engine/graph/motion_graph.h"
#include "engine/synthesis/preparation_run.h"
#include "engine/synthesis/synthesizer.h"
#include "engine/util/error.h"
#include "engine/util/huge_pages.h"
#include "engine/world/crowd.h"
#include "engine/world/floor.h"
#include "engine/world/frame_workers.h"
#include "engine/world/host_pauses.h"
#include "engine/world/policy_cache.h"

namespace prep {

namespace {

using Clock = std::chrono::steady_clock;
double ms_since(Clock::time_point t0) { return std::chrono::duration<double, std::milli>(Clock::now() - t0).count(); }

double cpu_ms(clockid_t clock) {
  timespec t{};
  clock_gettime(clock, &t);
  return 1e3 * static_cast<double>(t.tv_sec) + 1e-6 * static_cast<double>(t.tv_nsec);
}

using floor_plane::kPi;


std::string set_source_name(const MotionSet& set) { return set.manifest_path.empty() ? set.name : set.manifest_path; }

}  // namespace

SarsaBenchmark benchmark_sarsa(const MotionSet& set, const Params& params, std::int64_t max_steps) {
  const ActionTable table = tabulate_action_effects(set, params);
  const StateSpace states(params.quantization, table.motions);
  const ActionSpace actions(table.motions, table.alpha_levels, action_levels(params.quantization));
  const Environment env(states, actions, table, params.reward);
  SarsaParams sp = params.sarsa;
  sp.max_steps = max_steps;
  sp.convergence_fraction = 0.0f;  // a fixed amount of work: convergence (after ~9 M steps here) would cut it short
  TrainingOptions options;
  options.curve_every_steps = max_steps;  // the curve costs a scan of the table per point: keep it out
  const TrainingResult r = train_sarsa(env, sp, options);
  SarsaBenchmark b;
  b.states = states.size();
  b.actions = actions.size();
  b.threads = sp.threads;
  b.steps = r.steps;
  b.seconds = r.seconds;
  b.cpu_seconds = r.cpu_seconds;
  b.steps_per_second = r.seconds > 0 ? static_cast<double>(r.steps) / r.seconds : 0.0;
  b.steps_per_cpu_second = r.cpu_seconds > 0 ? static_cast<double>(r.steps) / r.cpu_seconds : 0.0;
  b.converged = r.converged;
  return b;
}

SynthesisBenchmark benchmark_synthesis(const MotionSet& set, const Params& base, bool balance, int characters, int frames) {
  Params params = base;
  params.balance.enabled = balance;
  const int walk = find_cyclic_clip(set, Role::Walk);
  if (walk < 0) throw InputError(set_source_name(set), "benchmark: the set has no cyclic walk clip");
  int target = -1;
  for (size_t i = 0; i < set.clips.size() && target < 0; ++i)
    if (set.clips[i].target_frame >= 0) target = static_cast<int>(i);
  if (target < 0) throw InputError(set_source_name(set), "benchmark: the set has no target motion");
  const MotionClip& tc = set.clips[static_cast<size_t>(target)];
  const Pose reference = tc.clip.frames[static_cast<size_t>(scan_reference_frame(set, tc, params))];

  // The walk at 60 Hz (every k-th frame of a faster clip), long enough for every phase offset.
  const MotionClip& wc = set.clips[static_cast<size_t>(walk)];
  const int every = std::max(1, static_cast<int>(std::lround(wc.clip.fps / 60.0f)));
  const float dt = static_cast<float>(every) / wc.clip.fps;
  const int loop = std::max(1, (wc.loop_last - wc.loop_first + 1) / every);
  LocomotionLoop source(wc);
  std::vector<Pose> poses;
  std::vector<FrameContacts> contacts;
  Pose p;
  FrameContacts fc{};
  for (int f = 0; f < (frames + loop) * every; ++f) {
    source.next(p, fc);
    if (f % every == 0) poses.push_back(p), contacts.push_back(fc);
  }

  const Synthesizer synth(set, params);
  SynthesisScratch scratch = synth.make_scratch();
  std::vector<int> phase(static_cast<size_t>(characters));
  for (int c = 0; c < characters; ++c) phase[static_cast<size_t>(c)] = (c * 7) % loop;
  long optimized = 0, steps = 0;
  // Every character from its first frame. Timed without a report (a diagnostic the pose does not need);
  // the optimizer's figures come from a second, untimed run of the same frames that asks for one.
  std::vector<SynthesisState> states(static_cast<size_t>(characters));
  std::vector<Pose> out(static_cast<size_t>(characters), synth.make_pose());
  const auto run = [&](bool with_report) {
    SynthesisReport report;
    for (int f = 0; f < frames; ++f)
      for (int c = 0; c < characters; ++c) {
        const size_t k = static_cast<size_t>(f + phase[static_cast<size_t>(c)]);
        SynthesisInput in;
        in.locomotion = &poses[k];
        in.contacts = contacts[k];
        in.reference = &reference;
        // alpha in [0.3, 1]: 0.65 + 0.35 sin, a 4 s period, each character at its own phase.
        in.alpha = 0.65f + 0.35f * std::sin(2.0f * kPi * (static_cast<float>(f) * dt / 4.0f + 0.618f * static_cast<float>(c)));
        in.dt = dt;
        if (!states[static_cast<size_t>(c)].started) {
          in.has_displacement = true;
          in.displacement = poses[k + 1].root_position - poses[k].root_position;
        }
        synth.step(in, states[static_cast<size_t>(c)], scratch, out[static_cast<size_t>(c)],
                   with_report ? &report : nullptr);
        if (with_report) optimized += report.balanced, steps += report.balance_steps;
      }
  };
  const auto t0 = Clock::now();
  const double cpu0 = cpu_ms(CLOCK_THREAD_CPUTIME_ID);
  run(false);
  const double ms = ms_since(t0), cpu = cpu_ms(CLOCK_THREAD_CPUTIME_ID) - cpu0;
  std::fill(states.begin(), states.end(), SynthesisState{});
  std::fill(out.begin(), out.end(), synth.make_pose());
  run(true);
  SynthesisBenchmark b;
  b.set = set.name;
  b.joints = set.skeleton->size();
  b.balance = balance;
  b.characters = characters;
  b.frames = frames;
  const double n = static_cast<double>(characters) * frames;
  b.us_per_character_frame = 1000.0 * ms / n;
  b.cpu_us_per_character_frame = 1000.0 * cpu / n;
  b.balanced_fraction = static_cast<double>(optimized) / n;
  b.mean_balance_steps = optimized > 0 ? static_cast<double>(steps) / static_cast<double>(optimized) : 0.0;
  return b;
}

LineFit fit_line(const std::vector<double>& x, const std::vector<double>& y) {
  const size_t n = std::min(x.size(), y.size());
  if (n == 0) return {};
  double mean_x = 0, mean_y = 0;
  for (size_t i = 0; i < n; ++i) mean_x += x[i], mean_y += y[i];
  mean_x /= static_cast<double>(n);
  mean_y /= static_cast<double>(n);
  double sxx = 0, sxy = 0;
  for (size_t i = 0; i < n; ++i) {
    sxx += (x[i] - mean_x) * (x[i] - mean_x);
    sxy += (x[i] - mean_x) * (y[i] - mean_y);
  }
  LineFit fit;
  fit.b = sxx > 0 ? sxy / sxx : 0.0;
  fit.a = mean_y - fit.b * mean_x;
  return fit;
}

CrowdBenchmark benchmark_crowd(const Scenario& scenario, std::shared_ptr<const WorldAssets> assets, int characters,
                               int threads, int frames, int warmup, std::uint64_t seed) {
  threads = std::max(1, std::min(threads, characters));
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  const double rss_before = resident_memory_mb();
  std::vector<std::unique_ptr<World>> worlds;
  worlds.reserve(static_cast<size_t>(characters));
  const int user = scenario.user();
  for (int k = 0; k < characters; ++k) {
    Scenario s = scenario;
    ScenarioCharacter& c = s.characters[static_cast<size_t>(user)];
    // One draw per statement: a constructor's arguments are unsequenced, and compilers differ in the order
    // they evaluate them (the same seed must give the same crowd everywhere).
    const float dz = 4.0f * unit(rng) - 2.0f;
    const float dx = 4.0f * unit(rng) - 2.0f;
    c.position += glm::vec2(dx, dz);
    c.heading = 2.0f * kPi * unit(rng);
    const float angle = 2.0f * kPi * unit(rng), distance = 4.0f + 4.0f * unit(rng);
    const glm::vec2 spot = c.position + distance * glm::vec2(std::sin(angle), std::cos(angle));
    if (!s.objects.empty()) s.objects[0].position = spot;
    s.goal.assign(1, spot);
    worlds.push_back(std::make_unique<World>(s, assets));
    // Unattended but always synthesizing: no launches (a target clip plays recorded frames, no synthesis).
    worlds.back()->set_auto(false);
    worlds.back()->set_stage_timing(false);  // as a crowd's worlds: no clock reads per character,
    worlds.back()->set_alpha_history(false);  // no alpha history,
    worlds.back()->set_balance_view(false);   // no COM and support polygon for panels,
    // and their decisions spread over ticks as a crowd's are.
    worlds.back()->hold_decisions(k % Crowd::kDecisionPhases);
  }
  const double rss_after = resident_memory_mb();
  // The worlds' heap on 2 MB pages (huge_pages.h), as Crowd does once its lanes are built.
  const auto huge_start = Clock::now();
  back_heap_with_huge_pages();
  const double huge_ms = ms_since(huge_start);

  FrameWorkers workers(threads);
  const auto fill_start = Clock::now();
  fill_entry_frames(*assets, workers);
  const double fill_ms = ms_since(fill_start);
  std::vector<long> synthesized(static_cast<size_t>(threads), 0), balanced(static_cast<size_t>(threads), 0);
  const size_t chunk = FrameWorkers::chunk_for(worlds.size(), threads);
  // Each run's wall time, per thread, this frame (host_pauses.h: a paused run tells a frame the machine
  // stopped from one whose work was slow). Room for every run of a frame: nothing is allocated while timing.
  std::vector<std::vector<double>> run_ms(static_cast<size_t>(threads));
  for (auto& r : run_ms) r.reserve(worlds.size() / chunk + 1);
  auto step_block = [&](size_t lo, size_t hi, int block, bool count) {
    const auto run_start = Clock::now();
    long run_synthesized = 0, run_balanced = 0;  // summed here, so the threads' counters (neighbours in
    for (size_t i = lo; i < hi; ++i) {           // memory) are written once per run, not per world
      prefetch_ahead(worlds, i, hi);
      worlds[i]->step();
      if (count)
        for (const WorldCharacter& c : worlds[i]->characters()) {
          run_synthesized += !c.in_target;
          run_balanced += !c.in_target && c.balanced;
        }
    }
    synthesized[static_cast<size_t>(block)] += run_synthesized;
    balanced[static_cast<size_t>(block)] += run_balanced;
    if (count) run_ms[static_cast<size_t>(block)].push_back(ms_since(run_start));
  };
  const std::function<void(size_t, size_t, int)> step_uncounted = [&](size_t lo, size_t hi, int b) { step_block(lo, hi, b, false); };
  const std::function<void(size_t, size_t, int)> step_counted = [&](size_t lo, size_t hi, int b) { step_block(lo, hi, b, true); };
  for (int f = 0; f < warmup; ++f) workers.run_chunks(worlds.size(), chunk, step_uncounted);
  std::vector<double> frame_ms, frame_balanced;  // per frame: its time, the share of characters balanced
  frame_ms.reserve(static_cast<size_t>(std::max(frames, 0)));
  frame_balanced.reserve(static_cast<size_t>(std::max(frames, 0)));
  long balanced_so_far = 0;
  std::vector<double> frame_runs;  // one frame's runs, all threads
  frame_runs.reserve(worlds.size() / chunk + static_cast<size_t>(threads));
  CrowdBenchmark b;
  const double cpu0 = cpu_ms(CLOCK_PROCESS_CPUTIME_ID);
  for (int f = 0; f < frames; ++f) {
    const auto t0 = Clock::now();
    workers.run_chunks(worlds.size(), chunk, step_counted);
    frame_ms.push_back(ms_since(t0));
    frame_runs.clear();
    for (auto& r : run_ms) {
      frame_runs.insert(frame_runs.end(), r.begin(), r.end());
      r.clear();
    }
    const PauseCount paused = count_pauses(frame_runs);
    b.longest_run_ms = std::max(b.longest_run_ms, paused.longest_ms);
    if (paused.pauses > 0) ++b.paused_frames;
    else b.max_unpaused_ms_per_frame = std::max(b.max_unpaused_ms_per_frame, frame_ms.back());
    const long balanced_now = std::accumulate(balanced.begin(), balanced.end(), 0L);
    frame_balanced.push_back(static_cast<double>(balanced_now - balanced_so_far) / characters);
    balanced_so_far = balanced_now;
  }
  const LineFit fit = fit_line(frame_balanced, frame_ms);
  const size_t slowest = static_cast<size_t>(std::max_element(frame_ms.begin(), frame_ms.end()) - frame_ms.begin());
  const double total = std::accumulate(frame_ms.begin(), frame_ms.end(), 0.0);
  std::sort(frame_ms.begin(), frame_ms.end());
  // Nearest rank: the smallest frame time that at least q of the frames do not exceed.
  const auto quantile = [&](double q) {
    if (frame_ms.empty()) return 0.0;
    const size_t rank = static_cast<size_t>(std::ceil(q * static_cast<double>(frame_ms.size())));
    return frame_ms[std::clamp<size_t>(rank, 1, frame_ms.size()) - 1];
  };
  b.characters = characters;
  b.threads = threads;
  b.frames = frames;
  b.ms_per_frame = frames > 0 ? total / frames : 0.0;
  b.median_ms_per_frame = quantile(0.5);
  b.p99_ms_per_frame = quantile(0.99);
  b.max_ms_per_frame = frame_ms.empty() ? 0.0 : frame_ms.back();
  b.cpu_ms_per_frame = frames > 0 ? (cpu_ms(CLOCK_PROCESS_CPUTIME_ID) - cpu0) / frames / threads : 0.0;
  long all = 0, optimized = 0;
  for (size_t t = 0; t < synthesized.size(); ++t) all += synthesized[t], optimized += balanced[t];
  const double character_frames = static_cast<double>(characters) * frames;
  b.synthesized_fraction = frames > 0 ? static_cast<double>(all) / character_frames : 0.0;
  b.balanced_fraction = frames > 0 ? static_cast<double>(optimized) / character_frames : 0.0;
  b.worst_frame_balanced_fraction = frames > 0 ? frame_balanced[slowest] : 0.0;
  b.fit_ms_none_balanced = fit.a;
  b.fit_ms_all_balanced = fit.a + fit.b;
  b.entry_fill_ms = fill_ms;
  b.huge_page_mb = static_cast<double>(huge_page_kb()) / 1024.0;
  b.huge_page_ms = huge_ms;
  b.kb_per_character = characters > 0 ? 1024.0 * (rss_after - rss_before) / characters : 0.0;
  return b;
}

double benchmark_graph_build_ms(const MotionSet& set, const Params& params, int repeats) {
  double best = 1e300;
  for (int r = 0; r < std::max(1, repeats); ++r) {
    const auto t0 = Clock::now();
    const MotionGraph g = MotionGraph::build(set, params.graph);
    best = std::min(best, ms_since(t0));
    if (g.nodes().empty()) break;
  }
  return best;
}

StartupBenchmark benchmark_startup(const std::string& scenario_file, const std::string& cache_dir) {
  const auto t0 = Clock::now();
  const Scenario scenario = load_scenario(scenario_file);
  bool trained = false;
  const auto assets = prepare_world_assets(scenario, load_scenario_params(scenario), cache_dir, &trained);
  World world(scenario, assets);
  world.step();
  StartupBenchmark b;
  b.ms = ms_since(t0);
  b.policy_trained = trained;
  return b;
}

double peak_memory_mb() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return static_cast<double>(u.ru_maxrss) / 1024.0;  // Linux: kilobytes
}

double resident_memory_mb() {
  std::FILE* f = std::fopen("/proc/self/statm", "r");
  if (!f) return 0.0;
  long size = 0, resident = 0;
  const int n = std::fscanf(f, "%ld %ld", &size, &resident);
  std::fclose(f);
  return n == 2 ? static_cast<double>(resident) * static_cast<double>(sysconf(_SC_PAGESIZE)) / (1024.0 * 1024.0) : 0.0;
}

}  // namespace prep
