// Sec. 5.1, movement style synthesis: per-joint blending weights (Eq. 1) and the blend of the locomotion
// pose toward the reference posture T_p (Eq. 2).
#pragma once

#include <glm/gtc/quaternion.hpp>
#include <cstdint>
#include <vector>

#include "engine/motion/body_map.h"
#include "engine/motion/pose.h"
#include "engine/motion/skeleton.h"
#include "engine/params/params.h"

namespace prep {

// The blending curve of every joint: C_i (shape) and c_i (scale) of Eq. 1, or one linear weight.
struct BlendCurves {
  std::vector<float> C;  // per joint
  std::vector<float> c;  // per joint
  bool linear = false;   // the traditional blend of Fig. 6 (top): w_i = alpha for every joint
  int root = 0;          // the root joint (its weight is w_r of Eq. 3-4)
  // The distinct (C_i, c_i) pairs and each joint's pair: most joints share one of two curves, so Eq. 1 is
  // evaluated once per curve rather than once per joint (same values).
  std::vector<float> curve_C, curve_c;
  std::vector<int> curve_of_joint;
  // Different for every set of curves make_blend_curves builds (a copy keeps it): weights computed from
  // these curves may be kept by it and reused for the same alpha.
  std::uint64_t id = 0;
};

// Defaults from BlendParams: upper-body joints (body.upper_body) take C_upper, every other joint (root,
// legs) C_lower; then C_override / c_override by joint name. Throws std::invalid_argument for an override
// naming no joint of the skeleton, a non-positive C_i, or an unknown method.
BlendCurves make_blend_curves(const Skeleton& skeleton, const BodyMap& body, const BlendParams& params);

// Eq. 1 for one joint; alpha is clamped to [0, 1].
float blend_weight(float alpha, float C, float c);

// Eq. 1 for every joint (or alpha everywhere for the linear method). `weights` must have one slot per joint.
void blend_weights(const BlendCurves& curves, float alpha, float* weights);

// Eq. 2 for one joint. The paper interpolates Euler angles linearly; we slerp quaternions on the shorter
// arc instead, which is the same blend without gimbal problems or order dependence (slerp_shorter in
// engine/motion/slerp.h). Exact at the ends: w <= 0 returns `from`, w >= 1 returns `to` bit for bit.
glm::quat blend_rotation(const glm::quat& from, const glm::quat& to, float w);

// Eq. 2 for every non-root joint: out.rotations[i] = blend(locomotion[i], reference[i], weights[i]).
// The root's rotation and position are the trajectory stage's (trajectory.h). `out` must be sized.
// Four joints at a time (SSE2).
void blend_joint_rotations(const Pose& locomotion, const Pose& reference, const float* weights, Pose& out);

}  // namespace prep
