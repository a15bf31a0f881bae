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
  // While the foot is flat (heel and toe planted) the toe joint keeps the bend it had when the foot became
  // flat: blending keeps turning it (fastest near alpha = 1, where Eq. 1's curves are steepest), and a toe
  // joint that bends under a flat foot would drag the planted toe tip along the floor.
  bool toe_held = false;
  glm::quat toe_local{1.0f, 0.0f, 0.0f, 0.0f};
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
                    glm::vec3 target, const glm::quat& foot_world, glm::vec3 forward,
                    glm::vec3 body_shift = glm::vec3(0.0f));

// Which contact points of each foot are pinned this frame. The contact detector flags a heel or toe as in
// contact while it is near the floor and slow, so during a step both are often flagged while the foot
// rolls: heel strike (the toe still coming down), heel-off (the heel already rising about the toe). Pinning
// both then would stretch the leg against the roll. So a flagged point is pinned if it is the slower of the
// two in the locomotion, or if both are nearly still (below ik.pivot_speed: a flat foot, both pinned). The
// foot then stays where it was planted and rolls about the point it stands on, as in the locomotion.
// Speeds are the locomotion's heel and toe speeds (m/s).
FrameContacts select_pinned_points(const FrameContacts& contacts, const std::array<float, 2>& heel_speed,
                                   const std::array<float, 2>& toe_speed, const IkParams& params);

// The foot IK stage for one frame: updates the plants from the pinned points (select_pinned_points), solves both legs and
// writes the hip, knee and ankle rotations of `pose`. `world_positions` / `world_rotations` are the pose's
// forward kinematics on entry (stale on return). dt is the frame time in seconds.
// When a planted foot is out of the leg's soft reach, the pelvis is lowered just enough (root_drop, per
// character state, recovering at ik.drop_recovery_speed, at most ik.max_root_drop): the foot stays planted
// and the knee bends instead of snapping straight or the foot sliding.
void apply_foot_ik(const Skeleton& skeleton, const BodyMap& body, const IkParams& params,
                   const FrameContacts& pinned, float dt, Pose& pose, const std::vector<glm::vec3>& world_positions,
                   const std::vector<glm::quat>& world_rotations, FootPlants& plants, float& root_drop);

// The floor, last of all. A pose whose ankle joint is below the floor (y = 0) is lifted until it is not
// (a cross-fade from a crawl on its knees into a walk sweeps the feet through it). Then a toe tip below
// the floor (the blend, the trajectory or a leg solved for a planted heel) is pitched back up to it about
// the ankle, the foot turning about its lateral axis as it rolls onto its heel, the ankle joint and
// everything above it untouched. `world_positions` / `world_rotations` are the pose's forward kinematics
// (stale on return when anything changed). Returns the feet turned.
int keep_toes_above_floor(const Skeleton& skeleton, const BodyMap& body, Pose& pose,
                          const std::vector<glm::vec3>& world_positions, const std::vector<glm::quat>& world_rotations);

}  // namespace prep
