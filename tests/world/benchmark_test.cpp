// The benchmark functions measure what they say (timings themselves are reported, never asserted).
#include "engine/world/benchmark.h"

#include <doctest/doctest.h>

#include <chrono>
#include <memory>
#include <thread>

#include "engine/library/builtin.h"
#include "engine/world/host_pauses.h"
#include "engine/world/policy_cache.h"
#include "tests/support/paths.h"

using namespace prep;

TEST_CASE("the synthesis benchmark runs the balance optimizer only when asked, at alpha >= 0.3 throughout") {
  const MotionSet set = make_builtin_motion_set(Params{});
  const SynthesisBenchmark with = benchmark_synthesis(set, Params{}, true, 6, 40);
  const SynthesisBenchmark without = benchmark_synthesis(set, Params{}, false, 6, 40);
  CHECK(with.joints == set.skeleton->size());
  CHECK(with.characters == 6);
  CHECK(with.frames == 40);
  // Alpha stays in [0.3, 1]: the optimizer runs on every frame with a foot down (walking: all of them).
  CHECK(with.balanced_fraction > 0.95);
  CHECK(with.mean_balance_steps > 0.0);  // a frame already in balance may take no step
  CHECK(with.mean_balance_steps <= Params{}.balance.max_steps);
  CHECK(without.balanced_fraction == 0.0);
  CHECK(with.us_per_character_frame > 0.0);
}

TEST_CASE("the crowd benchmark steps every character of every world, all synthesized, on the threads asked") {
  const Scenario s = load_scenario(test::repo() + "/assets/scenarios/kick.json");
  const auto assets = prepare_world_assets(s, load_scenario_params(s), test::tmp_dir() + "/policy-cache");
  const CrowdBenchmark c = benchmark_crowd(s, assets, 5, 2, 20, 5, 3);
  CHECK(c.characters == 5);
  CHECK(c.threads == 2);
  CHECK(c.frames == 20);
  CHECK(c.synthesized_fraction == doctest::Approx(1.0));  // launches are off: nobody plays a target clip
  CHECK(c.ms_per_frame > 0.0);
  CHECK(c.max_ms_per_frame >= c.ms_per_frame);
  // The frame-time distribution is ordered: median <= 99th percentile <= worst.
  CHECK(c.median_ms_per_frame > 0.0);
  CHECK(c.median_ms_per_frame <= c.p99_ms_per_frame);
  CHECK(c.p99_ms_per_frame <= c.max_ms_per_frame);
  // The line of frame time against the share balancing passes through the means: read at the run's mean
  // share it gives the mean frame.
  CHECK(c.fit_ms_none_balanced + (c.fit_ms_all_balanced - c.fit_ms_none_balanced) * c.balanced_fraction ==
        doctest::Approx(c.ms_per_frame).epsilon(1e-9));
  // Frames with a paused run (host_pauses.h) are set apart; the slowest of the others is among all frames.
  CHECK(c.paused_frames >= 0);
  CHECK(c.paused_frames <= c.frames);
  CHECK(c.longest_run_ms > 0.0);
  CHECK(c.max_unpaused_ms_per_frame <= c.max_ms_per_frame);
  if (c.paused_frames == 0) CHECK(c.max_unpaused_ms_per_frame == c.max_ms_per_frame);
  CHECK(c.worst_frame_balanced_fraction >= 0.0);
  CHECK(c.worst_frame_balanced_fraction <= 1.0);
  CHECK(benchmark_crowd(s, assets, 1, 2, 3, 0, 3).threads == 1);  // never more threads than characters
}

