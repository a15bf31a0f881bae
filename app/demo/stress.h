// A stress run of the demo (--stress SECONDS): on every frame one tunable of the Params set to a new value
// through the session, as the panels do (every 3 s one that may retrain the controller or rebuild the
// motion graph, on the other frames one the world takes live); every few seconds another scenario opened
// from the picker's list; launches at random; and,
// half-way, a broken Params file loaded the Preparation panel's way, whose message must name the file while
// the Params in force stay as they were.
#pragma once

#include <cstdint>
#include <string>

#include <nlohmann/json.hpp>

#include "engine/control/random.h"

namespace prep::demo {

class DemoApp;

struct StressReport {
  int frames = 0;
  int params_changes = 0;      // applied
  int params_refused = 0;      // a value the Params loader refused: nothing applied
  int reloading_changes = 0;   // changes that retrain the controller or rebuild the motion graph
  int scenario_switches = 0;
  int launches_asked = 0;
  int launches_started = 0;
  std::string broken_file;     // the broken Params file loaded
  std::string broken_message;  // what the demo said about it (the panel's message line)
  bool broken_named = false;   // the message names the file
  bool old_values_kept = false;  // the Params in force before and after the broken load are the same
  bool ok() const { return broken_named && old_values_kept && frames > 0; }
};

class StressScript {
 public:
  static constexpr double kScenarioEvery = 5.0;  // s between scenario switches
  static constexpr float kLaunchChance = 0.05f;  // per frame
  static constexpr double kAnyTunableEvery = 3.0;  // s between changes that may retrain or reload

  // `broken_params`: where the broken Params file is written (it is removed again at the end).
  StressScript(std::uint64_t seed, double seconds, std::string broken_params);
  ~StressScript();

  // Before each frame, `elapsed` seconds of wall time into the run.
  void before_frame(DemoApp& app, double elapsed);
  bool done(double elapsed) const { return elapsed >= seconds_; }
  const StressReport& report() const { return report_; }
  std::string summary() const;  // one line

 private:
  void change_tunable(DemoApp& app, bool any);
  void load_broken(DemoApp& app);

  Rng rng_;
  double seconds_;
  std::string broken_path_;
  nlohmann::json defaults_;
  double next_switch_ = kScenarioEvery;
  double next_any_ = kAnyTunableEvery;
  bool broken_done_ = false;
  StressReport report_;
};

}  // namespace prep::demo
