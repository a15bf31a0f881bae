// Loop ranges for cyclic locomotion: the pair of frames [first, last] over one or two gait cycles whose
// poses join best, so that playing last then first shows no jump.
#pragma once

#include <vector>

#include <glm/vec3.hpp>

#include "engine/motion/body_map.h"
#include "engine/motion/clip.h"
#include "engine/scan/motion_signals.h"

namespace prep {

// Every joint's position in the frame of the hips' heading (motion_signals.h), about the root's ground
// point: what the eye compares between two poses, wherever and whichever way the body is going.
class HeadingFramePoses {
 public:
  HeadingFramePoses(const Clip& clip, const MotionSignals& signals);

  // The pose distance of a loop join: the mean joint distance (cm) between frames a+k and b+k for
  // k = -1, 0, 1 (so velocities must match too), plus the difference of the root's ground velocity over
  // 0.1 s in the heading frame, counted as one more joint. a-1 and b+1 are clamped to the clip.
  float join_error_cm(int a, int b) const;
  // The same for one pair of frames.
  float distance_cm(int a, int b) const;

 private:
  int joints_ = 0;
  int frames_ = 0;
  std::vector<glm::vec3> points_;  // frames_ x (joints_ + 1): the last is the root's velocity term
};

// The gait cycle (two footsteps) in frames: the median interval between touchdowns of the same foot in
// [first, last]; -1 when the feet do not step there (fewer than three touchdowns in all).
int gait_cycle_frames(const MotionSignals& signals, int first, int last);

struct LoopRange {
  int first = -1;
  int last = -1;
  float error_cm = 0.0f;        // join_error_cm(last, first)
  float typical_cm = 0.0f;      // the median join error of the loops searched: what an arbitrary pick gives
  bool found() const { return first >= 0; }
  // How much better the join is than an arbitrary one: 1 at a perfect join, 0 at half the typical error.
  float confidence() const;
};

// The best join among loops of min_length..max_length frames within [first, last], both ends on frames
// where the body moves at its usual speed there (ground speed, smoothed over a gait cycle, within 20% of
// the range's median; every frame for a body standing still).
LoopRange find_loop(const HeadingFramePoses& poses, const MotionSignals& signals, int first, int last, int min_length,
                    int max_length);

}  // namespace prep
