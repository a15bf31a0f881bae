// Measured speed: the figures `prep bench` prints. Each function runs one measurement and returns
// what it measured; nothing here asserts a target (timings on a shared machine are noisy; the figures are
// reported, see README).
//
// - SARSA: training steps per second of engine/control/sarsa.h on a motion set's environment (wall clock and
//   CPU time, all threads).
// - Synthesis: microseconds per character-frame of Synthesizer::step (blend, trajectory, foot IK, balance),
//   with and without the balance optimizer, over a crowd of characters walking at alpha in [0.3, 1] (where
//   the optimizer runs, Sec. 5.3), each with its own SynthesisState, one thread.
// - Crowd: N characters, each with its controller and full synthesis at 60 Hz, ms per frame over both cores.
//   A crowd of independent worlds, one character each (its own ball as goal and source of influence), not
//   one world of N characters: World::step steps its characters one after another and they interact (an
//   opponent's source is the user, the user's the closest opponent), so it cannot be split between threads
//   without changing what it does, while independent worlds split cleanly: the worlds are cut into runs,
//   each taken by whichever thread is free next, and the frame ends when every run is done. Each
//   character's state is its own World's (a few kilobytes; reported per character from the resident
//   memory before and after the crowd is built).
// - Graph build time, start-up to the first synthesized frame, peak memory (getrusage).
// Wall-clock figures on a shared machine count other processes' work too, so the synthesis and crowd
// figures also come as CPU time (per thread, or per frame and core).
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "engine/motion/motion_set.h"
#include "engine/params/params.h"
#include "engine/world/world.h"

namespace prep {

struct SarsaBenchmark {
  int states = 0, actions = 0, threads = 0;
  std::int64_t steps = 0;
  double seconds = 0, cpu_seconds = 0;
  double steps_per_second = 0;      // wall clock
  double steps_per_cpu_second = 0;  // per core
  bool converged = false;
};
// Trains from scratch on the set's core locomotion with `params` (the paper's configuration by default)
// for max_steps steps (to the end of that round; the convergence test is off, so the work is fixed).
SarsaBenchmark benchmark_sarsa(const MotionSet& set, const Params& params, std::int64_t max_steps);

struct SynthesisBenchmark {
  std::string set;
  int joints = 0;
  bool balance = false;
  int characters = 0, frames = 0;
  double us_per_character_frame = 0;      // wall clock
  double cpu_us_per_character_frame = 0;  // the thread's CPU time: what the machine's load does not inflate
  double balanced_fraction = 0;   // character-frames in which the optimizer ran
  double mean_balance_steps = 0;  // gradient steps per optimized frame
};
// `characters` characters each play the set's walk (through the motion graph, phases spread over the
// loop) for `frames` frames at 60 Hz, alpha varying smoothly in [0.3, 1] per character, toward the T_p of
// the set's first target motion. Throws InputError naming the set when it has no cyclic walk or no target.
SynthesisBenchmark benchmark_synthesis(const MotionSet& set, const Params& params, bool balance, int characters,
                                       int frames);

// The least-squares line y = a + b x through the points (x[i], y[i]); a flat line through the mean of y
// when the x do not vary (or there are none: a = b = 0).
struct LineFit {
  double a = 0, b = 0;
};
LineFit fit_line(const std::vector<double>& x, const std::vector<double>& y);

struct CrowdBenchmark {
  int characters = 0, threads = 0, frames = 0;
  double ms_per_frame = 0;            // mean wall clock per frame
  double median_ms_per_frame = 0;     // the frame-time distribution: median, 99th percentile (nearest rank)
  double p99_ms_per_frame = 0;
  double max_ms_per_frame = 0;        // the slowest frame
  // Frames in which the machine stopped a thread (host_pauses.h): a run of worlds took over kPauseMs,
  // where runs take a millisecond or less. The slowest frame without one, and the longest run of all.
  int paused_frames = 0;
  double max_unpaused_ms_per_frame = 0;
  double longest_run_ms = 0;
  // The process' CPU time per frame over all threads, divided by the threads: the frame time the cores
  // would give if nothing else ran on them (on a shared machine the wall clock also counts others' work).
  double cpu_ms_per_frame = 0;
  double synthesized_fraction = 0;    // character-frames that went through Synthesizer::step
  double balanced_fraction = 0;       // ... in which the balance optimizer ran (alpha >= 0.3)
  // Where the slow frames come from: a frame costs more the more of its characters the optimizer runs for,
  // and that share grows as the crowd closes in on its balls (from about a tenth to nine tenths over the
  // default 600 frames). The share in the slowest frame, and the least-squares line of frame time against
  // the share, read at no character and at every character balancing: the second is what a frame costs
  // once the whole crowd prepares.
  double worst_frame_balanced_fraction = 0;
  double fit_ms_none_balanced = 0, fit_ms_all_balanced = 0;
  double kb_per_character = 0;        // resident memory added per character when the crowd was built
  double entry_fill_ms = 0;           // fill_entry_frames before the first frame (once per graph: 0 after)
  double huge_page_mb = 0;            // memory on 2 MB pages once the crowd was built (huge_pages.h)
  double huge_page_ms = 0;            // the time the kernel took to move the heap onto them
};
// N worlds made from `scenario` (one user character; its objects kept), each character placed at a
// random start (seeded) within 2 m of the scenario's start, facing a random direction, its first object
// (the ball) and its goal moved to a random spot 4-8 m away; launches off, so that every frame is
// synthesized: the characters turn, approach and prepare. Steps them `frames` frames after `warmup`.
CrowdBenchmark benchmark_crowd(const Scenario& scenario, std::shared_ptr<const WorldAssets> assets, int characters,
                               int threads, int frames, int warmup, std::uint64_t seed);

double benchmark_graph_build_ms(const MotionSet& set, const Params& params, int repeats);  // the fastest

struct StartupBenchmark {
  double ms = 0;                 // load the scenario's motions, build the graph, T_p, synthesizer, policy, world, one tick
  bool policy_trained = false;   // true when the policy was not in the cache and was trained meanwhile
};
StartupBenchmark benchmark_startup(const std::string& scenario_file, const std::string& cache_dir);

double peak_memory_mb();     // getrusage: the process' peak resident set
double resident_memory_mb(); // /proc/self/statm now (0 where unavailable)

}  // namespace prep
