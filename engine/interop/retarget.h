// Retargeting motion between humanoid skeletons by a joint map.
//
// A joint map (JSON) names, for joints of another skeleton, the joint of ours they correspond to:
//   {"name": "daz43", "joints": {"hip": "Hips", "abdomen": "Spine", "rThigh": "RightUpLeg", ...}}
// Source names match exactly, else ignoring case and any "namespace:" prefix (Mixamo's "mixamorig:").
// Entries naming a joint that a skeleton lacks are skipped; the two roots must be mapped.
//
// How a pose moves across (every Skeleton's rest pose has identity rotations, so a joint's world rotation
// is its world-space rotation away from the rest pose):
// - rest-pose differences: for each mapped pair, a constant alignment A_k turns the target bone's rest
//   directions (to its nearest mapped descendants, or to its End Site) onto the source's: the shortest arc
//   for one direction, the least-squares rotation (Horn 1987) for several, e.g. the pelvis: up the spine and
//   to both hips, which also fixes the twist. Both are exact inverses when source and target swap;
// - per frame, the target joint's world rotation is the source joint's world rotation times A_k (the
//   world-space delta from rest is transferred); unmapped target joints keep their rest rotation relative
//   to their parent; local rotations follow from the world ones;
//   A bone with no mapped child and no clean tip (a hand whose fingers branch) takes its nearest mapped
//   ancestor's alignment; feet are aligned in heading only, so that a flat foot stays flat;
// - bone lengths are the target's own; the root translation is scaled by the ratio of leg lengths (thigh +
//   shin): horizontally as is, vertically as the deviation from each skeleton's standing root height (legs
//   straight down, feet flat), so that strides, crouches and jumps scale and a standing pose stands;
// - legs of other proportions (thigh/shin ratio) would move the feet differently, so each target ankle is
//   then placed by two-bone IK (hip, knee; the knee stays in its transferred bending plane) where the
//   source's ankle is, scaled like the root and offset by the difference of ankle heights above the soles:
//   heel heights, contact timing and planted feet carry over. Then, with a toe joint, the foot bends at the
//   ball (two-bone IK on ankle and toe) so that its toe tip lands on the source's scaled toe tip (planted
//   toes stay planted through push-off); without one, the foot turns about the ankle to point at it.
#pragma once

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "engine/motion/clip.h"

namespace prep {

struct JointMap {
  std::string name;
  std::vector<std::pair<std::string, std::string>> pairs;  // (joint of the other skeleton, joint of ours)
};

JointMap load_joint_map(const std::string& path);  // throws InputError naming the file and field
JointMap parse_joint_map(const std::string& text, const std::string& source_name);
JointMap inverted(const JointMap& map);  // ours -> theirs

// Finds a joint by the map's matching rule (exact, else case- and namespace-insensitive). -1 if absent.
int find_joint_loosely(const Skeleton& skeleton, const std::string& name);

// A humanoid's legs (from BodyMap::detect; a skeleton that is not recognised falls back on its rest pose's
// extent below the root for both).
struct LegMeasures {
  float leg_length = 0.0f;            // thigh + shin, averaged over both legs
  float standing_root_height = 0.0f;  // root above the soles with the legs straight down and the feet flat
};
LegMeasures leg_measures(const Skeleton& skeleton);

class Retargeter {
 public:
  // Throws std::invalid_argument if the roots are not mapped to each other.
  Retargeter(std::shared_ptr<const Skeleton> source, std::shared_ptr<const Skeleton> target, const JointMap& map);

  void retarget(const Pose& source_pose, Pose& target_pose) const;
  Clip retarget(const Clip& clip) const;  // same frame rate and frame count, on the target skeleton

  float root_scale() const { return root_scale_; }
  // Target joint -> source joint, -1 where unmapped.
  const std::vector<int>& source_of() const { return source_of_; }

 private:
  std::shared_ptr<const Skeleton> source_, target_;
  std::vector<int> source_of_;
  std::vector<glm::quat> alignment_;  // A_k per target joint
  float root_scale_ = 1.0f;
  LegMeasures source_legs_, target_legs_;
  struct FootPlant {
    int hip = -1, knee = -1, ankle = -1;  // target joints
    int source_ankle = -1;
    float height_offset = 0.0f;  // target ankle height above its sole minus the scaled source's
    int toe_tip = -1, source_toe_tip = -1;  // joints whose End Sites are the toe tips (-1: no toe aiming)
    std::vector<int> foot;                  // the target ankle and its descendants
    int toe = -1;                           // target toe joint (child of the ankle), if any
  };
  std::vector<FootPlant> legs_;
};


}  // namespace prep
