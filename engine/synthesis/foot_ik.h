// Sec. 5.2 (end): foot inverse kinematics. A foot point (heel or toe) that is in contact in the locomotion
// stays where it was planted for its whole contact phase.
//
// The paper solves this with particle-based IK after Jakobsen. We use an analytic two-bone solver per leg
// (hip-knee-ankle, the knee bending in the plane it already bends in): it is exact where the target is
// reachable, needs no iterations and no tuning of stiffness or iteration counts, costs a handful of
// quaternion operations per leg, and leaves every other joint untouched, so the upper body that blending
// and the balance optimizer shape is not disturbed.
#pragma once

#include <array>
#include <glm/gtc/quaternion.hpp>
#include <glm/vec3.hpp>
#include <vector>

#include "engine/motion/body_map.h"
#include "engine/motion/contacts.h"
#include "engine/motion/pose.h"
#include "engine/motion/skeleton.h"
#include "engine/params/params.h"

namespace prep {

// Per-foot, per-character IK state (plain data, no heap).
struct FootPlant {
  bool heel_planted = false;
  bool toe_planted = false;
  glm::vec3 heel_anchor{0.0f};  // world position where the heel (ankle joint) was planted
  glm::vec3 toe_anchor{0.0f};   // world position where the toe tip was planted
  glm::vec3 offset{0.0f};       // last IK correction of the ankle (solved - unsolved), faded out after lift-off
  float fade = 0.0f;            // 1 while planted, falls to 0 over ik.release_s after lift-off
};
using FootPlants = std::array<FootPlant, 2>;  // [kLeft], [kRight]

// Solves one hip-knee-ankle chain so that the ankle reaches `target` and the foot's world rotation becomes
// `foot_world`. `world_positions` / `world_rotations` are the pose's forward kinematics before the solve
// (they are not updated). The knee bends in its current plane (the pole is the knee's own direction; a
// straight leg bends toward `forward`). The reach is softened (IkParams::knee_soft_start): beyond the larger
// of soft_start x leg length and the leg's current extension, the reach approaches reach_limit x leg
// length asymptotically, so the knee never snaps straight. Returns the ankle position reached.
glm::vec3 solve_leg(const Skeleton& skeleton, const LegChain& leg, const IkParams& params, Pose& pose,
                    const std::vector<glm::vec3>& world_positions, const std::vector<glm::quat>& world_rotations,
                    glm::vec3 target, const glm::quat& foot_world, glm::vec3 forward);

// The foot IK stage for one frame: updates the plants from the locomotion's contacts, solves both legs and
// writes the hip, knee and ankle rotations of `pose`. `world_positions` / `world_rotations` are the pose's
// forward kinematics on entry (stale on return). dt is the frame time in seconds.
void apply_foot_ik(const Skeleton& skeleton, const BodyMap& body, const IkParams& params,
                   const FrameContacts& contacts, float dt, Pose& pose, const std::vector<glm::vec3>& world_positions,
                   const std::vector<glm::quat>& world_rotations, FootPlants& plants);

}  // namespace prep
