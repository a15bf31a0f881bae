// One character's run-time state inside the World (its motion stream, controller, synthesis state and the
// bookkeeping of its approach), shared by the world's files. Internal to engine/world.
#pragma once

#include <algorithm>
#include <memory>
#include <vector>

#include <glm/gtc/quaternion.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "engine/control/controller.h"
#include "engine/synthesis/synthesizer.h"
#include "engine/world/motion_stream.h"
#include "engine/world/world.h"

namespace prep {

// Joint positions and rotations, body-part centroids and capsules in an object's frame that a world's
// call works out and uses at once, never kept from one call to the next: the calling thread's buffers,
// warm in its cache, rather than each character's.
struct CallScratch {
  std::vector<glm::vec3> positions, centroids;
  std::vector<glm::quat> rotations;
  std::vector<PlacedCapsule> framed;  // World::keep_clear_of_obstacles
  Pose pose;                          // World::entry_clear_of
  std::vector<PlacedCapsule> capsules;
};
inline CallScratch& call_scratch() {
  thread_local CallScratch scratch;
  return scratch;
}

struct World::Runtime {
  explicit Runtime(const MotionGraph& graph) : stream(graph) {}
  MotionStream stream;
  std::unique_ptr<Controller> controller;
  SynthesisState synthesis;
  SynthesisScratch scratch;
  Pose out;                      // this tick's pose being made (World::step_character)
  // scratch.positions / rotations are the forward kinematics of the character's pose (update_balance
  // leaves them so; displace moves the pose).
  bool kinematics_of_pose = false;
  float next_decision = 0.0f;
  // The source the last decision was taken for: the level is chosen again on a nearer distance bin of that
  // source only (RuntimeParams::level_per_source_bin; the controller keeps the bin).
  int decided_source_object = -1, decided_source_character = -1;
  int turning_toward_goal = 0;   // the turn action playing turns toward the goal: +1 / -1 its sign, else 0
  bool reseed = false;           // the next synthesized frame continues from the current position
  glm::vec3 last_displacement{0.0f};       // the locomotion's last step (m per tick)
  glm::vec3 synthesis_previous_root{0.0f};
  Pose fade_from;                // cross-fade from this pose ...
  float fade_left = 0.0f;        // ... over the remaining seconds
  float fade_total = 0.0f;
  // A cross-fade from `from` (the pose shown now) over `seconds`, or over what is left of the fade under
  // way if that is longer: a switch right after a release must not cut kept preparation's long fade short.
  void begin_fade(const Pose& from, float seconds) {
    fade_from = from;
    fade_total = fade_left = std::max(seconds, fade_left);
  }
  int target_object = -1, target_character = -1;
  bool struck = false;           // the strike landed (TargetMotion::strike_frame, else T_t)
  float struck_time = 0.0f;      // world time it landed
  // Aiming a strike or an obstacle clip (World::start_target): the root is slid by `aim` in all between the launch and the strike
  // frame, a smooth share per tick.
  glm::vec2 aim{0.0f};
  float aim_seconds = 0.0f, aim_elapsed = 0.0f;
  ObstacleFit fit;               // the obstacle clip playing, fitted to its obstacle (obstacle_fit.h)
  // The heading the target clip playing was started facing (World::start_target): its way on, where the
  // pelvis of a clip may swing far from it (a duck turned sideways under its beam).
  float launch_heading = 0.0f;
  // The source as last seen (for its speed toward the character and to notice a change of source).
  int source_key = -2;           // object index, or -(character index) - 3, or -2 for none
  glm::vec2 source_position{0.0f};
  float source_closing_speed = 0.0f;  // m/s toward the character (> 0 closing in)
  bool approach_seen = false, approach_from_far = false;  // the approach to it began more than 1 m away
  bool released = false;         // the target clip playing was left for prepared locomotion
  float speed = 0.0f;            // m/s over the floor, smoothed over about half a second (steering)
  glm::vec2 velocity{0.0f};      // m/s over the floor, last tick (keep_apart)
  float stride_scale = 1.0f;     // the tight turn's stride, following its target (steering.h)
  bool facing = false;           // the source obstacle is faced closely enough to arrive at (Approach)
  bool square = false;           // ... and to launch at (Approach)
  bool beside = false;           // beside the span's launch part (Approach): no arrival yet
  // The places along the source obstacle's span that leave its clip room before the next obstacle
  // (World::launch_lateral), sampled every kLateralStep from the span's launch part's one end; kept while
  // the source and the side it is approached from stay the same.
  int room_obstacle = -1;
  bool room_from_front = false;
  std::vector<RoomShort> room;     // the room each place lacks (World::RoomShort)
  bool room_moved = false;        // the launch place is not the character's own for want of room
  std::vector<PlacedCapsule> capsules;  // the body this frame (World::keep_clear_of_obstacles)
};

}  // namespace prep
