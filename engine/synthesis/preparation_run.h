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
  std::vector<float> foot_slide;           // per frame: the largest move (m) of a heel or toe point the
                                           // foot stood on (pinned) in this frame and the previous one
};

// Runs seconds * fps + 1 frames. Throws std::invalid_argument for a clip index out of range or a reference
// pose on another skeleton.
PreparationRun run_preparation(const MotionSet& set, const Params& params, const PreparationRunOptions& options);

// The reference posture T_p of a target clip by the scan of Sec. 4.2: from T_t back toward T_0, the first
// frame whose COM lies inside its support polygon, whose contact pattern equals T_0's and whose leg joints
// (relative to the root, in its heading frame) are within reference.legs_threshold (sum of squared
// differences) of T_0's; T_0 if none qualifies. Returns the frame index. (The motion graph computes the
// same for its target nodes; this is for tools that run synthesis on a motion set without a graph.)
int scan_reference_frame(const MotionSet& set, const MotionClip& target, const Params& params);

}  // namespace prep
