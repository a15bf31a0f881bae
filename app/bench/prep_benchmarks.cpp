// prep-benchmarks (Google Benchmark): the cost of movement synthesis per character-frame (Sec. 5) on the
// built-in skeleton (22 joints) and the 43-joint daz43 CMU skeleton, the whole Synthesizer::step and each
// of its stages alone, forward kinematics alone, and the motion graph's construction (Sec. 4.1) for each
// library.
//
// What a character-frame is here: one call of Synthesizer::step for one character at the engine tick
// (Params::runtime.fixed_dt, 60 Hz), walking (the set's first cyclic walk) with alpha moving through
// [0.3, 1] (0.65 + 0.35 sin, a 4 s period, each character at its own phase), so the balance optimizer runs
// on every frame, toward the T_p of a target (built-in: duck; daz43: jump_forward_13_11). Each iteration
// advances kCharacters characters by one frame, each with its own SynthesisState; the counter
// "per_frame" is the time per character-frame.
//
// Stage benchmarks ("stage/..."): each iteration first runs the stages before the measured one for every
// character (not timed, each character with its own scratch so the measured stage finds its inputs), then
// times the measured stage over all of them (manual timing; one clock read per kCharacters calls).
//
// Run: build/prep-benchmarks [--benchmark_filter=REGEX] [--benchmark_repetitions=5
//      --benchmark_report_aggregates_only=true]. Timings on a shared machine are noisy: compare figures
// taken in one run, and count instructions with valgrind --tool=callgrind (see README).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "engine/graph/motion_graph.h"
#include "engine/library/builtin.h"
#include "engine/motion/kinematics.h"
#include "engine/motion/motion_set.h"
#include "engine/synthesis/preparation_run.h"
#include "engine/synthesis/synthesizer.h"

