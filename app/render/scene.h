// What the renderer draws: a plain description that the application fills each frame (from a clip
// player now; from engine/world's state later). The renderer only reads it: it never drives the engine.
#pragma once

#include <glm/gtc/quaternion.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "engine/motion/pose.h"
#include "engine/motion/skeleton.h"

namespace prep::render {

// One posed character, already through forward kinematics. The world-space joint positions and rotations
// are also what a skinned body needs (joint matrices = world transform * inverse bind): a skinned glTF mesh
// draw is another pass over the same SceneCharacter, beside the capsule pass (Renderer::draw_capsule_bodies).
struct SceneCharacter {
  std::shared_ptr<const Skeleton> skeleton;
  std::vector<glm::vec3> joint_positions;  // world, one per joint
  std::vector<glm::quat> joint_rotations;  // world, one per joint
  glm::vec3 colour{0.0f};                  // palette::kCharacter for the player, kOtherCharacter for others
  bool is_source = false;                  // the source of influence (fight: the closest opponent)
  // The clearance view: capsules of this character's body (indices into BodyVolumes(*skeleton).capsules(),
  // engine/motion/body_volumes.h) drawn in palette::kClearance over the body; empty: none.
  std::vector<int> flagged;
  // Far from the camera (the crowd): drawn as a light body, its capsules with a few dozen triangles each,
  // never skinned.
  bool light = false;
};

// Runs forward kinematics for `pose` on `skeleton`.
SceneCharacter make_scene_character(std::shared_ptr<const Skeleton> skeleton, const Pose& pose, const glm::vec3& colour);

enum class ObjectType {
  Ball,    // a sphere resting on the floor; size.x is its diameter
  Bar,     // crawl under: two posts and a bar whose underside is size.y above the floor; size.x wide
  Beam,    // duck under: like a bar, higher (about 1.2 m); size.x wide, size.y to the underside
  Hurdle,  // jump over: a board whose top is size.y above the floor, on two legs with feet; size.x wide
  Box,     // a plain box standing on the floor, size = extents
};

const char* object_type_name(ObjectType type);

struct SceneObject {
  ObjectType type = ObjectType::Box;
  glm::vec3 position{0.0f};  // on the floor, centre of the footprint
  float heading = 0.0f;      // radians about +Y; at 0 the obstacle spans the X axis (crossed walking along +Z)
  glm::vec3 size{1.0f};      // see ObjectType
  bool is_source = false;    // highlighted as the source of influence
  bool light = false;        // far from the camera (the crowd): a ball drawn with the low-poly sphere
};

// Balance (Sec. 5.3) of one character, drawn on the floor when the demo's toggle is on (overlay.h): the
// support polygon (convex hull of the feet in contact, counter-clockwise in (x, z)) and the centre of mass.
struct BalanceView {
  glm::vec3 com{0.0f};
  std::vector<glm::vec2> support;  // empty in flight
  bool com_inside = false;         // the COM's floor projection lies inside the support polygon
};

struct Scene {
  std::vector<SceneCharacter> characters;
  std::vector<BalanceView> balance;       // drawn by render::Overlay; empty: not shown
  std::vector<SceneObject> objects;
  std::vector<glm::vec3> goal;            // goal point, or waypoints in order (first = current); empty: none
  float goal_radius = 0.4f;               // drawn as the goal ring (RewardParams::goal_radius)
  std::optional<glm::vec3> source;        // where the source of influence is (ring on the floor)
  float source_radius = 0.4f;             // RewardParams::source_radius
  glm::vec3 focus{0.0f, 0.9f, 0.0f};      // what the shadow map is centred on (usually the player's root)
};

// The head joint (named "head", case-insensitive), else the highest joint of the rest pose: where the
// clip viewer looks for the head, and the tests' point on the head's pixels (the head capsule, from
// BodyVolumes, sits just above it).
int head_joint(const Skeleton& skeleton);

}  // namespace prep::render
