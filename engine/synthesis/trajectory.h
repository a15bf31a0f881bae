// Sec. 5.2, movement trajectory adjustment: the root's horizontal travel (Eq. 3-4), its height (Eq. 5) and
// its orientation (blended like the joints, Eq. 2, but relative to the locomotion's heading).
#pragma once

#include <glm/gtc/quaternion.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "engine/motion/body_map.h"
#include "engine/motion/pose.h"
#include "engine/motion/skeleton.h"

namespace prep {

// Eq. 3-4. The paper scales "the horizontal root displacement of the locomotion"; that is its displacement
// per frame (its velocity), not its absolute position, so the character keeps the locomotion's direction
// and slows down as w_r rises. Returns the new root (x, z): previous + (1 - w_r) * displacement.
glm::vec2 advance_root(glm::vec2 previous_root_xz, glm::vec3 locomotion_displacement, float w_root);

// Eq. 5: the root height of the locomotion lowered by the mean change, caused by blending, of the left and
// right feet's heights relative to the root (positive when blending raised a foot toward the root, as in a
// crouch, so the root drops and the feet stay on the floor).
float adjust_root_height(float locomotion_root_y, float foot_dy_left, float foot_dy_right);

// Height of a joint above the root (world y difference) for a pose with the given root rotation, by walking
// the joint's chain only (no full forward kinematics).
float height_relative_to_root(const Skeleton& skeleton, const Pose& pose, int joint);

// The feet's changes of height relative to the root between the locomotion and the blended pose: the
// Delta y_l and Delta y_r of Eq. 5 (ankle joints; both poses must carry their root rotations).
void foot_height_changes(const Skeleton& skeleton, const BodyMap& body, const Pose& locomotion, const Pose& blended,
                         float& dy_left, float& dy_right);

// The root orientation blend. "The root orientation is scaled in the same way as other joints" (Sec. 5.2),
// but T_p's heading belongs to the target clip, not to where the character walks. So each root rotation is
// split into its heading (yaw about +Y) and its tilt relative to that heading (pelvis pitch, roll and any
// yaw beyond the heading); the tilts are blended with w_r (Eq. 2) and the result keeps the locomotion's
// heading, so the character still goes where the locomotion goes.
glm::quat blend_root_rotation(const glm::quat& locomotion_root, const glm::quat& reference_root, float w_root);

// Yaw rotation about +Y by `heading` radians (a character at heading h faces (sin h, 0, cos h)).
glm::quat heading_rotation(float heading);
// heading_rotation(heading_of(root_rotation)), without trigonometry.
glm::quat heading_rotation_of(const glm::quat& root_rotation);

}  // namespace prep
