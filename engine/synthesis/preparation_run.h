// Walking with preparation rising toward a target action: the locomotion clip looped seamlessly, alpha
// ramped over time, every frame through the Synthesizer. What `prep synth`, the synthesis tests and the
// benchmark run.
#pragma once

#include <vector>

#include "engine/motion/motion_set.h"
#include "engine/synthesis/synthesizer.h"

namespace prep {

// Plays a cyclic clip's loop range forever with continuous root motion: at each wrap the next cycle is
// moved and turned on the floor so that it continues from where the last one ended, with the last
// frame's step and turn. Frames are produced at the clip's frame rate.
class LocomotionLoop {
 public:
  explicit LocomotionLoop(const MotionClip& clip);
  // The next pose (world root position and rotation) and its contacts.
  void next(Pose& pose, FrameContacts& contacts);

 private:
  const MotionClip* clip_;
  int first_ = 0, last_ = 0, frame_ = 0;
  glm::quat turn_{1, 0, 0, 0};   // floor rotation applied to the current cycle
  glm::vec3 shift_{0.0f};        // floor translation applied after the rotation
};

struct PreparationRunOptions {
  int locomotion_clip = -1;  // index into the set (a cyclic clip)
  Pose reference;            // T_p
  float alpha_start = 0.0f;  // alpha ramps linearly from alpha_start ...
  float alpha_end = 1.0f;    // ... to alpha_end ...
  float seconds = 3.0f;      // ... over this time
};

struct PreparationRun {
  float fps = 30.0f;
  std::vector<Pose> frames;                // synthesized poses
  std::vector<Pose> locomotion;            // the locomotion input of each frame
  std::vector<FrameContacts> contacts;     // the locomotion's contacts (kept by the synthesized motion)
  std::vector<SynthesisReport> reports;
};

// Runs seconds * fps + 1 frames. Throws std::invalid_argument for a clip index out of range or a reference
// pose on another skeleton.
PreparationRun run_preparation(const MotionSet& set, const Params& params, const PreparationRunOptions& options);

}  // namespace prep
