#include "engine/synthesis/balance.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "engine/motion/kinematics.h"
#include "engine/motion/quaternion_ops.h"
#include "engine/motion/vector_ops.h"

namespace prep {
namespace {

// |x| smoothed near 0 (BalanceParams::norm_smoothing) so that C is differentiable where a term vanishes,
// e.g. the style term at the start of the optimization.
inline float smooth_norm(float squared, float e) { return std::sqrt(squared + e * e) - e; }

// A body part's centroid: c = (1 - f) * proximal + f * distal, computed as p + f (distal - p).
// (Raw pointers: the loops calling it store through SSE2 stores, which may alias anything, so a vector's
// address would be read again after each one.)
inline V3 centroid_of(const Joint* joints, const BalanceModel::Part& part, const glm::vec3* positions,
                      const glm::quat* rotations) {
  const size_t d = static_cast<size_t>(part.distal);
  const V3 p = V3::load(positions[static_cast<size_t>(part.proximal)]);
  const V3 distal = part.distal_is_end_site
                        ? V3::load(positions[d]) + rotate(rotations[d], V3::load(joints[d].end_site))
                        : V3::load(positions[d]);
  return p + part.f * (distal - p);
}

// Eq. 7's and Eq. 8-9's terms of one part (before the weights and the 1/n).
inline float style_term(V3 centroid, const glm::vec3& style, float e) {
  const V3 st = centroid - V3::load(style);
  return smooth_norm(dot(st, st), e);
}
inline V3 acceleration(V3 centroid, const glm::vec3& previous, const glm::vec3& before_previous) {
  return centroid - 2.0f * V3::load(previous) + V3::load(before_previous);
}

}  // namespace

void BalanceScratch::resize(int joints, int parts) {
  const size_t n = static_cast<size_t>(joints), m = static_cast<size_t>(parts);
  for (auto* v : {&positions, &trial_positions, &joint_point_gradient, &end_point_gradient, &subtree_force,
                  &subtree_torque, &joint_gradient, &subtree_moment, &angular, &linear}) {
    v->resize(n);
  }
  subtree_mass.resize(n);
  rotations.resize(n);
  trial_rotations.resize(n);
  for (auto* v : {&centroids, &trial_centroids, &start_centroids, &style, &part_gradient}) v->resize(m);
  smooth_term.resize(m);
  for (auto* v : {&base, &local, &trial_local, &offset, &step_rotation}) v->resize(static_cast<size_t>(kMaxOptimizedJoints));
}

BalanceModel BalanceModel::build(const Skeleton& skeleton, const BodyMap& body, const MassModel& mass) {
  BalanceModel model;
  float total = 0.0f;
  for (const BodySegment& s : mass.segments) total += s.mass_fraction;
  if (!(total > 0.0f)) throw std::invalid_argument("balance: the mass model has no mass");
  for (const BodySegment& s : mass.segments) {
    if (s.proximal < 0 || s.proximal >= skeleton.size() || s.distal < 0 || s.distal >= skeleton.size()) {
      throw std::invalid_argument("balance: segment \"" + s.name + "\" names no joint of the skeleton");
    }
    model.parts.push_back({s.proximal, s.distal, s.distal_is_end_site, s.com_fraction, s.mass_fraction / total});
  }
  const size_t n = static_cast<size_t>(skeleton.size());
  model.joint_mass.assign(n, 0.0f);
  model.end_mass.assign(n, 0.0f);
  // Which joints the mass table reads: a part's proximal and distal joints (an End Site also needs its
  // joint's rotation).
  std::vector<char> read(n, 0), end_read(n, 0);
  for (const Part& part : model.parts) {
    model.joint_mass[static_cast<size_t>(part.proximal)] += part.mass * (1.0f - part.f);
    (part.distal_is_end_site ? model.end_mass : model.joint_mass)[static_cast<size_t>(part.distal)] += part.mass * part.f;
    read[static_cast<size_t>(part.proximal)] = 1;
    (part.distal_is_end_site ? end_read : read)[static_cast<size_t>(part.distal)] = 1;
  }
  // carries[j]: a rotation at j moves a point the mass table reads (a read joint strictly below j, or j's
  // read End Site). needed[j]: j lies on the way to such a point (j itself read, or carries).
  std::vector<char> carries(n, 0), needed(n, 0);
  for (size_t j = n; j-- > 0;) {
    carries[j] = carries[j] || end_read[j];
    needed[j] = carries[j] || read[j];
    const int parent = skeleton.joints[j].parent;
    if (parent >= 0 && needed[j]) carries[static_cast<size_t>(parent)] = 1;
  }
  model.end_point.assign(end_read.begin(), end_read.end());
  model.optimized_index.assign(n, -1);
  for (size_t j = 0; j < n; ++j) {
    if (j < body.upper_body.size() && body.upper_body[j] && carries[j]) {
      model.optimized_index[j] = static_cast<int>(model.optimized.size());
      model.optimized.push_back(static_cast<int>(j));
    }
  }
  if (model.optimized.size() > static_cast<size_t>(kMaxOptimizedJoints)) {
    throw std::invalid_argument("balance: " + std::to_string(model.optimized.size()) +
                                " upper-body joints to optimize, more than kMaxOptimizedJoints (" +
                                std::to_string(kMaxOptimizedJoints) + ")");
  }
  // Moved joints: below an optimized joint (or one itself) and needed.
  std::vector<char> moved(n, 0);
  model.is_moved.assign(n, 0);
  for (size_t j = 0; j < n; ++j) {
    const int parent = skeleton.joints[j].parent;
    const bool below = model.optimized_index[j] >= 0 || (parent >= 0 && moved[static_cast<size_t>(parent)]);
    moved[j] = below;
    if (below && needed[j]) {
      model.moved.push_back(static_cast<int>(j));
      model.is_moved[j] = 1;
    }
  }
  model.moved = breadth_first(skeleton, model.moved);
  for (size_t i = 0; i < model.parts.size(); ++i) {
    const Part& part = model.parts[i];
    // A part moves if either of its points does: the distal point when its joint is moved (an End Site
    // turns with its joint's rotation), the proximal one likewise, except that an optimized joint's own
    // position does not move when it turns (but its End Site does).
    const auto point_moves = [&](int j, bool end_site) {
      const size_t jj = static_cast<size_t>(j);
      if (!model.is_moved[jj]) return false;
      if (end_site) return true;
      const int parent = skeleton.joints[jj].parent;
      return parent >= 0 && model.is_moved[static_cast<size_t>(parent)];
    };
    if (point_moves(part.proximal, false) || point_moves(part.distal, part.distal_is_end_site)) {
      model.moved_parts.push_back(static_cast<int>(i));
    }
  }
  return model;
}

void part_centroids(const Skeleton& skeleton, const BalanceModel& model, const std::vector<glm::vec3>& positions,
                    const std::vector<glm::quat>& rotations, glm::vec3* out) {
  const Joint* const joints = skeleton.joints.data();
  const BalanceModel::Part* const parts = model.parts.data();
  const glm::vec3* const p = positions.data();
  const glm::quat* const r = rotations.data();
  for (size_t i = 0, n = model.parts.size(); i < n; ++i) centroid_of(joints, parts[i], p, r).store(out[i]);
}

glm::vec3 model_center_of_mass(const BalanceModel& model, const glm::vec3* centroids) {
  V3 com = V3::zero();
  for (size_t i = 0; i < model.parts.size(); ++i) com += model.parts[i].mass * V3::load(centroids[i]);
  return com.vec();
}

namespace {

// balance_cost, also writing each part's smoothness term (Eq. 8-9, after the 1/n) to smooth_terms when
// given (and the targets have a history).
BalanceCost balance_cost_with_terms(const BalanceModel& model, const BalanceParams& params, const BalanceTargets& targets,
                                    const glm::vec3* centroids, float* smooth_terms) {
  const float e = params.norm_smoothing;
  const size_t n = model.parts.size();
  const float inv_n = 1.0f / static_cast<float>(n);
  BalanceCost cost;
  const glm::vec3 com = model_center_of_mass(model, centroids);
  const glm::vec2 d(com.x - targets.support_centre.x, com.z - targets.support_centre.y);
  const float d2 = glm::dot(d, d);
  cost.com = com;
  cost.com_distance = std::sqrt(d2);
  cost.balance = smooth_norm(d2, e);  // Eq. 6
  if (centroids == targets.style) {
    // At the style targets themselves (where the optimizer starts) every distance of Eq. 7 is zero and
    // every term the same number: one square root instead of one per part.
    const float at_target = smooth_norm(0.0f, e) * inv_n;
    for (size_t i = 0; i < n; ++i) cost.style += at_target;
  } else {
    for (size_t i = 0; i < n; ++i) cost.style += style_term(V3::load(centroids[i]), targets.style[i], e) * inv_n;  // Eq. 7
  }
  if (targets.previous && targets.before_previous) {
    for (size_t i = 0; i < n; ++i) {
      const V3 a = acceleration(V3::load(centroids[i]), targets.previous[i], targets.before_previous[i]);
      const float term = smooth_norm(dot(a, a), e) * inv_n;  // Eq. 8-9
      cost.smooth += term;
      if (smooth_terms) smooth_terms[i] = term;
    }
  }
  cost.total = params.w_b * cost.balance + params.w_s * cost.style + params.w_m * cost.smooth;  // Eq. 10
  return cost;
}

}  // namespace

BalanceCost balance_cost(const BalanceModel& model, const BalanceParams& params, const BalanceTargets& targets,
                         const glm::vec3* centroids) {
  return balance_cost_with_terms(model, params, targets, centroids, nullptr);
}

void balance_gradient(const Skeleton& skeleton, const BalanceModel& model, const BalanceParams& params,
                      const BalanceTargets& targets, BalanceScratch& s) {
  const float e = params.norm_smoothing;
  const size_t n_parts = model.parts.size();
  const float inv_n = 1.0f / static_cast<float>(n_parts);
  const glm::vec3* c = s.centroids.data();

  // dC/d(centroid i).
  const glm::vec3 com = model_center_of_mass(model, c);
  const glm::vec2 d(com.x - targets.support_centre.x, com.z - targets.support_centre.y);
  const glm::vec2 u = d / std::sqrt(glm::dot(d, d) + e * e);
  const glm::vec3 balance_dir = params.w_b * glm::vec3(u.x, 0.0f, u.y);
  const bool has_history = targets.previous && targets.before_previous;
  for (size_t i = 0; i < n_parts; ++i) {
    glm::vec3 g = model.parts[i].mass * balance_dir;
    const glm::vec3 st = c[i] - targets.style[i];
    g += (params.w_s * inv_n / std::sqrt(glm::dot(st, st) + e * e)) * st;
    if (has_history) {
      const glm::vec3 a = c[i] - 2.0f * targets.previous[i] + targets.before_previous[i];
      g += (params.w_m * inv_n / std::sqrt(glm::dot(a, a) + e * e)) * a;
    }
    s.part_gradient[i] = g;
  }

  // Spread onto the two points each centroid mixes.
  const size_t n = static_cast<size_t>(skeleton.size());
  std::fill(s.joint_point_gradient.begin(), s.joint_point_gradient.end(), glm::vec3(0.0f));
  std::fill(s.end_point_gradient.begin(), s.end_point_gradient.end(), glm::vec3(0.0f));
  for (size_t i = 0; i < n_parts; ++i) {
    const BalanceModel::Part& part = model.parts[i];
    s.joint_point_gradient[static_cast<size_t>(part.proximal)] += (1.0f - part.f) * s.part_gradient[i];
    (part.distal_is_end_site ? s.end_point_gradient : s.joint_point_gradient)[static_cast<size_t>(part.distal)] +=
        part.f * s.part_gradient[i];
  }

  // One backward pass (children come after their parents in the joint order).
  for (size_t j = 0; j < n; ++j) {
    const glm::vec3 ge = s.end_point_gradient[j];
    const glm::vec3 end = s.positions[j] + quat::rotate(s.rotations[j], skeleton.joints[j].end_site);
    s.subtree_force[j] = ge;
    s.subtree_torque[j] = glm::cross(end, ge);
    s.subtree_mass[j] = model.end_mass[j];
    s.subtree_moment[j] = model.end_mass[j] * end;
  }
  for (size_t j = n; j-- > 0;) {
    const glm::vec3 x = s.positions[j];
    // Points moved by a rotation at j: its End Site and everything below it, not its own origin.
    s.joint_gradient[j] = s.subtree_torque[j] - glm::cross(x, s.subtree_force[j]);
    // The COM weight below j (for com_response) is read before j's own position joins it, like the gradient.
    s.subtree_moment[j] -= s.subtree_mass[j] * x;  // now Q_j - M_j x_j
    const glm::vec3 gj = s.joint_point_gradient[j];
    const glm::vec3 lever = s.subtree_moment[j];
    s.subtree_force[j] += gj;
    s.subtree_torque[j] += glm::cross(x, gj);
    const int parent = skeleton.joints[j].parent;
    if (parent >= 0) {
      const size_t p = static_cast<size_t>(parent);
      s.subtree_force[p] += s.subtree_force[j];
      s.subtree_torque[p] += s.subtree_torque[j];
      const float mass_here = s.subtree_mass[j] + model.joint_mass[j];
      s.subtree_mass[p] += mass_here;
      s.subtree_moment[p] += lever + mass_here * x;  // back to a plain weighted sum for the parent
    }
  }
}

glm::vec3 com_response(const BalanceModel& model, const BalanceScratch& s) {
  V3 v = V3::zero();
  for (int j : model.optimized) {
    const size_t jj = static_cast<size_t>(j);
    v += cross(-V3::load(s.joint_gradient[jj]), V3::load(s.subtree_moment[jj]));
  }
  return v.vec();
}

namespace {

// Forward kinematics of the moved joints only (the rest of `positions` / `rotations` is the posture's and
// does not change), with the optimized joints' local rotations taken from `local`.
void moved_kinematics(const Skeleton& skeleton, const BalanceModel& model, const Pose& pose, const glm::quat* local,
                      std::vector<glm::vec3>& positions, std::vector<glm::quat>& rotations) {
  // The addresses held in locals: place_joint's SSE2 stores may alias anything (centroid_of).
  const Joint* const joints = skeleton.joints.data();
  const int* const optimized_index = model.optimized_index.data();
  const glm::quat* const blended = pose.rotations.data();
  glm::vec3* const x = positions.data();
  glm::quat* const r = rotations.data();
  for (int j : model.moved) {
    const size_t jj = static_cast<size_t>(j);
    const Joint& joint = joints[jj];
    const size_t p = static_cast<size_t>(joint.parent);  // never the root: the root is not upper body
    const int k = optimized_index[jj];
    const glm::quat& q = k >= 0 ? local[static_cast<size_t>(k)] : blended[jj];
    place_joint(x[p], r[p], joint.offset, q, x[jj], r[jj]);
  }
}

void moved_centroids(const Skeleton& skeleton, const BalanceModel& model, const std::vector<glm::vec3>& positions,
                     const std::vector<glm::quat>& rotations, glm::vec3* out) {
  const Joint* const joints = skeleton.joints.data();
  const BalanceModel::Part* const parts = model.parts.data();
  const glm::vec3* const p = positions.data();
  const glm::quat* const r = rotations.data();
  for (int i : model.moved_parts) centroid_of(joints, parts[static_cast<size_t>(i)], p, r).store(out[i]);
}

// The COM from the parts that never move (fixed_com, their weighted sum) and the moved parts.
inline glm::vec3 moved_com(const BalanceModel& model, const glm::vec3& fixed_com, const glm::vec3* centroids) {
  V3 com = V3::load(fixed_com);
  for (int i : model.moved_parts) com += model.parts[static_cast<size_t>(i)].mass * V3::load(centroids[static_cast<size_t>(i)]);
  return com.vec();
}

// Eq. 6-10 when only the moved parts differ from a posture whose cost over the other parts is `fixed`
// (style, smoothness); the COM takes every part.
BalanceCost moved_cost(const BalanceModel& model, const BalanceParams& params, const BalanceTargets& targets,
                       const glm::vec3* centroids, const BalanceCost& fixed, const glm::vec3& fixed_com) {
  const float e = params.norm_smoothing;
  const float inv_n = 1.0f / static_cast<float>(model.parts.size());
  BalanceCost cost;
  const glm::vec3 com = moved_com(model, fixed_com, centroids);
  const glm::vec2 d(com.x - targets.support_centre.x, com.z - targets.support_centre.y);
  const float d2 = glm::dot(d, d);
  cost.com = com;
  cost.com_distance = std::sqrt(d2);
  cost.balance = smooth_norm(d2, e);  // Eq. 6
  cost.style = fixed.style;
  cost.smooth = fixed.smooth;
  const bool history = targets.previous && targets.before_previous;
  for (int i : model.moved_parts) {
    const size_t ii = static_cast<size_t>(i);
    const V3 centroid = V3::load(centroids[ii]);
    cost.style += style_term(centroid, targets.style[ii], e) * inv_n;  // Eq. 7
    if (history) {
      const V3 acc = acceleration(centroid, targets.previous[ii], targets.before_previous[ii]);
      cost.smooth += smooth_norm(dot(acc, acc), e) * inv_n;  // Eq. 8-9
    }
  }
  cost.total = params.w_b * cost.balance + params.w_s * cost.style + params.w_m * cost.smooth;  // Eq. 10
  return cost;
}

// balance_gradient restricted to what the optimizer reads: the optimized joints' gradients and the
// subtree COM moments com_response uses. Only moved joints and parts enter (the others' points do not move
// with an optimized joint, so they add nothing below it).
void moved_gradient(const Skeleton& skeleton, const BalanceModel& model, const BalanceParams& params,
                    const BalanceTargets& targets, const glm::vec3& com, BalanceScratch& s) {
  const float e = params.norm_smoothing;
  const float inv_n = 1.0f / static_cast<float>(model.parts.size());
  const glm::vec3* c = s.centroids.data();
  const glm::vec2 d(com.x - targets.support_centre.x, com.z - targets.support_centre.y);
  const glm::vec2 u = d / std::sqrt(glm::dot(d, d) + e * e);
  const V3 balance_dir = V3::load(params.w_b * glm::vec3(u.x, 0.0f, u.y));
  const bool history = targets.previous && targets.before_previous;
  // The addresses held in locals: the SSE2 stores below may alias anything (centroid_of).
  const Joint* const joints = skeleton.joints.data();
  const BalanceModel::Part* const parts = model.parts.data();
  const char* const is_moved = model.is_moved.data();
  const char* const end_point = model.end_point.data();
  const float* const end_mass = model.end_mass.data();
  const float* const joint_mass = model.joint_mass.data();
  const glm::vec3* const positions = s.positions.data();
  const glm::quat* const rotations = s.rotations.data();
  glm::vec3* const joint_point_gradient = s.joint_point_gradient.data();
  glm::vec3* const end_point_gradient = s.end_point_gradient.data();
  glm::vec3* const subtree_force = s.subtree_force.data();
  glm::vec3* const subtree_torque = s.subtree_torque.data();
  glm::vec3* const subtree_moment = s.subtree_moment.data();
  float* const subtree_mass = s.subtree_mass.data();
  glm::vec3* const joint_gradient = s.joint_gradient.data();
  for (int j : model.moved) {
    const size_t jj = static_cast<size_t>(j);
    joint_point_gradient[jj] = end_point_gradient[jj] = subtree_force[jj] = subtree_torque[jj] = subtree_moment[jj] =
        glm::vec3(0.0f);
    subtree_mass[jj] = 0.0f;
  }
  for (int i : model.moved_parts) {
    const size_t ii = static_cast<size_t>(i);
    const BalanceModel::Part& part = parts[ii];
    const V3 centroid = V3::load(c[ii]);
    V3 g = part.mass * balance_dir;
    const V3 st = centroid - V3::load(targets.style[ii]);
    g += (params.w_s * inv_n / std::sqrt(dot(st, st) + e * e)) * st;
    if (history) {
      const V3 acc = acceleration(centroid, targets.previous[ii], targets.before_previous[ii]);
      g += (params.w_m * inv_n / std::sqrt(dot(acc, acc) + e * e)) * acc;
    }
    const size_t prox = static_cast<size_t>(part.proximal), dist = static_cast<size_t>(part.distal);
    if (is_moved[prox]) (V3::load(joint_point_gradient[prox]) + (1.0f - part.f) * g).store(joint_point_gradient[prox]);
    if (is_moved[dist]) {
      glm::vec3& point = (part.distal_is_end_site ? end_point_gradient : joint_point_gradient)[dist];
      (V3::load(point) + part.f * g).store(point);
    }
  }
  // One backward pass (children come after their parents): a joint's subtree sums are complete when it is
  // reached; its own End Site joins first, as it turns with the joint.
  const int* const moved = model.moved.data();
  for (size_t m = model.moved.size(); m-- > 0;) {
    const size_t j = static_cast<size_t>(moved[m]);
    const V3 x = V3::load(positions[j]);
    V3 force = V3::load(subtree_force[j]), torque = V3::load(subtree_torque[j]);
    V3 moment = V3::load(subtree_moment[j]);
    float mass = subtree_mass[j];
    if (end_point[j]) {
      const V3 ge = V3::load(end_point_gradient[j]);
      const V3 end = x + rotate(rotations[j], V3::load(joints[j].end_site));
      force += ge;
      torque += cross(end, ge);
      mass += end_mass[j];
      moment += end_mass[j] * end;
    }
    (torque - cross(x, force)).store(joint_gradient[j]);
    moment -= mass * x;  // now Q_j - M_j x_j (for com_response)
    moment.store(subtree_moment[j]);
    const size_t p = static_cast<size_t>(joints[j].parent);
    if (!is_moved[p]) continue;
    const V3 gj = V3::load(joint_point_gradient[j]);
    (V3::load(subtree_force[p]) + (force + gj)).store(subtree_force[p]);
    (V3::load(subtree_torque[p]) + (torque + cross(x, gj))).store(subtree_torque[p]);
    const float mass_here = mass + joint_mass[j];
    subtree_mass[p] += mass_here;
    (V3::load(subtree_moment[p]) + (moment + mass_here * x)).store(subtree_moment[p]);
  }
}

// The rotation by the rotation vector v, for the small v of a descent step: (1, v/2) normalized (first
// order in |v|; the line search judges the step by the true cost, so any such retraction serves, and this
// one needs no trigonometry). Written unnormalized, as one 16-byte store (a normalize reads it whole), for
// quat::normalize_each to finish.
inline void small_rotation_unnormalized(V3 v, glm::quat& out) {
#if defined(__SSE2__)
  // (0.5 v, 1) without leaving the register: halved lane by lane, w set to 1.
  const __m128 half = _mm_mul_ps(v.r, _mm_set1_ps(0.5f));
  const __m128 xyz = _mm_castsi128_ps(_mm_set_epi32(0, -1, -1, -1));
  kinematics_detail::store_quat(out, _mm_or_ps(_mm_and_ps(half, xyz), _mm_set_ps(1.0f, 0.0f, 0.0f, 0.0f)));
#else
  out = glm::quat(1.0f, 0.5f * v.x(), 0.5f * v.y(), 0.5f * v.z());
#endif
}

// The largest first-order speed of a moved part's centroid per unit step along -joint_gradient: a forward
// pass carries each joint frame's angular velocity (the sum of the steps of the optimized joints above it)
// and its origin's linear velocity, and a centroid mixes the velocities of its two points. Used to keep the
// first trial of a line search inside the trust region (one pass instead of wasted trial postures).
float step_motion(const Skeleton& skeleton, const BalanceModel& model, BalanceScratch& s) {
  // The addresses held in locals: the SSE2 stores below may alias anything (centroid_of).
  const Joint* const joints = skeleton.joints.data();
  const char* const is_moved = model.is_moved.data();
  const int* const optimized_index = model.optimized_index.data();
  const glm::vec3* const positions = s.positions.data();
  const glm::quat* const rotations = s.rotations.data();
  const glm::vec3* const joint_gradient = s.joint_gradient.data();
  glm::vec3* const angular = s.angular.data();
  glm::vec3* const linear = s.linear.data();
  for (int j : model.moved) {
    const size_t jj = static_cast<size_t>(j);
    const size_t p = static_cast<size_t>(joints[jj].parent);
    V3 w = V3::zero(), v = V3::zero();
    if (is_moved[p]) {
      w = V3::load(angular[p]);
      v = V3::load(linear[p]) + cross(w, V3::load(positions[jj]) - V3::load(positions[p]));
    }
    if (optimized_index[jj] >= 0) w -= V3::load(joint_gradient[jj]);
    w.store(angular[jj]);
    v.store(linear[jj]);
  }
  const auto point_speed = [&](int j, bool end_site) {
    const size_t jj = static_cast<size_t>(j);
    if (!is_moved[jj]) return V3::zero();
    if (!end_site) return V3::load(linear[jj]);
    return V3::load(linear[jj]) + cross(V3::load(angular[jj]), rotate(rotations[jj], V3::load(joints[jj].end_site)));
  };
  float largest2 = 0.0f;
  for (int i : model.moved_parts) {
    const BalanceModel::Part& part = model.parts[static_cast<size_t>(i)];
    const V3 v = (1.0f - part.f) * point_speed(part.proximal, false) + part.f * point_speed(part.distal, part.distal_is_end_site);
    largest2 = std::max(largest2, dot(v, v));
  }
  return std::sqrt(largest2);
}

// The largest distance between the moved parts' centroids in a and b.
float largest_move(const BalanceModel& model, const glm::vec3* a, const glm::vec3* b) {
  float largest2 = 0.0f;
  for (int i : model.moved_parts) {
    const V3 v = V3::load(a[static_cast<size_t>(i)]) - V3::load(b[static_cast<size_t>(i)]);
    largest2 = std::max(largest2, dot(v, v));
  }
  return std::sqrt(largest2);
}

// largest_move(a, b) and largest_move(a, c) in one pass over a.
void largest_moves(const BalanceModel& model, const glm::vec3* a, const glm::vec3* b, const glm::vec3* c,
                   float& from_b, float& from_c) {
  float largest_b2 = 0.0f, largest_c2 = 0.0f;
  for (int i : model.moved_parts) {
    const V3 x = V3::load(a[static_cast<size_t>(i)]);
    const V3 vb = x - V3::load(b[static_cast<size_t>(i)]), vc = x - V3::load(c[static_cast<size_t>(i)]);
    largest_b2 = std::max(largest_b2, dot(vb, vb));
    largest_c2 = std::max(largest_c2, dot(vc, vc));
  }
  from_b = std::sqrt(largest_b2);
  from_c = std::sqrt(largest_c2);
}

inline float bound_or_infinity(float bound) { return bound > 0.0f ? bound : INFINITY; }

}  // namespace

void optimized_balance_gradient(const Skeleton& skeleton, const BalanceModel& model, const BalanceParams& params,
                                const BalanceTargets& targets, BalanceScratch& scratch) {
  moved_gradient(skeleton, model, params, targets, model_center_of_mass(model, scratch.centroids.data()), scratch);
}

BalanceResult optimize_balance(const Skeleton& skeleton, const BalanceModel& model, const BalanceParams& params,
                               const BalanceTargets& targets, Pose& pose, BalanceScratch& s,
                               BalanceCorrection* memory, float dt, bool kinematics_given) {
  BalanceResult result;
  result.optimized = true;
  const size_t k_count = model.optimized.size();
  if (!kinematics_given) forward_kinematics(skeleton, pose, s.positions, &s.rotations);
  // The posture's centroids are the style targets (Eq. 7's p_i(t) is this very posture).
  std::copy(targets.style, targets.style + model.parts.size(), s.centroids.begin());
  BalanceCost current = balance_cost_with_terms(model, params, targets, targets.style, s.smooth_term.data());
  result.before = current;
  result.after = current;
  // The cost of the parts that never move (their style and smoothness terms stay as they are): the moved
  // parts' terms, as the cost just took them, taken back out.
  BalanceCost fixed = current;
  {
    const float inv_n = 1.0f / static_cast<float>(model.parts.size());
    const float style_at_target = smooth_norm(0.0f, params.norm_smoothing) * inv_n;
    const bool history = targets.previous && targets.before_previous;
    for (int i : model.moved_parts) {
      fixed.style -= style_at_target;  // each part is at its style target
      if (history) fixed.smooth -= s.smooth_term[static_cast<size_t>(i)];
    }
  }
  V3 fixed_com_sum = V3::load(current.com);  // the centroids are the style targets, whose COM the cost took
  for (int i : model.moved_parts) fixed_com_sum -= model.parts[static_cast<size_t>(i)].mass * V3::load(s.centroids[static_cast<size_t>(i)]);
  const glm::vec3 fixed_com = fixed_com_sum.vec();
  for (size_t k = 0; k < k_count; ++k) {
    s.base[k] = pose.rotations[static_cast<size_t>(model.optimized[k])];
    s.local[k] = s.base[k];
  }
  s.trial_positions = s.positions;  // same sizes: no allocation; the joints that never move stay valid
  s.trial_rotations = s.rotations;
  s.trial_centroids = s.centroids;
  const float max_shift = bound_or_infinity(params.max_part_shift);
  const float max_change = bound_or_infinity(params.max_shift_speed) * dt;
  const float before_distance = result.before.com_distance;
  // Within a tenth of the tighter bound of the trust region's edge, stop: steps that small change nothing
  // visible (each step goes 95% of the way to the edge, so one step usually gets there).
  const float tighter = std::min(max_shift, max_change);
  const float edge = std::isfinite(tighter) ? 0.1f * tighter : 1e-6f;

  // How far the centroids are from the blended posture's (`shift`) and from where this frame's descent
  // started (`change`), kept up as the centroids change: the trust region's bounds read them at every step.
  // The blended posture is where both start.
  float shift = 0.0f, change = 0.0f;

  // Warm start from the previous frame's correction, or the largest fraction of it that is acceptable.
  if (params.warm_start && memory && memory->valid) {
    for (size_t k = 0; k < k_count; ++k) s.offset[k] = memory->offset[k];
    for (int attempt = 0; attempt < 3; ++attempt) {
      if (attempt > 0) {  // half of the rotation (same axis, half the angle): normalize(1 + q) for q.w >= 0
        for (size_t k = 0; k < k_count; ++k) {
          s.offset[k] = quat::normalize(s.offset[k].w + 1.0f, s.offset[k].x, s.offset[k].y, s.offset[k].z);
        }
      }
      for (size_t k = 0; k < k_count; ++k) s.trial_local[k] = quat::mul(s.offset[k], s.base[k]);
      quat::normalize_each(s.trial_local.data(), k_count);
      moved_kinematics(skeleton, model, pose, s.trial_local.data(), s.trial_positions, s.trial_rotations);
      moved_centroids(skeleton, model, s.trial_positions, s.trial_rotations, s.trial_centroids.data());
      const BalanceCost c = moved_cost(model, params, targets, s.trial_centroids.data(), fixed, fixed_com);
      if (!(c.total < current.total && c.com_distance <= before_distance)) continue;
      const float trial_shift = largest_move(model, s.trial_centroids.data(), targets.style);
      if (trial_shift <= max_shift) {
        s.local.swap(s.trial_local);
        s.positions.swap(s.trial_positions);
        s.rotations.swap(s.trial_rotations);
        s.centroids.swap(s.trial_centroids);
        current = c;
        shift = trial_shift;
        result.warm_started = true;
        break;
      }
    }
    if (!result.warm_started) {  // the trial buffers hold a rejected posture: back to the blended one
      s.trial_positions = s.positions;
      s.trial_rotations = s.rotations;
      s.trial_centroids = s.centroids;
    }
  }
  s.start_centroids = s.centroids;  // `change` is 0: the descent starts here

  for (int iteration = 0; iteration < params.max_steps; ++iteration) {
    // Room left in the trust region: a step may move a centroid this far from where it is now (by the
    // triangle inequality this keeps both bounds). Checked first: at the edge no gradient is needed.
    const float room = std::min(max_shift - shift, max_change - change);
    if (!(room > edge)) break;  // at the edge of the trust region: what is left is not worth a step
    const glm::vec3 com = moved_com(model, fixed_com, s.centroids.data());
    moved_gradient(skeleton, model, params, targets, com, s);
    // First trial step: where the linearized COM comes closest to the support centre along the descent
    // direction, capped at step_size; then backtracking halves it.
    float step = params.step_size;
    {
      const glm::vec2 d(com.x - targets.support_centre.x, com.z - targets.support_centre.y);
      const glm::vec3 r = com_response(model, s);
      const glm::vec2 v(r.x, r.z);
      const float vv = glm::dot(v, v);
      if (vv > 1e-12f) {
        const float best = -glm::dot(d, v) / vv;
        if (best > 0.0f) step = std::min(best, params.step_size);
      }
    }
    // Keep the first trial inside the trust region: the centroids' first-order motion per unit step (step_motion).
    const float motion = step_motion(skeleton, model, s);
    if (motion * step > room) step = 0.95f * room / motion;
    bool accepted = false;
    BalanceCost trial_cost;
    for (int shortening = 0; shortening <= params.max_halvings; ++shortening) {
      for (size_t k = 0; k < k_count; ++k) {
        const size_t j = static_cast<size_t>(model.optimized[k]);
        const glm::quat& parent_world = s.rotations[static_cast<size_t>(skeleton.joints[j].parent)];
        // A world-frame rotation vector at joint j, expressed in its parent's frame, premultiplies its local rotation.
        small_rotation_unnormalized(rotate_back(parent_world, -step * V3::load(s.joint_gradient[j])), s.step_rotation[k]);
      }
      quat::normalize_each(s.step_rotation.data(), k_count);
      for (size_t k = 0; k < k_count; ++k) s.trial_local[k] = quat::mul(s.step_rotation[k], s.local[k]);
      quat::normalize_each(s.trial_local.data(), k_count);
      moved_kinematics(skeleton, model, pose, s.trial_local.data(), s.trial_positions, s.trial_rotations);
      moved_centroids(skeleton, model, s.trial_positions, s.trial_rotations, s.trial_centroids.data());
      const float moved = largest_move(model, s.trial_centroids.data(), s.centroids.data());
      if (moved > room) {
        // Outside the trust region: shorten the step to (nearly) its edge rather than halving blindly;
        // centroids move about linearly with the step.
        step *= 0.95f * room / moved;
        continue;
      }
      trial_cost = moved_cost(model, params, targets, s.trial_centroids.data(), fixed, fixed_com);
      if (trial_cost.total < current.total && trial_cost.com_distance <= before_distance) {
        accepted = true;
        break;
      }
      step *= 0.5f;  // backtracking
    }
    if (!accepted) break;  // a local optimum (within the trust region): no descent step helps
    const float improvement = current.total - trial_cost.total;
    s.local.swap(s.trial_local);
    s.positions.swap(s.trial_positions);
    s.rotations.swap(s.trial_rotations);
    s.centroids.swap(s.trial_centroids);
    current = trial_cost;
    largest_moves(model, s.centroids.data(), targets.style, s.start_centroids.data(), shift, change);
    ++result.steps;
    if (improvement < params.tolerance) break;
  }
  for (size_t k = 0; k < k_count; ++k) pose.rotations[static_cast<size_t>(model.optimized[k])] = s.local[k];
  if (memory) {
    for (size_t k = 0; k < k_count; ++k) memory->offset[k] = quat::mul_conjugate(s.local[k], s.base[k]);
    quat::normalize_each(memory->offset.data(), k_count);
    for (size_t k = 0; k < k_count; ++k) memory->offset[k] = quat::with_positive_w(memory->offset[k]);
    memory->valid = true;
  }
  result.largest_shift = shift;
  result.after = current;
  return result;
}

}  // namespace prep
