#include "engine/interop/retarget.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <glm/gtc/quaternion.hpp>
#include <glm/mat3x3.hpp>
#include <nlohmann/json.hpp>
#include <map>
#include <set>
#include <stdexcept>

#include "engine/motion/body_map.h"
#include "engine/motion/kinematics.h"
#include "engine/util/error.h"
#include "engine/util/files.h"

namespace prep {

JointMap parse_joint_map(const std::string& text, const std::string& source_name) {
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(text);
  } catch (const nlohmann::json::exception& e) {  // bad syntax, or a number past a double's range (1e400)
    throw InputError(source_name, "not valid JSON: " + std::string(e.what()));
  }
  if (!j.is_object()) throw InputError(source_name, "a joint map is a JSON object");
  JointMap map;
  for (auto it = j.begin(); it != j.end(); ++it) {
    if (it.key() == "name") {
      if (!it->is_string()) throw InputError(source_name, "field \"name\" must be a string");
      map.name = it->get<std::string>();
    } else if (it.key() == "joints") {
      if (!it->is_object()) throw InputError(source_name, "field \"joints\" must be an object {their joint: our joint}");
      for (auto p = it->begin(); p != it->end(); ++p) {
        if (!p->is_string()) throw InputError(source_name, "field \"joints." + p.key() + "\" must be a joint name (string)");
        map.pairs.emplace_back(p.key(), p->get<std::string>());
      }
    } else if (it.key() != "comment") {
      throw InputError(source_name, "unknown field \"" + it.key() + "\" (expected name, joints, comment)");
    }
  }
  if (map.pairs.empty()) throw InputError(source_name, "field \"joints\" is missing or empty");
  return map;
}

JointMap load_joint_map(const std::string& path) { return parse_joint_map(read_file(path), path); }

JointMap inverted(const JointMap& map) {
  JointMap out;
  out.name = map.name + " (inverted)";
  for (const auto& pair : map.pairs) {
    // A plain reference, not a structured binding: clang (the fuzz tree's compiler) does not let a lambda
    // capture a binding before C++20.
    const std::string& ours = pair.second;
    const bool taken = std::any_of(out.pairs.begin(), out.pairs.end(), [&](const auto& p) { return p.first == ours; });
    if (!taken) out.pairs.emplace_back(ours, pair.first);
  }
  return out;
}

namespace {
std::string loose(const std::string& name) {
  const size_t colon = name.find_last_of(':');
  std::string s = colon == std::string::npos ? name : name.substr(colon + 1);
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}
}  // namespace

int find_joint_loosely(const Skeleton& skeleton, const std::string& name) {
  const int exact = skeleton.find(name);
  if (exact >= 0) return exact;
  const std::string key = loose(name);
  for (int j = 0; j < skeleton.size(); ++j)
    if (loose(skeleton.joints[static_cast<size_t>(j)].name) == key) return j;
  return -1;
}

namespace {

// The lowest point of the rest pose (joints and End Sites) with the root at the origin.
float lowest_rest_point(const Skeleton& skeleton) {
  std::vector<glm::vec3> p;
  std::vector<glm::quat> q;
  forward_kinematics(skeleton, Pose(skeleton.size()), p, &q);
  float lowest = 0.0f;
  for (int j = 0; j < skeleton.size(); ++j) {
    lowest = std::min(lowest, p[static_cast<size_t>(j)].y);
    if (skeleton.joints[static_cast<size_t>(j)].has_end_site) lowest = std::min(lowest, end_site_position(skeleton, j, p, q).y);
  }
  return lowest;
}

// Height of the ankle above the sole with the foot flat (the rest pose): above the toe tip.
float ankle_above_sole(const Skeleton& skeleton, const LegChain& leg, const std::vector<glm::vec3>& p,
                       const std::vector<glm::quat>& q) {
  const int tip = leg.toe_tip_joint;
  if (tip < 0 || !skeleton.joints[static_cast<size_t>(tip)].has_end_site) return 0.0f;
  return std::max(0.0f, p[static_cast<size_t>(leg.ankle)].y - end_site_position(skeleton, tip, p, q).y);
}

}  // namespace

