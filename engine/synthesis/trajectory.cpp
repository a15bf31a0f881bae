#include "engine/synthesis/trajectory.h"

#include <cmath>

#include "engine/motion/kinematics.h"
#include "engine/synthesis/blending.h"

namespace prep {

glm::vec2 advance_root(glm::vec2 previous_root_xz, glm::vec3 locomotion_displacement, float w_root) {
  const float keep = 1.0f - w_root;
  return {previous_root_xz.x + keep * locomotion_displacement.x,   // Eq. 3
          previous_root_xz.y + keep * locomotion_displacement.z};  // Eq. 4
}

float adjust_root_height(float locomotion_root_y, float foot_dy_left, float foot_dy_right) {
  return locomotion_root_y - 0.5f * (foot_dy_left + foot_dy_right);  // Eq. 5
}

float height_relative_to_root(const Skeleton& skeleton, const Pose& pose, int joint) {
  // Walk up from the joint: a point p in joint j's frame is offset_j + R_j * p in its parent's frame.
  // Chains are short (hip, knee, ankle), so this is a few quaternion rotations rather than a
  // whole-skeleton pass. The joint's own origin starts as p = 0.
#if defined(__SSE2__)
  using namespace kinematics_detail;  // the same register arithmetic as forward kinematics
  __m128 p = _mm_setzero_ps();
  int j = joint;
  while (j > 0) {
    const Joint& J = skeleton.joints[static_cast<size_t>(j)];
    p = _mm_add_ps(load_vec3(J.offset), rotate(load_quat(pose.rotations[static_cast<size_t>(j)]), p));
    j = J.parent;
  }
  glm::vec3 result;
  store_vec3(result, rotate(load_quat(pose.rotations[0]), p));
  return result.y;
#else
  glm::vec3 p(0.0f);
  int j = joint;
  while (j > 0) {
    const Joint& J = skeleton.joints[static_cast<size_t>(j)];
    p = J.offset + pose.rotations[static_cast<size_t>(j)] * p;
    j = J.parent;
  }
  return (pose.rotations[0] * p).y;
#endif
}

void foot_height_changes(const Skeleton& skeleton, const BodyMap& body, const Pose& locomotion, const Pose& blended,
                         float& dy_left, float& dy_right) {
#if defined(__SSE2__)
  // Each ankle's height relative to the root in the blended pose minus the locomotion's
  // (height_relative_to_root of each, the same arithmetic), the two legs' chains walked up side by side
  // while both have joints left: four independent chains of rotations in flight.
  using namespace kinematics_detail;
  const Joint* const joints = skeleton.joints.data();
  const glm::quat* const b_rot = blended.rotations.data();
  const glm::quat* const l_rot = locomotion.rotations.data();
  __m128 b[2] = {_mm_setzero_ps(), _mm_setzero_ps()}, l[2] = {_mm_setzero_ps(), _mm_setzero_ps()};
  int j[2] = {body.legs[kLeft].ankle, body.legs[kRight].ankle};
  const auto up_one = [&](int side) {
    const Joint& J = joints[static_cast<size_t>(j[side])];
    const __m128 offset = load_vec3(J.offset);
    b[side] = _mm_add_ps(offset, rotate(load_quat(b_rot[static_cast<size_t>(j[side])]), b[side]));
    l[side] = _mm_add_ps(offset, rotate(load_quat(l_rot[static_cast<size_t>(j[side])]), l[side]));
    j[side] = J.parent;
  };
  while (j[0] > 0 && j[1] > 0) {
    up_one(0);
    up_one(1);
  }
  for (int side : {0, 1})
    while (j[side] > 0) up_one(side);
  float dy[2];
  for (int side : {0, 1}) {
    glm::vec3 bv, lv;
    store_vec3(bv, rotate(load_quat(b_rot[0]), b[side]));
    store_vec3(lv, rotate(load_quat(l_rot[0]), l[side]));
    dy[side] = bv.y - lv.y;
  }
  dy_left = dy[0];
  dy_right = dy[1];
#else
  dy_left = height_relative_to_root(skeleton, blended, body.legs[kLeft].ankle) -
            height_relative_to_root(skeleton, locomotion, body.legs[kLeft].ankle);
  dy_right = height_relative_to_root(skeleton, blended, body.legs[kRight].ankle) -
             height_relative_to_root(skeleton, locomotion, body.legs[kRight].ankle);
#endif
}

glm::quat heading_rotation(float heading) { return glm::angleAxis(heading, glm::vec3(0.0f, 1.0f, 0.0f)); }

glm::quat heading_rotation_of(const glm::quat& root_rotation) {
  // The turn about +Y taking +Z to the root's forward on the floor, (sin h, cos h) = (f.x, f.z) / |f|: the
  // half-angle quaternion normalize(1 + cos h, sin h * Y), which heading_rotation(heading_of(root)) gives
  // through an atan2 and a sine and cosine.
  const glm::vec3 forward = root_rotation * glm::vec3(0.0f, 0.0f, 1.0f);
  const float length = std::sqrt(forward.x * forward.x + forward.z * forward.z);
  if (!(length > 1e-6f)) return glm::quat(1.0f, 0.0f, 0.0f, 0.0f);  // facing straight up or down: heading_of's atan2(0, 0)
  const float c = forward.z / length, s = forward.x / length;
  if (1.0f + c < 1e-6f) return glm::quat(0.0f, 0.0f, 1.0f, 0.0f);  // facing -Z: a half turn
  return glm::normalize(glm::quat(1.0f + c, 0.0f, s, 0.0f));
}

glm::quat blend_root_rotation(const glm::quat& locomotion_root, const glm::quat& reference_root, float w_root) {
  if (w_root <= 0.0f) return locomotion_root;  // exactly the locomotion at alpha = 0
  const glm::quat loco_heading = heading_rotation_of(locomotion_root);
  const glm::quat loco_tilt = glm::conjugate(loco_heading) * locomotion_root;
  const glm::quat ref_tilt = glm::conjugate(heading_rotation_of(reference_root)) * reference_root;
  return glm::normalize(loco_heading * blend_rotation(loco_tilt, ref_tilt, w_root));  // Eq. 2 on the root
}

}  // namespace prep
