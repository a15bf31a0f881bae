#include "engine/synthesis/balance.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "engine/motion/kinematics.h"

namespace prep {
namespace {

// |x| smoothed near 0 (BalanceParams::norm_smoothing) so that C is differentiable where a term vanishes,
// e.g. the style term at the start of the optimization.
inline float smooth_norm(float squared, float e) { return std::sqrt(squared + e * e) - e; }

// Rotation by the rotation vector v (axis * angle).
inline glm::quat exp_map(glm::vec3 v) {
  const float angle = glm::length(v);
  if (angle < 1e-9f) return glm::quat(1, 0, 0, 0);
  return glm::angleAxis(angle, v / angle);
}

inline glm::vec3 distal_point(const Skeleton& skeleton, const BalanceModel::Part& part,
                              const std::vector<glm::vec3>& positions, const std::vector<glm::quat>& rotations) {
  const size_t d = static_cast<size_t>(part.distal);
  return part.distal_is_end_site ? positions[d] + rotations[d] * skeleton.joints[d].end_site : positions[d];
}

}  // namespace

void BalanceScratch::resize(int joints, int parts) {
  const size_t n = static_cast<size_t>(joints), m = static_cast<size_t>(parts);
  for (auto* v : {&positions, &trial_positions, &joint_point_gradient, &end_point_gradient, &subtree_force,
                  &subtree_torque, &joint_gradient, &subtree_moment}) {
    v->resize(n);
  }
  subtree_mass.resize(n);
  rotations.resize(n);
  trial_rotations.resize(n);
  for (auto* v : {&centroids, &trial_centroids, &part_gradient}) v->resize(m);
  trial.rotations.resize(n);
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
  for (int j = 0; j < skeleton.size(); ++j) {
    if (j < static_cast<int>(body.upper_body.size()) && body.upper_body[static_cast<size_t>(j)]) {
      model.optimized.push_back(j);
    }
  }
  model.joint_mass.assign(static_cast<size_t>(skeleton.size()), 0.0f);
  model.end_mass.assign(static_cast<size_t>(skeleton.size()), 0.0f);
  for (const Part& part : model.parts) {
    model.joint_mass[static_cast<size_t>(part.proximal)] += part.mass * (1.0f - part.f);
    (part.distal_is_end_site ? model.end_mass : model.joint_mass)[static_cast<size_t>(part.distal)] += part.mass * part.f;
  }
  return model;
}

void part_centroids(const Skeleton& skeleton, const BalanceModel& model, const std::vector<glm::vec3>& positions,
                    const std::vector<glm::quat>& rotations, glm::vec3* out) {
  for (size_t i = 0; i < model.parts.size(); ++i) {
    const BalanceModel::Part& part = model.parts[i];
    const glm::vec3 p = positions[static_cast<size_t>(part.proximal)];
    out[i] = p + part.f * (distal_point(skeleton, part, positions, rotations) - p);
  }
}

glm::vec3 model_center_of_mass(const BalanceModel& model, const glm::vec3* centroids) {
  glm::vec3 com(0.0f);
  for (size_t i = 0; i < model.parts.size(); ++i) com += model.parts[i].mass * centroids[i];
  return com;
}

BalanceCost balance_cost(const BalanceModel& model, const BalanceParams& params, const BalanceTargets& targets,
                         const glm::vec3* centroids) {
  const float e = params.norm_smoothing;
  const size_t n = model.parts.size();
  const float inv_n = 1.0f / static_cast<float>(n);
  BalanceCost cost;
  const glm::vec3 com = model_center_of_mass(model, centroids);
  const glm::vec2 d(com.x - targets.support_centre.x, com.z - targets.support_centre.y);
  const float d2 = glm::dot(d, d);
  cost.com_distance = std::sqrt(d2);
  cost.balance = smooth_norm(d2, e);  // Eq. 6
  for (size_t i = 0; i < n; ++i) {
    const glm::vec3 s = centroids[i] - targets.style[i];
    cost.style += smooth_norm(glm::dot(s, s), e) * inv_n;  // Eq. 7
  }
  if (targets.previous && targets.before_previous) {
    for (size_t i = 0; i < n; ++i) {
      const glm::vec3 a = centroids[i] - 2.0f * targets.previous[i] + targets.before_previous[i];
      cost.smooth += smooth_norm(glm::dot(a, a), e) * inv_n;  // Eq. 8-9
    }
  }
  cost.total = params.w_b * cost.balance + params.w_s * cost.style + params.w_m * cost.smooth;  // Eq. 10
  return cost;
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
    const glm::vec3 end = s.positions[j] + s.rotations[j] * skeleton.joints[j].end_site;
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
  glm::vec3 v(0.0f);
  for (int j : model.optimized) {
    const size_t jj = static_cast<size_t>(j);
    v += glm::cross(-s.joint_gradient[jj], s.subtree_moment[jj]);
  }
  return v;
}

BalanceResult optimize_balance(const Skeleton& skeleton, const BalanceModel& model, const BalanceParams& params,
                               const BalanceTargets& targets, Pose& pose, BalanceScratch& s) {
  BalanceResult result;
  forward_kinematics(skeleton, pose, s.positions, &s.rotations);
  part_centroids(skeleton, model, s.positions, s.rotations, s.centroids.data());
  BalanceCost current = balance_cost(model, params, targets, s.centroids.data());
  result.before = current;
  result.after = current;
  result.optimized = true;

  s.trial.root_position = pose.root_position;
  for (int iteration = 0; iteration < params.max_steps; ++iteration) {
    balance_gradient(skeleton, model, params, targets, s);
    // First trial step: where the linearized COM comes closest to the support centre along the descent
    // direction, capped at step_size; then backtracking halves it.
    float step = params.step_size;
    {
      const glm::vec3 com = model_center_of_mass(model, s.centroids.data());
      const glm::vec2 d(com.x - targets.support_centre.x, com.z - targets.support_centre.y);
      const glm::vec3 r = com_response(model, s);
      const glm::vec2 v(r.x, r.z);
      const float vv = glm::dot(v, v);
      if (vv > 1e-12f) {
        const float best = -glm::dot(d, v) / vv;
        if (best > 0.0f) step = std::min(best, params.step_size);
      }
    }
    bool accepted = false;
    BalanceCost trial_cost;
    for (int halving = 0; halving <= params.max_halvings; ++halving, step *= 0.5f) {
      s.trial.rotations = pose.rotations;  // same size: no allocation
      for (int j : model.optimized) {
        const size_t jj = static_cast<size_t>(j);
        const int parent = skeleton.joints[jj].parent;
        const glm::quat parent_world = parent >= 0 ? s.rotations[static_cast<size_t>(parent)] : glm::quat(1, 0, 0, 0);
        // A world-frame rotation vector at joint j, expressed in its parent's frame, premultiplies its local rotation.
        const glm::vec3 delta = glm::inverse(parent_world) * (-step * s.joint_gradient[jj]);
        s.trial.rotations[jj] = glm::normalize(exp_map(delta) * pose.rotations[jj]);
      }
      forward_kinematics(skeleton, s.trial, s.trial_positions, &s.trial_rotations);
      part_centroids(skeleton, model, s.trial_positions, s.trial_rotations, s.trial_centroids.data());
      trial_cost = balance_cost(model, params, targets, s.trial_centroids.data());
      if (trial_cost.total < current.total && trial_cost.com_distance <= result.before.com_distance) {
        accepted = true;
        break;
      }
    }
    if (!accepted) break;  // a local optimum: no descent step helps
    const float improvement = current.total - trial_cost.total;
    pose.rotations.swap(s.trial.rotations);
    s.positions.swap(s.trial_positions);
    s.rotations.swap(s.trial_rotations);
    s.centroids.swap(s.trial_centroids);
    current = trial_cost;
    ++result.steps;
    if (improvement < params.tolerance) break;
  }
  result.after = current;
  return result;
}

}  // namespace prep