namespace {

using namespace prep;

constexpr int kCharacters = 16;
constexpr float kPi = 3.14159265358979f;

enum class Library { Builtin, Daz43, Cmu31 };

const MotionSet& motion_set(Library library) {
  static std::map<Library, std::unique_ptr<MotionSet>> sets;
  auto& slot = sets[library];
  if (!slot) {
    const Params params;
    const std::string root = PREP_SOURCE_DIR;
    switch (library) {
      case Library::Builtin: slot = std::make_unique<MotionSet>(make_builtin_motion_set(params)); break;
      case Library::Daz43: slot = std::make_unique<MotionSet>(load_motion_set(root + "/assets/manifests/daz43.json", params)); break;
      case Library::Cmu31: slot = std::make_unique<MotionSet>(load_motion_set(root + "/assets/manifests/cmu31.json", params)); break;
    }
  }
  return *slot;
}

// The walk stream at the engine tick and everything a character-frame needs.
struct Workload {
  const MotionSet* set = nullptr;
  Params params;
  Pose reference;
  std::vector<Pose> poses;
  std::vector<FrameContacts> contacts;
  float dt = 1.0f / 60.0f;
};

Workload make_workload(Library library, bool balance) {
  Workload w;
  w.set = &motion_set(library);
  w.params.balance.enabled = balance;
  const MotionSet& set = *w.set;
  const int target = set.find(library == Library::Builtin ? "duck" : "jump_forward_13_11");
  const int walk = find_cyclic_clip(set, Role::Walk);
  if (target < 0 || walk < 0) throw std::runtime_error("benchmark: the library lacks its walk or target clip");
  const MotionClip& tc = set.clips[static_cast<size_t>(target)];
  w.reference = tc.clip.frames[static_cast<size_t>(scan_reference_frame(set, tc, w.params))];
  const MotionClip& wc = set.clips[static_cast<size_t>(walk)];
  const int every = std::max(1, static_cast<int>(std::lround(wc.clip.fps * w.params.runtime.fixed_dt)));
  w.dt = static_cast<float>(every) / wc.clip.fps;
  LocomotionLoop loop(wc);
  Pose p;
  FrameContacts fc{};
  const int clip_frames = static_cast<int>(20.0f * wc.clip.fps);  // 20 s of walking
  for (int f = 0; f < clip_frames; ++f) {
    loop.next(p, fc);
    if (f % every == 0) w.poses.push_back(p), w.contacts.push_back(fc);
  }
  return w;
}

// One character walking through the workload.
struct Character {
  SynthesisState state;
  Pose out;
  int frame = 0;
  float phase = 0.0f;
};

SynthesisInput input_for(const Workload& w, const Character& c, int tick) {
  SynthesisInput in;
  const size_t k = static_cast<size_t>(c.frame) % (w.poses.size() - 1);
  in.locomotion = &w.poses[k];
  in.contacts = w.contacts[k];
  in.reference = &w.reference;
  in.alpha = 0.65f + 0.35f * std::sin(2.0f * kPi * (static_cast<float>(tick) * w.dt / 4.0f + c.phase));
  in.dt = w.dt;
  if (k == 0) {  // the stream restarts: give the step instead of letting it see a jump
    in.has_displacement = true;
    in.displacement = w.poses[1].root_position - w.poses[0].root_position;
  }
  return in;
}

std::vector<Character> make_characters(const Workload& w, const Synthesizer& synth) {
  std::vector<Character> cs(kCharacters);
  for (int i = 0; i < kCharacters; ++i) {
    cs[static_cast<size_t>(i)].out = synth.make_pose();
    cs[static_cast<size_t>(i)].frame = (i * 37) % static_cast<int>(w.poses.size() - 1);
    cs[static_cast<size_t>(i)].phase = 0.618f * static_cast<float>(i);
  }
  return cs;
}

// optimized and steps were counted over counted_ticks ticks of every character (default: the timed ones).
void set_counters(benchmark::State& state, long optimized, long steps, long counted_ticks = -1) {
  const double frames = static_cast<double>(state.iterations()) * kCharacters;
  state.counters["per_frame"] = benchmark::Counter(frames, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  if (optimized > 0) {
    const double counted = counted_ticks < 0 ? frames : static_cast<double>(counted_ticks) * kCharacters;
    state.counters["balanced"] = static_cast<double>(optimized) / counted;
    state.counters["steps"] = static_cast<double>(steps) / static_cast<double>(optimized);
  }
}

// The whole Synthesizer::step, one scratch shared by all characters (as in the World), without a report
// (a diagnostic the pose does not need). The optimizer's counters come from an untimed replay of the
// first ticks (at most 120) that asks for one.
void BM_SynthesisStep(benchmark::State& state, Library library, bool balance) {
  const Workload w = make_workload(library, balance);
  const Synthesizer synth(*w.set, w.params);
  SynthesisScratch scratch = synth.make_scratch();
  std::vector<Character> cs = make_characters(w, synth);
  int tick = 0;
  for (auto _ : state) {
    for (Character& c : cs) {
      synth.step(input_for(w, c, tick), c.state, scratch, c.out);
      ++c.frame;
    }
    ++tick;
    benchmark::DoNotOptimize(cs.front().out.rotations.data());
  }
  cs = make_characters(w, synth);
  SynthesisReport report;
  long optimized = 0, steps = 0;
  const int replayed = std::min(tick, 120);
  for (int replay = 0; replay < replayed; ++replay) {
    for (Character& c : cs) {
      synth.step(input_for(w, c, replay), c.state, scratch, c.out, &report);
      optimized += report.balanced;
      steps += report.balance_steps;
      ++c.frame;
    }
  }
  set_counters(state, optimized, steps, replayed);
  state.SetLabel(std::to_string(w.set->skeleton->size()) + " joints");
}

enum class Stage { Blend, Trajectory, Ik, Balance };

// Forward kinematics of the synthesized pose alone (every joint's world position and rotation), the pass
// the IK and floor stages run on the whole body.
void BM_ForwardKinematics(benchmark::State& state, Library library) {
  const Workload w = make_workload(library, true);
  const Synthesizer synth(*w.set, w.params);
  SynthesisScratch scratch = synth.make_scratch();
  std::vector<Character> cs = make_characters(w, synth);
  for (int tick = 0; tick < 30; ++tick) {  // poses with preparation and balance in them
    for (Character& c : cs) {
      synth.step(input_for(w, c, tick), c.state, scratch, c.out);
      ++c.frame;
    }
  }
  std::vector<std::vector<glm::vec3>> positions(cs.size());
  std::vector<std::vector<glm::quat>> rotations(cs.size());
  for (auto _ : state) {
    for (size_t i = 0; i < cs.size(); ++i) forward_kinematics(synth.skeleton(), cs[i].out, positions[i], &rotations[i]);
    benchmark::DoNotOptimize(positions.back().data());
  }
  set_counters(state, 0, 0);
  state.SetLabel(std::to_string(w.set->skeleton->size()) + " joints");
}

// One stage alone: the stages before it run untimed for every character, then the stage is timed.
void BM_SynthesisStage(benchmark::State& state, Library library, Stage stage) {
  const Workload w = make_workload(library, true);
  const Synthesizer synth(*w.set, w.params);
  std::vector<SynthesisScratch> scratch(kCharacters);
  for (auto& s : scratch) s = synth.make_scratch();
  std::vector<Character> cs = make_characters(w, synth);
  std::vector<SynthesisInput> inputs(kCharacters);
  SynthesisReport report;
  long optimized = 0, steps = 0;
  int tick = 0;
  using Clock = std::chrono::steady_clock;
  for (auto _ : state) {
    for (size_t i = 0; i < cs.size(); ++i) {
      Character& c = cs[i];
      inputs[i] = input_for(w, c, tick);
      if (stage > Stage::Blend) synth.stage_blend(inputs[i], scratch[i], c.out);
      if (stage > Stage::Trajectory) synth.stage_trajectory(inputs[i], c.state, scratch[i], c.out);
      if (stage > Stage::Ik) synth.stage_ik(inputs[i], c.state, scratch[i], c.out);
    }
    const auto t0 = Clock::now();
    for (size_t i = 0; i < cs.size(); ++i) {
      Character& c = cs[i];
      switch (stage) {
        case Stage::Blend: synth.stage_blend(inputs[i], scratch[i], c.out); break;
        case Stage::Trajectory: synth.stage_trajectory(inputs[i], c.state, scratch[i], c.out); break;
        case Stage::Ik: synth.stage_ik(inputs[i], c.state, scratch[i], c.out); break;
        case Stage::Balance: synth.stage_balance(inputs[i], c.state, scratch[i], c.out, &report); break;
      }
    }
    const auto t1 = Clock::now();
    state.SetIterationTime(std::chrono::duration<double>(t1 - t0).count());
    // Keep every character's stream going: the stages after the measured one, untimed.
    for (size_t i = 0; i < cs.size(); ++i) {
      Character& c = cs[i];
      if (stage < Stage::Trajectory) synth.stage_trajectory(inputs[i], c.state, scratch[i], c.out);
      if (stage < Stage::Ik) synth.stage_ik(inputs[i], c.state, scratch[i], c.out);
      if (stage < Stage::Balance) synth.stage_balance(inputs[i], c.state, scratch[i], c.out, &report);
      if (stage == Stage::Balance) optimized += report.balanced, steps += report.balance_steps;
      ++c.frame;
    }
    ++tick;
  }
  set_counters(state, optimized, steps);
}

void BM_GraphBuild(benchmark::State& state, Library library) {
  const MotionSet& set = motion_set(library);
  const Params params;
  for (auto _ : state) {
    MotionGraph graph = MotionGraph::build(set, params.graph);
    benchmark::DoNotOptimize(graph.build_seconds());
  }
  state.SetLabel(set.name + ", " + std::to_string(set.clips.size()) + " clips");
}

}  // namespace

BENCHMARK_CAPTURE(BM_SynthesisStep, daz43_full, Library::Daz43, true)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_SynthesisStep, daz43_no_balance, Library::Daz43, false)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_SynthesisStep, builtin_full, Library::Builtin, true)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_SynthesisStep, builtin_no_balance, Library::Builtin, false)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_SynthesisStage, daz43_blend, Library::Daz43, Stage::Blend)->UseManualTime()->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_SynthesisStage, daz43_trajectory, Library::Daz43, Stage::Trajectory)->UseManualTime()->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_SynthesisStage, daz43_ik, Library::Daz43, Stage::Ik)->UseManualTime()->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_SynthesisStage, daz43_balance, Library::Daz43, Stage::Balance)->UseManualTime()->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_SynthesisStage, builtin_blend, Library::Builtin, Stage::Blend)->UseManualTime()->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_SynthesisStage, builtin_trajectory, Library::Builtin, Stage::Trajectory)->UseManualTime()->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_SynthesisStage, builtin_ik, Library::Builtin, Stage::Ik)->UseManualTime()->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_SynthesisStage, builtin_balance, Library::Builtin, Stage::Balance)->UseManualTime()->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_ForwardKinematics, daz43, Library::Daz43)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_ForwardKinematics, builtin, Library::Builtin)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_GraphBuild, builtin, Library::Builtin)->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK_CAPTURE(BM_GraphBuild, daz43, Library::Daz43)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK_CAPTURE(BM_GraphBuild, cmu31, Library::Cmu31)->Unit(benchmark::kMillisecond)->Iterations(3);

BENCHMARK_MAIN();
