#include "engine/graph/reference_posture.h"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <stdexcept>

#include "engine/motion/kinematics.h"
#include "engine/motion/support_polygon.h"

namespace prep {

std::vector<glm::vec3> leg_positions(const MotionSet& set, const Pose& pose) {
  const Skeleton& sk = *set.skeleton;
  std::vector<glm::vec3> positions;
  std::vector<glm::quat> rotations;
  forward_kinematics(sk, pose, positions, &rotations);
  const FootPoints feet = foot_points(sk, set.body, positions, rotations);
  const glm::quat unturn = glm::angleAxis(-heading_of(pose.rotations[0]), glm::vec3(0.0f, 1.0f, 0.0f));
  const glm::vec3 origin(pose.root_position.x, 0.0f, pose.root_position.z);
  std::vector<glm::vec3> out;
  for (int side : {kLeft, kRight}) {
    const LegChain& leg = set.body.legs[static_cast<size_t>(side)];
    for (int j : {leg.hip, leg.knee, leg.ankle}) out.push_back(unturn * (positions[static_cast<size_t>(j)] - origin));
    out.push_back(unturn * (feet.toe[static_cast<size_t>(side)] - origin));
  }
  return out;
}

bool same_feet_down(const FrameContacts& a, const FrameContacts& b) {
  return a[kLeft].any() == b[kLeft].any() && a[kRight].any() == b[kRight].any();
}

float legs_distance(const std::vector<glm::vec3>& a, const std::vector<glm::vec3>& b) {
  float sum = 0.0f;
  for (size_t i = 0; i < a.size() && i < b.size(); ++i) {
    const glm::vec3 d = a[i] - b[i];
    sum += glm::dot(d, d);
  }
  return sum;
}

bool com_in_support(const MotionSet& set, const MotionClip& mc, int frame, const ContactParams& params) {
  const Skeleton& sk = *set.skeleton;
  std::vector<glm::vec3> positions, centroids;
  std::vector<glm::quat> rotations;
  forward_kinematics(sk, mc.clip.frames[static_cast<size_t>(frame)], positions, &rotations);
  const SupportPolygon support =
      support_polygon(foot_points(sk, set.body, positions, rotations), mc.contacts[static_cast<size_t>(frame)], params);
  segment_centroids(sk, set.mass, positions, rotations, centroids);
  const glm::vec3 com = center_of_mass(set.mass, centroids);
  return support.contains({com.x, com.z});
}

ReferencePosture find_reference_posture(const MotionSet& set, int clip, const Params& params) {
  if (clip < 0 || clip >= static_cast<int>(set.clips.size())) throw std::invalid_argument("reference posture: no such clip");
  const MotionClip& mc = set.clips[static_cast<size_t>(clip)];
  if (mc.clip.frame_count() == 0 || mc.contacts.size() != mc.clip.frames.size())
    throw std::invalid_argument("reference posture: clip '" + mc.clip.name + "' has no frames or no contacts");
  ReferencePosture r;
  r.clip = clip;
  r.t_t = std::clamp(mc.target_frame, 0, mc.clip.frame_count() - 1);
  const std::vector<glm::vec3> legs0 = leg_positions(set, mc.clip.frames[0]);
  const FrameContacts& contacts0 = mc.contacts[0];
  for (int f = r.t_t; f >= 0; --f) {  // from T_t back toward T_0
    const bool same = same_feet_down(mc.contacts[static_cast<size_t>(f)], contacts0);
    if (!same) continue;
    const float legs = legs_distance(leg_positions(set, mc.clip.frames[static_cast<size_t>(f)]), legs0);
    if (legs >= params.reference.legs_threshold) continue;
    if (!com_in_support(set, mc, f, params.contacts)) continue;
    r.frame = f;
    r.found = true;
    r.com_in_support = r.same_contacts = r.legs_close = true;
    r.legs_distance = legs;
    return r;
  }
  // None qualified: T_0, with the conditions as they hold there.
  r.frame = 0;
  r.same_contacts = true;
  r.legs_close = true;
  r.legs_distance = 0.0f;
  r.com_in_support = com_in_support(set, mc, 0, params.contacts);
  return r;
}

std::vector<ReferencePosture> find_reference_postures(const MotionSet& set, const Params& params) {
  std::vector<ReferencePosture> out;
  for (size_t c = 0; c < set.clips.size(); ++c)
    if (!is_locomotion(set.clips[c].role)) out.push_back(find_reference_posture(set, static_cast<int>(c), params));
  return out;
}

}  // namespace prep
