// A crowd of prepared characters (the crowd demo, prep-demo --crowd N): N lanes side by side on a grid,
// each a copy of one scenario moved aside and each its own World, so the characters of different lanes
// never meet and the lanes step in parallel on the machine's cores (frame_workers.h). Every lane plays
// unattended (launches on). When a lane's run is done (World::done) for kLaneRest, or has lasted
// kLaneTimeout, the lane starts over from a start moved a little along and across the lane and turned a
// little: the lanes drift apart in phase, and every character keeps preparing for something.
#pragma once

#include <cstdint>
#include <memory>
#include <random>
#include <vector>

#include <glm/vec2.hpp>

#include "engine/world/frame_workers.h"
#include "engine/world/scenario.h"
#include "engine/world/world.h"

namespace prep {

struct CrowdOptions {
  int lanes = 200;
  int threads = 2;
  std::uint64_t seed = 1;
  float start_jitter = 1.0f;    // m: each start moves up to this far along the lane, and half of it across
  float heading_jitter = 0.3f;  // radians: ... and turns up to this far
};

// The motion graph's phase-matched entries (MotionGraph::best_entry_frame) from every clip frame into
// every core motion, found ahead on the workers' threads: a crowd meets thousands of them in its first
// seconds, and each costs 0.2 ms (built-in library) on the frame it is first met.
void fill_entry_frames(const WorldAssets& assets, FrameWorkers& workers);

class Crowd {
 public:
  static constexpr float kLaneRest = 1.0f;      // s a lane stays done before it starts over
  static constexpr float kLaneTimeout = 45.0f;  // s after which a lane starts over in any case
  static constexpr float kLaneMargin = 1.5f;    // m between the contents of neighbouring lanes
  // Lane i takes its first decision (i mod kDecisionPhases) ticks late (World::hold_decisions), so the
  // lanes' decisions, which come one action apart, are spread over that many ticks instead of one.
  static constexpr int kDecisionPhases = 16;

  // Throws InputError for a scenario without a user character or lanes < 1.
  Crowd(const Scenario& lane, std::shared_ptr<const WorldAssets> assets, const CrowdOptions& options);
  Crowd(const Crowd&) = delete;
  Crowd& operator=(const Crowd&) = delete;

  void step();  // one fixed tick of every lane (both cores), then the restarts
  int lanes() const { return static_cast<int>(worlds_.size()); }
  const World& lane(int i) const { return *worlds_[static_cast<size_t>(i)]; }
  glm::vec2 lane_origin(int i) const { return origins_[static_cast<size_t>(i)]; }
  // The rectangle the lanes cover on the floor (x, z): from `low` to `high`.
  glm::vec2 low() const { return low_; }
  glm::vec2 high() const { return high_; }
  int restarts() const { return restarts_; }
  float time() const { return time_; }

 private:
  std::unique_ptr<World> make_lane(int i);

  Scenario scenario_;
  std::shared_ptr<const WorldAssets> assets_;
  CrowdOptions options_;
  std::vector<std::unique_ptr<World>> worlds_;
  std::vector<glm::vec2> origins_;
  std::vector<float> started_, done_for_;
  std::vector<std::mt19937_64> random_;
  glm::vec2 low_{0.0f}, high_{0.0f};
  FrameWorkers workers_;
  std::function<void(size_t, size_t, int)> step_lanes_;
  int restarts_ = 0;
  float time_ = 0.0f;
};

}  // namespace prep