LegMeasures leg_measures(const Skeleton& skeleton) {
  LegMeasures m;
  std::vector<glm::vec3> p;
  std::vector<glm::quat> q;
  forward_kinematics(skeleton, Pose(skeleton.size()), p, &q);
  try {
    const BodyMap body = BodyMap::detect(skeleton);
    for (const LegChain& leg : body.legs) {
      const float thigh = glm::length(p[static_cast<size_t>(leg.knee)] - p[static_cast<size_t>(leg.hip)]);
      const float shin = glm::length(p[static_cast<size_t>(leg.ankle)] - p[static_cast<size_t>(leg.knee)]);
      m.leg_length += 0.5f * (thigh + shin);
      // Legs straight down under the hips, foot flat: however the rest pose splays the legs.
      m.standing_root_height += 0.5f * (p[0].y - p[static_cast<size_t>(leg.hip)].y + thigh + shin + ankle_above_sole(skeleton, leg, p, q));
    }
    if (m.leg_length > 0.0f && m.standing_root_height > 0.0f) return m;
  } catch (const std::invalid_argument&) {
    // Not a recognisable humanoid: fall back on the rest pose's extent.
  }
  m.standing_root_height = -lowest_rest_point(skeleton);
  m.leg_length = m.standing_root_height;
  return m;
}

namespace {

bool is_descendant(const Skeleton& sk, int joint, int ancestor) {
  for (int a = sk.joints[static_cast<size_t>(joint)].parent; a >= 0; a = sk.joints[static_cast<size_t>(a)].parent)
    if (a == ancestor) return true;
  return false;
}

// Where a joint's bone points when it has no mapped child: its End Site, or the End Site at the end of a
// single-child chain. Returns false when the tip is ambiguous (several children, no End Site).
bool clean_tip(const Skeleton& sk, const std::vector<glm::vec3>& p, int joint, glm::vec3& tip) {
  int j = joint;
  for (;;) {
    const Joint& jt = sk.joints[static_cast<size_t>(j)];
    if (jt.has_end_site) {
      tip = p[static_cast<size_t>(j)] + jt.end_site;  // rest rotations are the identity
      return true;
    }
    int only = -1, count = 0;
    for (int c = j + 1; c < sk.size(); ++c)
      if (sk.joints[static_cast<size_t>(c)].parent == j) {
        only = c;
        ++count;
      }
    if (count != 1) return false;
    j = only;
  }
}

// The rotation turning direction a onto direction b (the shortest arc).
glm::quat rotation_between(const glm::vec3& a, const glm::vec3& b) {
  const glm::vec3 u = glm::normalize(a), v = glm::normalize(b);
  const float d = glm::dot(u, v);
  if (d > 1.0f - 1e-7f) return glm::quat(1, 0, 0, 0);
  if (d < -1.0f + 1e-7f) {
    glm::vec3 axis = glm::cross(u, glm::vec3(1, 0, 0));
    if (glm::length(axis) < 1e-3f) axis = glm::cross(u, glm::vec3(0, 1, 0));
    return glm::angleAxis(3.14159265f, glm::normalize(axis));
  }
  return glm::normalize(glm::quat(1.0f + d, glm::cross(u, v)));
}

// The unit quaternion R maximizing sum_i dot(s_i, R t_i) for unit directions (Horn's closed form: the
// eigenvector of the largest eigenvalue of a symmetric 4x4 matrix, found by power iteration after a
// shift that makes every eigenvalue non-negative).
glm::quat best_rotation(const std::vector<glm::vec3>& t, const std::vector<glm::vec3>& s) {
  double S[3][3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
  for (size_t i = 0; i < t.size(); ++i) {
    const glm::dvec3 a = glm::normalize(glm::dvec3(t[i])), b = glm::normalize(glm::dvec3(s[i]));
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) S[r][c] += a[r] * b[c];
  }
  const double xx = S[0][0], xy = S[0][1], xz = S[0][2], yx = S[1][0], yy = S[1][1], yz = S[1][2], zx = S[2][0],
               zy = S[2][1], zz = S[2][2];
  const double shift = static_cast<double>(t.size());
  const double N[4][4] = {{xx + yy + zz + shift, yz - zy, zx - xz, xy - yx},
                          {yz - zy, xx - yy - zz + shift, xy + yx, zx + xz},
                          {zx - xz, xy + yx, -xx + yy - zz + shift, yz + zy},
                          {xy - yx, zx + xz, yz + zy, -xx - yy + zz + shift}};
  double q[4] = {1.0, 0.1, 0.1, 0.1};
  for (int it = 0; it < 500; ++it) {
    double next[4] = {0, 0, 0, 0};
    for (int r = 0; r < 4; ++r)
      for (int c = 0; c < 4; ++c) next[r] += N[r][c] * q[c];
    const double len = std::sqrt(next[0] * next[0] + next[1] * next[1] + next[2] * next[2] + next[3] * next[3]);
    if (!(len > 0.0)) break;
    for (int r = 0; r < 4; ++r) q[r] = next[r] / len;
  }
  return glm::normalize(glm::quat(static_cast<float>(q[0]), static_cast<float>(q[1]), static_cast<float>(q[2]), static_cast<float>(q[3])));
}

}  // namespace

