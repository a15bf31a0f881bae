// The body as solid volumes: one capsule per bone (parent joint -> joint, and joint -> End Site) and a
// sphere-like capsule for the head, sized for an adult body. The renderer draws exactly these (its
// capsule view), and the clearance measure (engine/world/clearance.h) tests them against obstacles and
// other characters, so what is drawn is what is checked.
//
// Radii come from each bone's anatomy: the joint's name (thigh/upleg, shin/leg, forearm, spine, ...), for
// our skeleton, the CMU conversions and Mixamo-style names alike; the head and which limb a capsule belongs
// to come from the body map. Radii (m): trunk 0.10, pelvis 0.085, thigh 0.068, shin 0.052, neck 0.05,
// upper arm 0.048, collar 0.045, foot 0.042, forearm 0.04, hand 0.032, toes 0.03, fingers 0.011; the head
// a 0.10 m sphere whose centre is 0.11 m above the head joint along the head's up axis.
#pragma once

#include <string>
#include <vector>

#include <glm/gtc/quaternion.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "engine/motion/body_map.h"
#include "engine/motion/skeleton.h"

namespace prep {

// Which part of the body a capsule is: the limbs a clearance report names and the exceptions it makes
// (a punching hand meets its target).
enum class BodyPart { Head, Trunk, LeftArm, RightArm, LeftHand, RightHand, LeftLeg, RightLeg, LeftFoot, RightFoot };
const char* body_part_name(BodyPart part);  // "head", "trunk", "left arm", ...

struct BodyCapsule {
  int joint = -1;        // the segment starts at this joint ...
  int end_joint = -1;    // ... and ends at this one, or (-1) at `local_end` in `joint`'s frame
  glm::vec3 local_end{0.0f};  // the End Site; for the head its up axis (the capsule is centred along it)
  float radius = 0.0f;   // m
  BodyPart part = BodyPart::Trunk;
  std::string name;      // "LeftUpLeg", the joint the bone starts at (the head: the head joint's name)
};

// A capsule placed in the world for one pose: the segment a-b grown by radius.
struct PlacedCapsule {
  glm::vec3 a{0.0f}, b{0.0f};
  float radius = 0.0f;
};

class BodyVolumes {
 public:
  BodyVolumes() = default;
  // The body map names the head and the limbs (BodyMap::detect); a skeleton it cannot map gets capsules by
  // name alone, with the head the highest joint of the rest pose and every capsule counted as trunk.
  explicit BodyVolumes(const Skeleton& skeleton);

  const std::vector<BodyCapsule>& capsules() const { return capsules_; }
  // The capsules of a pose from its forward kinematics (world joint positions and rotations).
  void place(const std::vector<glm::vec3>& positions, const std::vector<glm::quat>& rotations,
             std::vector<PlacedCapsule>& out) const;
  // A box on the floor (x, z) that holds every capsule of the pose, from the joint positions alone: each
  // joint grown by the farthest any of its capsules reaches from it (its radius, and the End Site's length
  // or the head's extent for a capsule that ends in the joint's own frame). Never smaller than the placed
  // capsules' box, and a fraction of the cost of placing them: a body that this box keeps clear of
  // something is clear of it.
  void floor_box_bound(const std::vector<glm::vec3>& positions, glm::vec2& low, glm::vec2& high) const;

 private:
  int head_ = 0;
  std::vector<BodyCapsule> capsules_;
  struct BoundPoint {
    int joint = -1;
    float reach = 0.0f;  // m: how far from the joint its capsules reach
  };
  std::vector<BoundPoint> bound_points_;  // every joint a capsule starts or ends at
};

// The radius of the bone that starts at a joint of this name (any case), 0 for eyes and jaw (not drawn).
float bone_radius(const std::string& joint_name);

}  // namespace prep