TEST_CASE("the frame-time line is the least-squares fit, flat where the share does not vary") {
  // Points on y = 2 + 3 x come back exactly; noise symmetric about that line leaves it where it is.
  const LineFit exact = fit_line({0.0, 0.5, 1.0}, {2.0, 3.5, 5.0});
  CHECK(exact.a == doctest::Approx(2.0));
  CHECK(exact.b == doctest::Approx(3.0));
  const LineFit noisy = fit_line({0.0, 0.0, 1.0, 1.0}, {1.9, 2.1, 4.9, 5.1});
  CHECK(noisy.a == doctest::Approx(2.0));
  CHECK(noisy.b == doctest::Approx(3.0));
  const LineFit flat = fit_line({0.4, 0.4}, {1.0, 3.0});
  CHECK(flat.a == doctest::Approx(2.0));
  CHECK(flat.b == 0.0);
  const LineFit none = fit_line({}, {});
  CHECK(none.a == 0.0);
  CHECK(none.b == 0.0);
}

TEST_CASE("the SARSA benchmark trains the paper's 19,200 states for the steps asked") {
  const MotionSet set = make_builtin_motion_set(Params{});
  Params p;
  p.sarsa.convergence_episodes = 100;  // short rounds: the step limit is checked at the end of a round
  const SarsaBenchmark b = benchmark_sarsa(set, p, 20000);
  CHECK(b.states == 19200);
  CHECK(b.actions == 24);
  CHECK(b.steps >= 20000);
  CHECK(b.steps < 200000);
  CHECK(b.steps_per_second > 0.0);
}

TEST_CASE("peak and resident memory are read from the process") {
  CHECK(peak_memory_mb() > 1.0);
  CHECK(resident_memory_mb() > 1.0);
  CHECK(resident_memory_mb() <= peak_memory_mb() + 1.0);
}

TEST_CASE("a piece of work over the pause limit counts as a pause, and the probe finds a thread stopped mid-piece") {
  const PauseCount c = count_pauses({0.5, 25.0, 1.0, 100.0, 19.9}, 20.0);
  CHECK(c.pauses == 2);
  CHECK(c.longest_ms == 100.0);
  CHECK(c.paused_ms == doctest::Approx(125.0));
  CHECK(count_pauses({}, 20.0).pauses == 0);

  // A thread put to sleep inside one piece for twice the limit: the probe sees that piece as a pause,
  // while its other pieces take microseconds.
  const double stop_ms = 2.0 * kPauseMs;
  const HostPauseProbe p = probe_host_pauses(0.3, 2, [&](int thread, std::int64_t piece) {
    if (thread == 1 && piece == 5) std::this_thread::sleep_for(std::chrono::duration<double, std::milli>(stop_ms));
  });
  CHECK(p.threads == 2);
  CHECK(p.pieces > 100);
  CHECK(p.median_piece_us > 0.0);
  CHECK(p.median_piece_us < 1000.0);
  CHECK(p.paused.pauses >= 1);
  CHECK(p.paused.longest_ms >= stop_ms);
  CHECK(p.paused.paused_ms >= stop_ms);
  CHECK(p.stopped.pauses >= p.paused.pauses);  // every pause is a stop too
  CHECK(p.stopped.paused_ms >= p.paused.paused_ms);
}

TEST_CASE("the probe counts a stop of a few milliseconds, too short to be a pause") {
  // A thread put to sleep inside one piece for three milliseconds: over the probe's stop limit, while a
  // piece takes microseconds and a pause takes over twenty milliseconds.
  const double stop_ms = 3.0 * kProbeStopMs;
  static_assert(3.0 * kProbeStopMs < kPauseMs, "the stop is shorter than a pause");
  const HostPauseProbe p = probe_host_pauses(0.2, 2, [&](int thread, std::int64_t piece) {
    if (thread == 0 && piece == 7) std::this_thread::sleep_for(std::chrono::duration<double, std::milli>(stop_ms));
  });
  CHECK(p.median_piece_us < 1e3 * kProbeStopMs);
  CHECK(p.stopped.pauses >= 1);
  CHECK(p.stopped.longest_ms >= stop_ms);
  CHECK(p.stopped.paused_ms >= stop_ms);
}