Retargeter::Retargeter(std::shared_ptr<const Skeleton> source, std::shared_ptr<const Skeleton> target, const JointMap& map)
    : source_(std::move(source)), target_(std::move(target)) {
  const Skeleton& S = *source_;
  const Skeleton& T = *target_;
  source_of_.assign(static_cast<size_t>(T.size()), -1);
  for (const auto& [theirs, ours] : map.pairs) {
    const int s = find_joint_loosely(S, theirs);
    const int t = find_joint_loosely(T, ours);
    if (s >= 0 && t >= 0 && source_of_[static_cast<size_t>(t)] < 0) source_of_[static_cast<size_t>(t)] = s;
  }
  if (source_of_[0] != 0)
    throw std::invalid_argument("retarget (" + map.name + "): the map does not take the source root \"" + S.joints[0].name +
                                "\" to the target root \"" + T.joints[0].name + "\"");
  std::vector<glm::vec3> ps, pt;
  forward_kinematics(S, Pose(S.size()), ps);
  forward_kinematics(T, Pose(T.size()), pt);
  alignment_.assign(static_cast<size_t>(T.size()), glm::quat(1, 0, 0, 0));
  std::set<int> target_feet;  // ankles and toes of the target
  std::vector<std::array<int, 4>> target_legs;  // hip, knee, ankle, toe-tip joint
  std::map<int, int> source_toe_tip;            // source ankle -> its toe-tip joint
  try {
    const BodyMap body = BodyMap::detect(T);
    for (const LegChain& leg : body.legs) {
      target_feet.insert(leg.ankle);
      if (leg.toe >= 0) target_feet.insert(leg.toe);
      target_legs.push_back({leg.hip, leg.knee, leg.ankle, leg.toe_tip_joint});
    }
    const BodyMap source_body = BodyMap::detect(S);
    for (const LegChain& leg : source_body.legs)
      if (leg.toe_tip_joint >= 0 && S.joints[static_cast<size_t>(leg.toe_tip_joint)].has_end_site)
        source_toe_tip[leg.ankle] = leg.toe_tip_joint;
  } catch (const std::invalid_argument&) {
    // Not recognisably a humanoid: every bone is aligned by its directions.
  }
  for (int k = 0; k < T.size(); ++k) {
    const int j = source_of_[static_cast<size_t>(k)];
    if (j < 0) continue;
    // Directions to the nearest mapped descendants (in both skeletons).
    std::vector<glm::vec3> dt, ds;
    for (int k2 = k + 1; k2 < T.size(); ++k2) {
      const int j2 = source_of_[static_cast<size_t>(k2)];
      if (j2 < 0 || !is_descendant(T, k2, k) || !is_descendant(S, j2, j)) continue;
      bool nearest = true;
      for (int a = T.joints[static_cast<size_t>(k2)].parent; a != k; a = T.joints[static_cast<size_t>(a)].parent)
        if (source_of_[static_cast<size_t>(a)] >= 0) nearest = false;
      if (!nearest) continue;
      const glm::vec3 a = pt[static_cast<size_t>(k2)] - pt[static_cast<size_t>(k)];
      const glm::vec3 b = ps[static_cast<size_t>(j2)] - ps[static_cast<size_t>(j)];
      if (glm::length(a) < 1e-5f || glm::length(b) < 1e-5f) continue;
      dt.push_back(a);
      ds.push_back(b);
    }
    if (dt.empty()) {
      glm::vec3 tip_t, tip_s;
      if (clean_tip(T, pt, k, tip_t) && clean_tip(S, ps, j, tip_s)) {
        const glm::vec3 a = tip_t - pt[static_cast<size_t>(k)], b = tip_s - ps[static_cast<size_t>(j)];
        if (glm::length(a) > 1e-5f && glm::length(b) > 1e-5f) {
          dt.push_back(a);
          ds.push_back(b);
        }
      }
    }
    if (dt.empty()) {
      // No direction to align (a hand whose fingers branch, a head with eyes): the bone keeps its rest
      // relation to the nearest mapped ancestor, i.e. it takes that ancestor's alignment.
      for (int a = T.joints[static_cast<size_t>(k)].parent; a >= 0; a = T.joints[static_cast<size_t>(a)].parent)
        if (source_of_[static_cast<size_t>(a)] >= 0) {
          alignment_[static_cast<size_t>(k)] = alignment_[static_cast<size_t>(a)];
          break;
        }
      continue;
    }
    // One direction: the shortest arc. Several: the rotation that best turns all target directions onto
    // the source ones (least squares, Horn 1987), which also fixes the twist. Both are symmetric in the
    // two skeletons, so the alignment from B to A is exactly the inverse of the one from A to B.
    glm::quat a = dt.size() == 1 ? rotation_between(dt[0], ds[0]) : best_rotation(dt, ds);
    if (target_feet.count(k)) {
      // A foot at rest stands flat in every skeleton (toe tips lower or higher relative to the ankle
      // depending on the skeleton's foot), so flat must stay flat: only the heading is aligned.
      const glm::vec3 ht(dt[0].x, 0.0f, dt[0].z), hs(ds[0].x, 0.0f, ds[0].z);
      a = glm::length(ht) > 1e-5f && glm::length(hs) > 1e-5f ? rotation_between(ht, hs) : glm::quat(1, 0, 0, 0);
    }
    alignment_[static_cast<size_t>(k)] = a;
  }
  source_legs_ = leg_measures(S);
  target_legs_ = leg_measures(T);
  if (!(source_legs_.leg_length > 1e-4f) || !(target_legs_.leg_length > 1e-4f))
    throw std::invalid_argument("retarget: a rest pose has no legs below the root");
  root_scale_ = target_legs_.leg_length / source_legs_.leg_length;
  std::vector<glm::quat> qs_rest, qt_rest;
  forward_kinematics(S, Pose(S.size()), ps, &qs_rest);
  forward_kinematics(T, Pose(T.size()), pt, &qt_rest);
  BodyMap source_body, target_body;
  bool bodies = true;
  try {
    source_body = BodyMap::detect(S);
    target_body = BodyMap::detect(T);
  } catch (const std::invalid_argument&) {
    bodies = false;
  }
  // Legs whose hip, knee and ankle form a chain in the target and whose ankle is mapped get foot planting.
  for (const auto& [hip, knee, ankle, toe_tip] : target_legs) {
    if (hip < 0 || knee < 0 || ankle < 0 || T.joints[static_cast<size_t>(knee)].parent != hip ||
        T.joints[static_cast<size_t>(ankle)].parent != knee || source_of_[static_cast<size_t>(ankle)] < 0)
      continue;
    FootPlant leg;
    leg.hip = hip;
    leg.knee = knee;
    leg.ankle = ankle;
    leg.source_ankle = source_of_[static_cast<size_t>(ankle)];
    // Ankle heights above the soles: the source's height above its floor scales like the legs, around
    // the target's own ankle height.
    float ankle_t = 0.0f, ankle_s = 0.0f;
    if (bodies) {
      for (const LegChain& l : target_body.legs)
        if (l.ankle == ankle) ankle_t = ankle_above_sole(T, l, pt, qt_rest);
      for (const LegChain& l : source_body.legs)
        if (l.ankle == leg.source_ankle) ankle_s = ankle_above_sole(S, l, ps, qs_rest);
    }
    leg.height_offset = ankle_t - root_scale_ * ankle_s;
    auto st = source_toe_tip.find(leg.source_ankle);
    if (toe_tip >= 0 && T.joints[static_cast<size_t>(toe_tip)].has_end_site && st != source_toe_tip.end()) {
      leg.toe_tip = toe_tip;
      leg.source_toe_tip = st->second;
      // A toe joint between the ankle and the toe tip lets the foot bend at the ball.
      if (toe_tip != ankle && T.joints[static_cast<size_t>(toe_tip)].parent == ankle) leg.toe = toe_tip;
      for (int k = ankle; k < T.size(); ++k)
        if (k == ankle || is_descendant(T, k, ankle)) leg.foot.push_back(k);
    }
    legs_.push_back(leg);
  }
}

