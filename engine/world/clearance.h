// Clearance: how far each character's body is from the solid parts of the objects (object_solids.h) and
// from the other characters' bodies, per frame. The body is its capsules (engine/motion/body_volumes.h).
// A signed distance: positive is a gap, negative a penetration, in metres, between surfaces.
//
// - Body to object: each capsule against each box (the distance from the capsule's segment to the box,
//   exact: it is convex along the segment, so a golden-section search finds its minimum) and the ball's
//   sphere, less the capsule's radius.
// - Body to body: each capsule pair (segment to segment), less both radii. A punch's hand and forearm
//   against the character it is launched at do not count from the launch until the arm is back in guard
//   (WorldCharacter::arm_out_at): meeting it is the point.
#pragma once

#include <limits>
#include <memory>
#include <string>
#include <vector>

#include <glm/gtc/quaternion.hpp>
#include <glm/vec3.hpp>
#include <nlohmann/json.hpp>

#include "engine/motion/body_volumes.h"
#include "engine/world/object_solids.h"
#include "engine/world/world.h"

namespace prep {

// Thresholds of the acceptance (prep evaluate; the tests).
namespace clearance_metric {
constexpr float kObjectTolerance = 0.01f;     // m: a body may touch an object this deep, no deeper
constexpr float kCharacterTolerance = 0.02f;  // m: two bodies may touch this deep, no deeper
}  // namespace clearance_metric

// The nearest approach of one body to something, in one frame.
struct Nearest {
  float distance = std::numeric_limits<float>::infinity();  // m, signed (< 0: penetrating)
  int capsule = -1;     // index into BodyVolumes::capsules() of the body measured
  int object = -1;      // World::objects() index, or
  int character = -1;   // the other character
  SolidPart part = SolidPart::Rail;  // the object's part (objects only)
  int other_capsule = -1;            // the other body's capsule (characters only)
};

struct CharacterClearance {
  Nearest object;                    // the nearest object part
  Nearest character;                 // the nearest other body
  std::vector<int> penetrating;      // capsules deeper than the tolerances in anything (the debug view)
};

// A punch's striking hand and forearm (the side the action names): they may meet the one punched at.
bool is_striking_limb(TargetAction punch, BodyPart part);

// The point of the segment from a to b nearest p.
glm::vec3 closest_on_segment(glm::vec3 p, glm::vec3 a, glm::vec3 b);
// Signed distances of the primitives (exposed for the tests).
float segment_box_distance(glm::vec3 a, glm::vec3 b, glm::vec3 centre, glm::vec3 half_extents);  // to the box's surface
float segment_segment_distance(glm::vec3 a0, glm::vec3 a1, glm::vec3 b0, glm::vec3 b1);
// The signed gap between a placed capsule and one solid of an object standing at `at` on the floor, turned
// `heading` (radians).
float capsule_solid_distance(const PlacedCapsule& capsule, const ObjectSolid& solid, glm::vec2 at, float heading);
// How deep the capsule is in the solid: max(0, -capsule_solid_distance), the same number, with the pairs
// that cannot touch skipped. A segment's distance to a solid is at least its midpoint's less half its
// length (a distance changes no faster than the point moves), so a capsule whose bounding sphere clears
// the solid by more than kSurelyClear is not in it, and no search along the segment is needed.
float capsule_solid_depth(const PlacedCapsule& capsule, const ObjectSolid& solid, glm::vec2 at, float heading);
// The same for a capsule whose ends are already in the object's frame (ObjectFrame::to_local).
float framed_capsule_solid_depth(const PlacedCapsule& framed, const ObjectSolid& solid);
constexpr float kSurelyClear = 1e-4f;  // m: far above the rounding of the distances, far below any depth that matters

class ClearanceMeter {
 public:
  explicit ClearanceMeter(const Skeleton& skeleton);
  const BodyVolumes& volumes() const { return volumes_; }

  // Every character of the world this frame (index = World::characters()).
  void measure(const World& world);
  const std::vector<CharacterClearance>& result() const { return result_; }
  // The placed capsules of character i this frame (after measure).
  const std::vector<PlacedCapsule>& capsules(int character) const { return placed_[static_cast<size_t>(character)]; }
  // m: the gap between character i's feet (either) and object k's solids this frame (after measure).
  float feet_to_object(const World& world, int character, int object) const;
  // "head in the rail of the bar at (0.0, 4.0)": who and what, for reports.
  std::string describe(const World& world, int character, const Nearest& n) const;

 private:
  BodyVolumes volumes_;
  std::vector<CharacterClearance> result_;
  std::vector<std::vector<PlacedCapsule>> placed_;
  std::vector<std::vector<ObjectSolid>> solids_;  // per object, this frame
  std::vector<glm::vec3> positions_;
  std::vector<glm::quat> rotations_;
};

// Clearance over a run, observed after every World::step(): the frames that penetrate, the deepest, and per
// launch the nearest approach while its target motion played.
struct LaunchClearance {
  int character = -1;
  TargetAction action = TargetAction::Kick;
  float time = 0;                  // s: the launch
  float min_clearance = std::numeric_limits<float>::infinity();  // m: nearest object (punch: other body)
  std::string nearest;             // what it was (ClearanceMeter::describe)
  // A kick at a ball: the gap between the nearer foot and the ball's surface on the frame the ball is struck
  // (it starts to roll on the next); NaN until then.
  float strike_gap = std::numeric_limits<float>::quiet_NaN();
};

struct ClearanceSummary {
  int frames = 0;              // observed
  int object_frames = 0;       // with a body deeper than kObjectTolerance in an object
  int character_frames = 0;    // with two bodies overlapping more than kCharacterTolerance
  float min_object = std::numeric_limits<float>::infinity();     // m: the nearest any body came to an object
  float min_character = std::numeric_limits<float>::infinity();  // m: ... to another body
  std::string min_object_what, min_character_what;              // who and what, and when
};
nlohmann::json clearance_json(const ClearanceSummary& s);
// For a person: the frames deeper than the tolerances, and the nearest approaches with what they were.
std::string clearance_text(const ClearanceSummary& s);

class ClearanceLog {
 public:
  explicit ClearanceLog(const World& world);  // the world's current state is the first frame
  void observe(const World& world);

  ClearanceSummary summary;
  std::vector<LaunchClearance> launches;  // in the order of World::launches()

  const ClearanceMeter& meter() const { return meter_; }

 private:
  ClearanceMeter meter_;
  size_t launches_seen_ = 0;
  std::vector<int> open_;  // per character: its launch whose target motion plays (index into launches), -1
  std::vector<int> object_of_;  // per launch: the object it was launched at (-1: none)
};

}  // namespace prep
