#include "engine/scan/loop_search.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/geometric.hpp>

#include "engine/motion/kinematics.h"

namespace prep {
namespace {

constexpr float kVelocitySpanSeconds = 0.1f;
constexpr float kSteadySpeedTolerance = 0.2f;  // a loop end's speed within 20% of the usual
constexpr float kStandingSpeed = 0.25f;        // m/s: below this the body is standing, every frame steady

glm::vec3 to_heading_frame(const glm::vec3& v, float heading) {
  const float c = std::cos(heading), s = std::sin(heading);
  // Undo a yaw of `heading` about +Y.
  return {c * v.x - s * v.z, v.y, s * v.x + c * v.z};
}

}  // namespace

HeadingFramePoses::HeadingFramePoses(const Clip& clip, const MotionSignals& signals)
    : joints_(clip.skeleton->size()), frames_(clip.frame_count()) {
  points_.resize(static_cast<size_t>(frames_) * static_cast<size_t>(joints_ + 1));
  const int span = std::max(1, static_cast<int>(std::lround(kVelocitySpanSeconds * clip.fps)));
  std::vector<glm::vec3> positions;
  for (int f = 0; f < frames_; ++f) {
    forward_kinematics(*clip.skeleton, clip.frames[static_cast<size_t>(f)], positions);
    const glm::vec3 root = signals.root[static_cast<size_t>(f)];
    const glm::vec3 ground(root.x, 0.0f, root.z);
    const float heading = signals.heading[static_cast<size_t>(f)];
    glm::vec3* out = &points_[static_cast<size_t>(f) * static_cast<size_t>(joints_ + 1)];
    for (int j = 0; j < joints_; ++j) out[j] = to_heading_frame(positions[static_cast<size_t>(j)] - ground, heading);
    const int a = std::max(0, f - span / 2), b = std::min(frames_ - 1, a + span);
    glm::vec3 moved = signals.root[static_cast<size_t>(b)] - signals.root[static_cast<size_t>(a)];
    moved.y = 0.0f;
    out[joints_] = b > a ? to_heading_frame(moved, heading) * (static_cast<float>(span) / static_cast<float>(b - a)) : glm::vec3(0.0f);
  }
}

float HeadingFramePoses::distance_cm(int a, int b) const {
  const glm::vec3* p = &points_[static_cast<size_t>(a) * static_cast<size_t>(joints_ + 1)];
  const glm::vec3* q = &points_[static_cast<size_t>(b) * static_cast<size_t>(joints_ + 1)];
  float sum = 0.0f;
  for (int j = 0; j <= joints_; ++j) sum += glm::length(p[j] - q[j]);
  return 100.0f * sum / static_cast<float>(joints_ + 1);
}

float HeadingFramePoses::join_error_cm(int a, int b) const {
  float sum = 0.0f;
  for (int k = -1; k <= 1; ++k)
    sum += distance_cm(std::clamp(a + k, 0, frames_ - 1), std::clamp(b + k, 0, frames_ - 1));
  return sum / 3.0f;
}

int gait_cycle_frames(const MotionSignals& signals, int first, int last) {
  std::vector<int> intervals;
  int touchdowns = 0;
  for (int side : {kLeft, kRight}) {
    int previous = -1;
    for (int f = std::max(first, 1); f <= last; ++f) {
      const bool down = signals.contacts[static_cast<size_t>(f)][static_cast<size_t>(side)].any();
      const bool was = signals.contacts[static_cast<size_t>(f - 1)][static_cast<size_t>(side)].any();
      if (!down || was) continue;
      ++touchdowns;
      if (previous >= 0) intervals.push_back(f - previous);
      previous = f;
    }
  }
  if (touchdowns < 3 || intervals.empty()) return -1;
  std::nth_element(intervals.begin(), intervals.begin() + static_cast<std::ptrdiff_t>(intervals.size() / 2), intervals.end());
  return intervals[intervals.size() / 2];
}

float LoopRange::confidence() const {
  if (!found() || !(typical_cm > 0.0f)) return 0.0f;
  return std::clamp(1.0f - 2.0f * error_cm / typical_cm, 0.0f, 1.0f);
}

LoopRange find_loop(const HeadingFramePoses& poses, const MotionSignals& signals, int first, int last, int min_length,
                    int max_length) {
  LoopRange best;
  if (last - first < min_length) return best;
  // Steady frames: the ground speed, smoothed over about a gait cycle, near the range's median.
  const int cycle = gait_cycle_frames(signals, first, last);
  const int half = std::max(1, (cycle > 0 ? cycle : signals.frames_in(1.0f)) / 2);
  const std::vector<float> speed = smoothed(signals.ground_speed, half);
  const float usual = median_of(speed, first, last);
  auto steady = [&](int f) {
    return usual < kStandingSpeed || std::abs(speed[static_cast<size_t>(f)] - usual) <= kSteadySpeedTolerance * usual;
  };
  float best_error = std::numeric_limits<float>::max();
  std::vector<float> errors;  // every candidate's, to judge the best one against
  for (int a = first; a <= last - min_length; ++a) {
    if (!steady(a)) continue;
    for (int b = a + min_length; b <= std::min(last, a + max_length); ++b) {
      if (!steady(b)) continue;
      const float e = poses.join_error_cm(b, a);
      errors.push_back(e);
      if (e < best_error) {
        best_error = e;
        best.first = a;
        best.last = b;
      }
    }
  }
  if (!best.found()) return best;
  best.error_cm = best_error;
  best.typical_cm = median_of(errors, 0, static_cast<int>(errors.size()) - 1);
  return best;
}

}  // namespace prep