namespace {

// World positions of a skeleton from its root position and world rotations.
void positions_from(const Skeleton& sk, const glm::vec3& root, const std::vector<glm::quat>& world, std::vector<glm::vec3>& p) {
  p.resize(world.size());
  p[0] = root;
  for (size_t k = 1; k < p.size(); ++k) {
    const auto parent = static_cast<size_t>(sk.joints[k].parent);
    p[k] = p[parent] + world[parent] * sk.joints[k].offset;
  }
}

// Two-bone IK in world rotations: joint a rotates the bone to joint b, joint b the bone to the end point
// (b's frame offset `end`). Bends b in its current bending plane (or about `fallback_axis` when straight)
// and swings a, so that the end point reaches `goal` (or points at it when out of reach).
void two_bone(std::vector<glm::quat>& world, const glm::vec3& pa, const glm::vec3& pb, size_t a, size_t b,
              const glm::vec3& b_offset, const glm::vec3& end, const glm::vec3& goal, const glm::vec3& fallback_axis) {
  const float l1 = glm::length(b_offset), l2 = glm::length(end);
  if (l1 < 1e-6f || l2 < 1e-6f) return;
  const glm::vec3 u = pb - pa, v = world[b] * end;
  glm::vec3 axis = glm::cross(u, v);
  if (glm::length(axis) < 1e-4f * l1 * l2) axis = fallback_axis;
  if (glm::length(axis) < 1e-9f) return;
  axis = glm::normalize(axis);
  const float bend_now = std::atan2(glm::length(glm::cross(u, v)), glm::dot(u, v));
  const float reach = std::clamp(glm::length(goal - pa), std::fabs(l1 - l2) + 1e-5f, (l1 + l2) * 0.99999f);
  const float interior = std::acos(std::clamp((l1 * l1 + l2 * l2 - reach * reach) / (2.0f * l1 * l2), -1.0f, 1.0f));
  world[b] = glm::normalize(glm::angleAxis((3.14159265f - interior) - bend_now, axis) * world[b]);
  const glm::vec3 tip = pb + world[b] * end;
  const glm::quat swing = rotation_between(tip - pa, goal - pa);
  world[a] = glm::normalize(swing * world[a]);
  world[b] = glm::normalize(swing * world[b]);
}

}  // namespace

