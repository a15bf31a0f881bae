// Milliseconds per stage of a frame and frames per second, averaged over recent frames.
#pragma once

#include <array>
#include <chrono>

namespace prep::demo {

enum Stage { kUpdate, kScene, kShadow, kMainPass, kPanels, kFinish, kStageCount };
const char* stage_name(int stage);

class Timings {
 public:
  // Exponential average over about `window` frames.
  explicit Timings(int window = 60) : smoothing_(1.0 / window) {}

  void add(int stage, double ms);
  void end_frame(double frame_ms);

  double average_ms(int stage) const { return average_[stage]; }
  double frame_ms() const { return frame_ms_; }
  double fps() const { return frame_ms_ > 0.0 ? 1000.0 / frame_ms_ : 0.0; }

 private:
  double smoothing_;
  std::array<double, kStageCount> average_{};
  std::array<bool, kStageCount> seen_{};
  double frame_ms_ = 0.0;
  bool frame_seen_ = false;
};

// An exponential average over about `window` samples (the first sample starts it).
class RunningAverage {
 public:
  explicit RunningAverage(int window = 60) : smoothing_(1.0 / window) {}
  void add(double x) {
    value_ = seen_ ? value_ + smoothing_ * (x - value_) : x;
    seen_ = true;
  }
  double value() const { return value_; }

 private:
  double smoothing_;
  double value_ = 0.0;
  bool seen_ = false;
};

using Clock = std::chrono::steady_clock;
inline double ms_since(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

}  // namespace prep::demo
