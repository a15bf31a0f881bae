// Body-part centroids and the centre of mass from an anthropometric mass table.
//
// Table: de Leva (1996), "Adjustments to Zatsiorsky-Seluyanov's segment inertia parameters", J. Biomech.
// 29(9), male values: segment mass as a fraction of body mass and the segment's centre of mass as a
// fraction of its length from the proximal joint. The paper cites Armstrong (1988) for the same purpose.
#pragma once

#include <glm/gtc/quaternion.hpp>
#include <glm/vec3.hpp>
#include <string>
#include <vector>

#include "engine/motion/body_map.h"
#include "engine/motion/skeleton.h"

namespace prep {

struct BodySegment {
  std::string name;          // "trunk", "head", "left_thigh", ...
  int proximal = -1;         // joint at the proximal end
  int distal = -1;           // joint at the distal end (or the joint whose End Site is the distal end)
  bool distal_is_end_site = false;
  float mass_fraction = 0;   // of total body mass
  float com_fraction = 0;    // centroid position along proximal -> distal
};

struct MassModel {
  std::vector<BodySegment> segments;  // masses sum to 1
  static MassModel build(const Skeleton& skeleton, const BodyMap& body);
};

// Centroid (3D) of every segment, in the order of MassModel::segments: the "body parts" of Eq. 7-9.
void segment_centroids(const Skeleton& skeleton, const MassModel& model, const std::vector<glm::vec3>& world_positions,
                       const std::vector<glm::quat>& world_rotations, std::vector<glm::vec3>& out);

// The same for the listed segments only (indices into MassModel::segments), into `out`, which holds an entry
// per segment; the others are left as they are.
void segment_centroids(const Skeleton& skeleton, const MassModel& model, const std::vector<glm::vec3>& world_positions,
                       const std::vector<glm::quat>& world_rotations, const std::vector<int>& segments,
                       std::vector<glm::vec3>& out);
// The segments whose centroid moves when the given joints turn and nothing above them moves: those with a
// joint strictly below one of them at either end, or with one of them as the distal joint of an End Site.
std::vector<int> segments_moved_by_turning(const Skeleton& skeleton, const MassModel& model, const std::vector<int>& joints);

// Mass-weighted mean of the segment centroids.
glm::vec3 center_of_mass(const MassModel& model, const std::vector<glm::vec3>& centroids);

}  // namespace prep