void Retargeter::retarget(const Pose& source_pose, Pose& target_pose) const {
  const Skeleton& S = *source_;
  const Skeleton& T = *target_;
  thread_local std::vector<glm::vec3> ps, pt;
  thread_local std::vector<glm::quat> qs, qt;
  forward_kinematics(S, source_pose, ps, &qs);
  const auto n = static_cast<size_t>(T.size());
  qt.resize(n);
  // World rotations: the source's world-space rotation away from its rest pose, times the alignment.
  for (size_t k = 0; k < n; ++k) {
    const int j = source_of_[k];
    const int parent = T.joints[k].parent;
    if (j >= 0) qt[k] = glm::normalize(qs[static_cast<size_t>(j)] * alignment_[k]);
    else qt[k] = parent >= 0 ? qt[static_cast<size_t>(parent)] : glm::quat(1, 0, 0, 0);
  }
  // Root: horizontal travel scales with leg length; the height too, as a deviation from standing.
  const glm::vec3 r = source_pose.root_position;
  target_pose.root_position = glm::vec3(r.x * root_scale_,
                                        target_legs_.standing_root_height + (r.y - source_legs_.standing_root_height) * root_scale_,
                                        r.z * root_scale_);
  // Feet: the ankle goes where the source's ankle is, scaled like the root (two-bone IK on hip and knee),
  // so that heel heights, contact timing and planted feet carry over despite other leg proportions.
  for (const FootPlant& leg : legs_) {
    positions_from(T, target_pose.root_position, qt, pt);
    const auto hip = static_cast<size_t>(leg.hip), knee = static_cast<size_t>(leg.knee), ankle = static_cast<size_t>(leg.ankle);
    const glm::vec3 goal = ps[static_cast<size_t>(leg.source_ankle)] * root_scale_ + glm::vec3(0.0f, leg.height_offset, 0.0f);
    const glm::quat ankle_world = qt[ankle];
    // A straight knee bends forwards (the shin swings back): about the axis forward x thigh.
    const glm::vec3 thigh = pt[knee] - pt[hip];
    two_bone(qt, pt[hip], pt[knee], hip, knee, T.joints[knee].offset, T.joints[ankle].offset, goal,
             glm::cross(ankle_world * glm::vec3(0, 0, 1), thigh));
    qt[ankle] = ankle_world;  // the foot keeps its transferred orientation ...
    if (leg.toe_tip < 0) continue;
    positions_from(T, target_pose.root_position, qt, pt);
    const auto tip = static_cast<size_t>(leg.toe_tip);
    const auto stip = static_cast<size_t>(leg.source_toe_tip);
    const glm::vec3 toe_goal = (ps[stip] + qs[stip] * S.joints[stip].end_site) * root_scale_;
    if (leg.toe >= 0) {
      // ... and with a toe joint, the foot bends at the ball so that the toe tip lands on the source's
      // (scaled) toe tip: heel and toes both stay where the source's are, even for feet of other shapes.
      const auto toe = static_cast<size_t>(leg.toe);
      two_bone(qt, pt[ankle], pt[toe], ankle, toe, T.joints[toe].offset, T.joints[tip].end_site, toe_goal,
               glm::cross(pt[toe] - pt[ankle], glm::vec3(0, 1, 0)));
    } else {
      // ... or, without one, turns about the ankle so that the toe tip points at the source's toe tip.
      const glm::vec3 toe_now = pt[tip] + qt[tip] * T.joints[tip].end_site;
      const glm::quat turn = rotation_between(toe_now - pt[ankle], toe_goal - pt[ankle]);
      for (int k : leg.foot) qt[static_cast<size_t>(k)] = glm::normalize(turn * qt[static_cast<size_t>(k)]);
    }
  }
  target_pose.rotations.resize(n);
  for (size_t k = 0; k < n; ++k) {
    const int parent = T.joints[k].parent;
    target_pose.rotations[k] = parent >= 0 ? glm::normalize(glm::conjugate(qt[static_cast<size_t>(parent)]) * qt[k]) : qt[k];
  }
}

Clip Retargeter::retarget(const Clip& clip) const {
  Clip out;
  out.name = clip.name;
  out.skeleton = target_;
  out.fps = clip.fps;
  out.frames.resize(clip.frames.size());
  for (size_t f = 0; f < clip.frames.size(); ++f) retarget(clip.frames[f], out.frames[f]);
  make_hemisphere_continuous(out);
  return out;
}

}  // namespace prep
