// The demo's engine side (no GL): one scenario's World run at its fixed time step, with everything around
// it that must never freeze a frame -- loading the motions, training the controller's policy in the
// background (engine/world/policy_cache.h PolicyJob) and swapping it in, live Params -- and the snapshots
// that let rendering interpolate poses between the last two ticks. The renderer reads scene(); nothing
// here draws, and nothing that draws drives the world but through the intent calls below.
//
// Choices (the paper leaves them open):
// - Fixed step with an accumulator: each frame adds its wall time (times time_scale) and runs whole ticks
//   of RuntimeParams::fixed_dt, at most kMaxTicksPerFrame (a slower frame's extra time is dropped: the
//   simulation slows down rather than piling up ticks, no spiral); the rest carries over. The drawn poses are interpolated between the
//   previous and the last tick by the remainder (accumulator / fixed_dt), so they lag the engine by at
//   most one tick (1/60 s) and move smoothly at any frame rate.
// - A Params change applies at once (World::set_params). When it changes policy_params_hash (a lower-body
//   C_i, the blend method, a reward radius ...), the policy for the new Params is loaded from the cache or
//   trained in the background, kRetrainDelay after the last change (a slider drag is one change, not a
//   training per pixel); a job for Params no longer wanted is cancelled. Until the new policy arrives the
//   old one keeps playing.
// - Intent given before the world exists (goal moved, object picked, auto toggled while loading or
//   training) is kept and applied when it starts.
#pragma once

#include <deque>
#include <functional>
#include <future>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "app/render/scene.h"
#include "engine/params/params.h"
#include "engine/world/key_player.h"
#include "engine/world/policy_cache.h"
#include "engine/world/world.h"

namespace prep::demo {

// A scenario file the picker offers.
struct ScenarioEntry {
  std::string name;  // the scenario's name
  std::string path;
  std::string description;
};
// The scenarios in a folder: every *.json that parses as a scenario (a Params file such as
// controller.json beside them is left out), sorted by name.
std::vector<ScenarioEntry> list_scenarios(const std::string& folder);
std::string default_scenarios_dir();   // <repository>/assets/scenarios
std::string default_scenario_path();   // ... /obstacles.json
std::string default_crowd_scenario_path();  // ... /stadium.json (one lane of the crowd demo)

enum class SessionPhase {
  Empty,     // nothing opened
  Loading,   // motions, motion graph, T_p (background)
  Training,  // the controller's policy: from the cache or trained (background)
  Running,   // the world runs
  Failed,    // loading or first training failed (error())
};
const char* phase_name(SessionPhase phase);

struct SessionOptions {
  std::string cache_dir;   // policy cache; "" = default_policy_cache_dir()
  bool background = true;  // false: open() blocks until the world runs (headless runs)
  // Blocking mode: called about 10 times a second while the policy loads or trains.
  std::function<void(const std::string& status, float progress)> on_progress;
};

// The user character at one tick, for the plots.
struct TickSample {
  float time = 0.0f;
  float alpha = 0.0f;       // the Gaussian-smoothed level synthesis used
  float com_height = 0.0f;  // m
  float com_offset = 0.0f;  // m: the COM's floor projection to the support polygon's centre (0 in flight)
  bool com_inside = false;
};

class WorldSession {
 public:
  static constexpr int kMaxTicksPerFrame = 6;      // 0.1 s of simulation per frame at most
  static constexpr double kRetrainDelay = 0.5;     // s of wall time after the last policy-relevant change
  static constexpr size_t kSampleHistory = 600;    // ticks kept for the plots (10 s at 60 Hz)
  static constexpr float kSteerLead = prep::kSteerLead;  // m the steered goal leads (engine/world/key_player.h)

  explicit WorldSession(SessionOptions options = {});
  ~WorldSession();
  WorldSession(const WorldSession&) = delete;
  WorldSession& operator=(const WorldSession&) = delete;

  // Opens a scenario file with its Params (its "params" file, or `params` when given). The scene shows its
  // objects and goal at once; the motions and the policy follow (in the background unless blocking). When
  // the motions and the Params are those already loaded, the world starts at once. Throws InputError for
  // a bad scenario or Params file (and then keeps what was open); in blocking mode also when the motions
  // or the training fail.
  void open(const std::string& path, std::optional<Params> params = std::nullopt);
  // The same scenario from its start (same motions and policy, the Params as they are now).
  void restart();

