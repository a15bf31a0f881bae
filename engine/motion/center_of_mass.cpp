#include "engine/motion/center_of_mass.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <glm/geometric.hpp>
#include <stdexcept>

#include "engine/motion/joint_names.h"
#include "engine/motion/kinematics.h"
#include "engine/motion/vector_ops.h"

namespace prep {
namespace {

// de Leva (1996), Table 4, male: mass in % of body mass, and the longitudinal centre-of-mass position in %
// of the segment length measured from the first-named end point. The trunk's three parts (upper, middle,
// lower: suprasternale-xiphoid, xiphoid-omphalion, omphalion-mid-hip) add up to the whole trunk's mass.
// Head+neck uses the vertex-cervicale (C7) length; the foot the heel-toe tip length.
constexpr float kHeadMass = 6.94f, kHeadComFromVertex = 50.02f;
constexpr float kTrunkMass = 43.46f, kTrunkComFromSuprasternale = 44.86f;
constexpr float kUpperTrunkMass = 15.96f, kUpperTrunkComFromSuprasternale = 29.99f;
constexpr float kMiddleTrunkMass = 16.33f, kMiddleTrunkComFromXiphoid = 45.02f;
constexpr float kLowerTrunkMass = 11.17f, kLowerTrunkComFromOmphalion = 61.15f;
constexpr float kUpperArmMass = 2.71f, kUpperArmComFromShoulder = 57.72f;
constexpr float kForearmMass = 1.62f, kForearmComFromElbow = 45.74f;
constexpr float kHandMass = 0.61f, kHandComFromWrist = 79.00f;
constexpr float kThighMass = 14.16f, kThighComFromHip = 40.95f;
constexpr float kShankMass = 4.33f, kShankComFromKnee = 44.59f;
constexpr float kFootMass = 1.37f, kFootComFromHeel = 44.15f;
// de Leva's trunk lengths (male, mm): lower 145.7, middle 215.5, upper 170.7. They place the omphalion
// (navel) and the xiphoid at these fractions of the way from the mid-hip point up to the suprasternale.
constexpr float kOmphalionHeight = 145.7f / (145.7f + 215.5f + 170.7f);
constexpr float kXiphoidHeight = (145.7f + 215.5f) / (145.7f + 215.5f + 170.7f);
// A spine joint stands in for the navel or the xiphoid only if it is this close (fraction of trunk height).
constexpr float kSpineJointTolerance = 0.2f;

using joint_names::lower;

struct Rest {
  std::vector<glm::vec3> positions;
  std::vector<glm::quat> rotations;
};

// The third knuckle (de Leva's MET3) that ends the hand: the first joint below the wrist named like the
// middle finger or the fingers, else the wrist's End Site, else the wrist itself.
void hand_end(const Skeleton& sk, int wrist, BodySegment& s) {
  for (int j = wrist + 1; j < sk.size(); ++j) {
    int a = j;
    while (a > wrist) a = sk.joints[static_cast<size_t>(a)].parent;
    if (a != wrist) continue;
    const std::string name = lower(sk.joints[static_cast<size_t>(j)].name);
    if (name.find("mid") != std::string::npos || name.find("finger") != std::string::npos) {
      s.distal = j;
      return;
    }
  }
  s.distal = wrist;
  s.distal_is_end_site = sk.joints[static_cast<size_t>(wrist)].has_end_site;
}

}  // namespace

MassModel MassModel::build(const Skeleton& skeleton, const BodyMap& body) {
  if (skeleton.size() == 0) throw std::invalid_argument("mass model: empty skeleton");
  Rest rest;
  forward_kinematics(skeleton, Pose(skeleton.size()), rest.positions, &rest.rotations);
  const auto pos = [&](int j) { return rest.positions[static_cast<size_t>(j)]; };

  MassModel model;
  const auto add = [&](std::string name, int proximal, int distal, bool end_site, float mass_pct, float com_pct) {
    BodySegment s;
    s.name = std::move(name);
    s.proximal = proximal;
    s.distal = distal;
    s.distal_is_end_site = end_site;
    s.mass_fraction = mass_pct / 100.0f;
    s.com_fraction = com_pct / 100.0f;
    model.segments.push_back(std::move(s));
  };

  // Trunk: pelvis (root, standing in for the mid-hip point) to the neck base (the suprasternale's level).
  // Split in three where the spine has joints near the navel and the xiphoid, else one segment.
  const int top = body.neck >= 0 ? body.neck : body.head;
  const float trunk_height = pos(top).y - pos(body.root).y;
  int navel = -1, xiphoid = -1;
  if (trunk_height > 0.0f) {
    float best_navel = kSpineJointTolerance, best_xiphoid = kSpineJointTolerance;
    for (int j : body.spine) {
      const float h = (pos(j).y - pos(body.root).y) / trunk_height;
      if (std::abs(h - kOmphalionHeight) < best_navel) best_navel = std::abs(h - kOmphalionHeight), navel = j;
      if (std::abs(h - kXiphoidHeight) < best_xiphoid) best_xiphoid = std::abs(h - kXiphoidHeight), xiphoid = j;
    }
  }
  if (navel >= 0 && xiphoid >= 0 && navel != xiphoid && pos(navel).y < pos(xiphoid).y) {
    // Fractions from de Leva's first-named (upper) end, turned around to run from the lower joint up.
    add("lower_trunk", body.root, navel, false, kLowerTrunkMass, 100.0f - kLowerTrunkComFromOmphalion);
    add("middle_trunk", navel, xiphoid, false, kMiddleTrunkMass, 100.0f - kMiddleTrunkComFromXiphoid);
    add("upper_trunk", xiphoid, top, false, kUpperTrunkMass, 100.0f - kUpperTrunkComFromSuprasternale);
  } else {
    add("trunk", body.root, top, false, kTrunkMass, 100.0f - kTrunkComFromSuprasternale);
  }

  // Head and neck: from the neck base to the vertex. The vertex is the head's End Site when it has one;
  // otherwise (daz43) it is estimated above the head joint at twice the height of the eyes above it
  // (the eyes sit about halfway up the skull), or one neck length above the head joint.
  {
    const int proximal = body.neck >= 0 ? body.neck : body.head;
    const Joint& head = skeleton.joints[static_cast<size_t>(body.head)];
    if (head.has_end_site && proximal != body.head) {
      add("head", proximal, body.head, true, kHeadMass, 100.0f - kHeadComFromVertex);
    } else {
      float eyes = 0.0f;
      for (int j = body.head + 1; j < skeleton.size(); ++j)
        if (skeleton.joints[static_cast<size_t>(j)].parent == body.head) eyes = std::max(eyes, pos(j).y - pos(body.head).y);
      const float neck_length = proximal != body.head ? glm::length(pos(body.head) - pos(proximal)) : 0.0f;
      const float above_head = head.has_end_site ? glm::length(head.end_site) : eyes > 0.0f ? 2.0f * eyes : neck_length;
      if (proximal != body.head && neck_length > 0.0f) {
        // The centroid on the neck->head line, expressed as a fraction of the neck->head length.
        const float along = (1.0f - kHeadComFromVertex / 100.0f) * (neck_length + above_head);
        add("head", proximal, body.head, false, kHeadMass, 100.0f * along / neck_length);
      } else {
        add("head", body.head, body.head, head.has_end_site, kHeadMass, 100.0f - kHeadComFromVertex);
      }
    }
  }

  static const char* const side_names[2] = {"left_", "right_"};
  for (int side : {kLeft, kRight}) {
    const std::string p = side_names[side];
    const ArmChain& arm = body.arms[static_cast<size_t>(side)];
    add(p + "upper_arm", arm.shoulder, arm.elbow, false, kUpperArmMass, kUpperArmComFromShoulder);
    add(p + "forearm", arm.elbow, arm.wrist, false, kForearmMass, kForearmComFromElbow);
    add(p + "hand", arm.wrist, arm.wrist, false, kHandMass, kHandComFromWrist);
    hand_end(skeleton, arm.wrist, model.segments.back());

    const LegChain& leg = body.legs[static_cast<size_t>(side)];
    add(p + "thigh", leg.hip, leg.knee, false, kThighMass, kThighComFromHip);
    add(p + "shank", leg.knee, leg.ankle, false, kShankMass, kShankComFromKnee);
    const bool tip_site = leg.toe_tip_joint >= 0 && skeleton.joints[static_cast<size_t>(leg.toe_tip_joint)].has_end_site;
    const int tip = tip_site ? leg.toe_tip_joint : leg.toe >= 0 ? leg.toe : leg.ankle;
    add(p + "foot", leg.ankle, tip, tip_site, kFootMass, kFootComFromHeel);
  }

  // de Leva's masses add up to 100 %; dividing by the sum keeps that exact in floating point.
  float total = 0.0f;
  for (const BodySegment& s : model.segments) total += s.mass_fraction;
  for (BodySegment& s : model.segments) s.mass_fraction /= total;
  return model;
}

namespace {

// A segment's centroid: from its proximal joint toward its distal point (the joint, or its End Site).
inline void segment_centroid(const BodySegment& s, const Joint* joints, const glm::vec3* positions, const glm::quat* rotations,
                             glm::vec3& centroid) {
  const size_t d = static_cast<size_t>(s.distal);
  const V3 a = V3::load(positions[static_cast<size_t>(s.proximal)]);
  const V3 b = s.distal_is_end_site ? V3::load(positions[d]) + rotate(rotations[d], V3::load(joints[d].end_site))
                                    : V3::load(positions[d]);
  (a + s.com_fraction * (b - a)).store(centroid);
}

}  // namespace

void segment_centroids(const Skeleton& skeleton, const MassModel& model, const std::vector<glm::vec3>& world_positions,
                       const std::vector<glm::quat>& world_rotations, std::vector<glm::vec3>& out) {
  out.resize(model.segments.size());
  // The addresses held in locals: the SSE2 store may alias anything, and would have them read again.
  const BodySegment* const segments = model.segments.data();
  const Joint* const joints = skeleton.joints.data();
  const glm::vec3* const positions = world_positions.data();
  const glm::quat* const rotations = world_rotations.data();
  glm::vec3* const centroids = out.data();
  for (size_t i = 0, n = model.segments.size(); i < n; ++i) segment_centroid(segments[i], joints, positions, rotations, centroids[i]);
}

void segment_centroids(const Skeleton& skeleton, const MassModel& model, const std::vector<glm::vec3>& world_positions,
                       const std::vector<glm::quat>& world_rotations, const std::vector<int>& which,
                       std::vector<glm::vec3>& out) {
  const BodySegment* const segments = model.segments.data();
  const Joint* const joints = skeleton.joints.data();
  const glm::vec3* const positions = world_positions.data();
  const glm::quat* const rotations = world_rotations.data();
  glm::vec3* const centroids = out.data();
  for (int i : which) {
    const size_t k = static_cast<size_t>(i);
    segment_centroid(segments[k], joints, positions, rotations, centroids[k]);
  }
}

std::vector<int> segments_moved_by_turning(const Skeleton& skeleton, const MassModel& model, const std::vector<int>& joints) {
  // below[j]: j is strictly below one of the joints (its position moves when they turn).
  std::vector<char> turned(static_cast<size_t>(skeleton.size()), 0), below(static_cast<size_t>(skeleton.size()), 0);
  for (int j : joints) turned[static_cast<size_t>(j)] = 1;
  for (int j = 0; j < skeleton.size(); ++j) {
    const int parent = skeleton.joints[static_cast<size_t>(j)].parent;
    if (parent >= 0) below[static_cast<size_t>(j)] = turned[static_cast<size_t>(parent)] || below[static_cast<size_t>(parent)];
  }
  std::vector<int> moved;
  for (size_t i = 0; i < model.segments.size(); ++i) {
    const BodySegment& s = model.segments[i];
    const size_t p = static_cast<size_t>(s.proximal), d = static_cast<size_t>(s.distal);
    if (below[p] || below[d] || (s.distal_is_end_site && turned[d])) moved.push_back(static_cast<int>(i));
  }
  return moved;
}

glm::vec3 center_of_mass(const MassModel& model, const std::vector<glm::vec3>& centroids) {
  const BodySegment* const segments = model.segments.data();
  const glm::vec3* const points = centroids.data();
  V3 sum = V3::zero();
  float mass = 0.0f;
  for (size_t i = 0, n = std::min(model.segments.size(), centroids.size()); i < n; ++i) {
    const float m = segments[i].mass_fraction;
    sum += m * V3::load(points[i]);
    mass += m;
  }
  return (mass > 0.0f ? sum / mass : sum).vec();
}

}  // namespace prep
