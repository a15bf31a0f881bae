// A clip: poses at a fixed frame rate on one skeleton.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "engine/motion/pose.h"
#include "engine/motion/skeleton.h"

namespace prep {

struct Clip {
  std::string name;
  std::shared_ptr<const Skeleton> skeleton;
  float fps = 30.0f;
  std::vector<Pose> frames;

  int frame_count() const { return static_cast<int>(frames.size()); }
  float duration() const { return frames.empty() ? 0.0f : (frame_count() - 1) / fps; }

  // Samples at time t in seconds (clamped to the clip), interpolating between the two nearest frames.
  void sample(float t, Pose& out) const;
  Pose sample(float t) const {
    Pose p;
    sample(t, p);
    return p;
  }
};

// Makes neighbouring frames' quaternions lie in the same hemisphere (q and -q are the same rotation), so
// that interpolation never takes the long way round. Mocap converted from Euler angles needs this.
void make_hemisphere_continuous(Clip& clip);

}  // namespace prep