  // Advances by dt seconds of wall time: polls the background work, then runs the world's ticks (none
  // when paused). Returns the ticks run.
  int advance(double dt);
  // One tick now (stepping while paused).
  void step_once();

  SessionPhase phase() const { return phase_; }
  std::string status() const;   // one line for the panels
  float progress() const;       // 0..1 of the current background job (1 when none)
  const std::string& error() const { return error_; }
  const std::string& notice() const { return notice_; }  // the last non-fatal problem (a retraining that failed)

  const Scenario& scenario() const { return scenario_; }
  const std::string& scenario_path() const { return path_; }
  World* world() { return world_.get(); }
  const World* world() const { return world_.get(); }
  const WorldAssets* assets() const { return assets_.get(); }

  // The scene to draw: poses interpolated between the last two ticks (or the preview while loading).
  render::Scene scene(bool balance_overlay) const;
  float blend() const;  // the interpolation factor in [0, 1)

  const Params& params() const { return params_; }
  void set_params(const Params& params);
  // The policy playing was trained for other Params (a new one is on its way).
  bool policy_stale() const;
  bool retraining() const { return job_ != nullptr && world_ != nullptr; }

  // Intent. launch(): the user's character starts the target motion now (false when it cannot: already in
  // one, or the set has no clip for it, or the world is not running). launch_prepared(): the action of the
  // current source of influence.
  bool launch(TargetAction action);
  bool launch_prepared();
  std::optional<TargetAction> prepared_action() const;  // the action the user's source calls for
  void set_goal(glm::vec2 goal);
  glm::vec2 goal() const;  // the user's current goal (the last one set once reached)
  // Steering, as in a game (the demo's W A S D held): while a direction on the floor is given (any
  // length; zero: none), before every tick the user's goal is placed kSteerLead ahead of the user's
  // character in that direction, so the character walks that way at its own pace, turning as the
  // direction turns. steer({0, 0}) lets go: the goal stays where it was last placed, close ahead, and the
  // character walks there and stops. Given before the world runs, it applies once it does.
  void steer(glm::vec2 direction);
  glm::vec2 steering() const { return steer_; }  // unit, or zero
  // Picking an object makes it the source of influence and sets the goal where acting on it leads: a
  // ball is the goal itself (Sec. 7.2's kick); an obstacle, 2 m beyond it along the approach; an opponent
  // is faced (the goal on it).
  void pick_object(int object);
  void set_auto(bool on);
  bool auto_launch() const;

  bool paused = false;
  float time_scale = 1.0f;

  const std::deque<TickSample>& samples() const { return samples_; }
  // Summed over the ticks of the last advance().
  const World::StageTimes& stage_times() const { return stage_times_; }
  int ticks_last_advance() const { return ticks_last_advance_; }

 private:
  struct Snapshot {
    std::vector<Pose> poses;
    std::vector<glm::vec3> objects;
  };
  struct Retired;

  void poll();
  void start_loading();
  void start_policy_job();
  void on_policy(std::shared_ptr<const Policy> policy);
  void start_world();
  void tick();
  Snapshot capture() const;
  void retire_job();
  std::uint64_t wanted_hash() const { return policy_params_hash(params_); }
  void wait_blocking();

  SessionOptions options_;
  std::string path_;
  Scenario scenario_;
  Params params_;
  SessionPhase phase_ = SessionPhase::Empty;
  std::string error_, notice_;

  std::future<std::shared_ptr<WorldAssets>> loading_;
  std::shared_ptr<const WorldAssets> assets_;  // with the policy playing once there is one
  std::unique_ptr<PolicyJob> job_;
  std::uint64_t job_hash_ = 0;
  double retrain_at_ = -1.0;  // wall-clock second (session clock) to start the wanted job; < 0: none pending
  double clock_ = 0.0;        // wall time seen by advance()
  std::vector<std::unique_ptr<Retired>> retired_;

  std::unique_ptr<World> world_;
  double accumulator_ = 0.0;
  Snapshot previous_, current_;
  mutable std::vector<Pose> blended_;

  // Intent kept for the world (and before it exists).
  std::vector<glm::vec2> pending_goal_;  // non-empty: set when the world starts
  int pending_pick_ = -1;
  std::optional<bool> auto_override_;
  glm::vec2 last_goal_{0.0f};
  glm::vec2 steer_{0.0f};

  std::deque<TickSample> samples_;
  World::StageTimes stage_times_;
  int ticks_last_advance_ = 0;
};

}  // namespace prep::demo
