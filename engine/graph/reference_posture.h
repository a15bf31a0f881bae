// Sec. 4.2: the reference posture T_p of a target motion, the single posture that carries the style of
// its preparation. From the user-marked first frame of the target movement T_t the clip is scanned back
// toward its first frame T_0; T_p is the first frame where (1) the centre of mass projects inside the
// support polygon, (2) the foot contact pattern equals T_0's and (3) the sum of squared differences of
// the leg joint positions to T_0's is under ReferenceParams::legs_threshold. If none qualifies, T_0.
#pragma once

#include <vector>

#include "engine/motion/motion_set.h"
#include "engine/params/params.h"

namespace prep {

struct ReferencePosture {
  int clip = -1;              // index into MotionSet::clips
  int t_t = -1;               // T_t (clip frames)
  int frame = 0;              // T_p (clip frames); 0 = T_0 when no frame qualified
  bool found = false;         // a frame met all three conditions (else frame = T_0)
  // The conditions as they hold at `frame` (all true when found; at T_0 conditions 2 and 3 hold trivially).
  bool com_in_support = false;
  bool same_contacts = false;
  bool legs_close = false;
  float legs_distance = 0.0f;  // sum of squared leg joint position differences to T_0 (m^2)
};

// Leg joint positions (hip, knee, ankle and toe tip of both legs) of a frame in the character's floor
// frame: horizontally relative to the root, rotated so that the root's heading is +Z; heights as they are.
std::vector<glm::vec3> leg_positions(const MotionSet& set, const Pose& pose);
// Condition 2: the same feet are on the floor (a foot counts as down with its heel or its toe; comparing
// heel and toe separately would tell apart phases of one stance that the paper's "contact foot pattern"
// does not).
bool same_feet_down(const FrameContacts& a, const FrameContacts& b);
// Sum of squared differences of two such sets (condition 3).
float legs_distance(const std::vector<glm::vec3>& a, const std::vector<glm::vec3>& b);
// Condition 1 at one frame of a clip (uses the clip's stored contacts).
bool com_in_support(const MotionSet& set, const MotionClip& clip, int frame, const ContactParams& params);

ReferencePosture find_reference_posture(const MotionSet& set, int clip, const Params& params);
// T_p of every target motion of the set, in clip order.
std::vector<ReferencePosture> find_reference_postures(const MotionSet& set, const Params& params);

}  // namespace prep
