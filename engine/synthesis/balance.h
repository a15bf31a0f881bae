// Sec. 5.3, balancing the character: a posture cost (Eq. 6-10) and gradient descent over the upper-body
// joints that keeps the centre of mass over the support polygon.
#pragma once

#include <glm/gtc/quaternion.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <vector>

#include "engine/motion/body_map.h"
#include "engine/motion/center_of_mass.h"
#include "engine/motion/pose.h"
#include "engine/motion/skeleton.h"
#include "engine/params/params.h"

namespace prep {

// The skeleton-dependent part of the optimizer, built once per skeleton. Every body part's centroid is a
// fixed mix of two points, c = (1 - f) * proximal + f * distal (the mass table's centroid fractions), and
// each point moves rigidly with one joint's frame: that is what makes the gradient cheap (see
// balance_gradient).
struct BalanceModel {
  struct Part {
    int proximal = -1;
    int distal = -1;
    bool distal_is_end_site = false;
    float f = 0.0f;     // centroid fraction from proximal to distal
    float mass = 0.0f;  // fraction of body mass (normalised to sum to 1)
  };
  std::vector<Part> parts;          // in the order of MassModel::segments
  std::vector<int> optimized;       // the upper-body joints (Sec. 5.3: only they are adjusted)
  // The COM as a weighted sum of joint positions and End Sites: COM = sum_j joint_mass[j] * x_j +
  // end_mass[j] * e_j (from the parts' masses and centroid fractions), for the COM's response to a step.
  std::vector<float> joint_mass, end_mass;
  static BalanceModel build(const Skeleton& skeleton, const BodyMap& body, const MassModel& mass);
};

// Working buffers, sized once (no allocation per frame); one per thread, shared by any number of characters.
struct BalanceScratch {
  std::vector<glm::vec3> positions, trial_positions;  // joint world positions
  std::vector<glm::quat> rotations, trial_rotations;  // joint world rotations
  std::vector<glm::vec3> centroids, trial_centroids;  // body-part centroids
  std::vector<glm::vec3> part_gradient;               // dC/d(centroid)
  std::vector<glm::vec3> joint_point_gradient;        // dC/d(joint position)
  std::vector<glm::vec3> end_point_gradient;          // dC/d(End Site position)
  std::vector<glm::vec3> subtree_force, subtree_torque;
  std::vector<float> subtree_mass;                    // COM weight carried below each joint
  std::vector<glm::vec3> subtree_moment;              // sum of weight * point below each joint
  std::vector<glm::vec3> joint_gradient;              // dC/d(world rotation vector at the joint)
  Pose trial;
  void resize(int joints, int parts);
};

// Inputs of Eq. 6-10 other than the posture itself.
struct BalanceTargets {
  glm::vec2 support_centre{0.0f};             // p_cos on the floor (x, z)
  const glm::vec3* style = nullptr;           // centroids of the blended posture p_i(t) (Eq. 7)
  const glm::vec3* previous = nullptr;        // p_i^op(t-1), or null when there is no history (Eq. 8-9)
  const glm::vec3* before_previous = nullptr; // p_i^op(t-2)
};

struct BalanceCost {
  float balance = 0.0f;   // C_b (smoothed norm)
  float style = 0.0f;     // C_s
  float smooth = 0.0f;    // C_m
  float total = 0.0f;     // C
  float com_distance = 0.0f;  // plain |p_com - p_cos| on the floor, metres
};

// Centroids of the body parts from joint world positions/rotations (same values as segment_centroids).
void part_centroids(const Skeleton& skeleton, const BalanceModel& model, const std::vector<glm::vec3>& positions,
                    const std::vector<glm::quat>& rotations, glm::vec3* out);
glm::vec3 model_center_of_mass(const BalanceModel& model, const glm::vec3* centroids);

// Eq. 6-10 for a posture given by its centroids.
BalanceCost balance_cost(const BalanceModel& model, const BalanceParams& params, const BalanceTargets& targets,
                         const glm::vec3* centroids);

// Analytic gradient of C with respect to a small world-frame rotation vector applied at every joint (all
// joints; the optimizer uses the upper body's). A rotation theta at joint j moves every point p carried by
// j's subtree by theta x (p - x_j), so dC/dtheta_j = sum_p (p - x_j) x dC/dp = T_j - x_j x S_j with
// S_j = sum dC/dp and T_j = sum p x dC/dp over the points below j: one backward pass accumulates both
// subtree sums, instead of one forward-kinematics pass per finite difference.
// Needs scratch.positions/rotations/centroids to hold the posture's; fills scratch.joint_gradient and the
// subtree mass sums from which com_response() gives the COM's first-order motion for a step.
void balance_gradient(const Skeleton& skeleton, const BalanceModel& model, const BalanceParams& params,
                      const BalanceTargets& targets, BalanceScratch& scratch);

// First-order motion of the COM when every optimized joint j turns by the world rotation vector
// -joint_gradient[j] (the steepest-descent direction): sum_j -g_j x (Q_j - M_j x_j), with M_j and Q_j the
// COM weight and weighted point sum below j. Used to size the first trial step of each line search so the
// COM would land on the support centre (Sec. 5.3's gradient descent, with a better first guess).
glm::vec3 com_response(const BalanceModel& model, const BalanceScratch& scratch);

struct BalanceResult {
  bool optimized = false;       // false when skipped (alpha below the threshold, disabled, no support)
  int steps = 0;                // accepted gradient steps
  BalanceCost before, after;
};

// Gradient descent on the upper-body joints of `pose` (the blended, IK-solved posture, whose centroids
// are targets.style). Each step follows the negative gradient with a backtracking line search: a step is
// accepted only if it lowers C and leaves the COM no further from the support centre than it was before
// the optimization (balance is the optimizer's purpose, Sec. 5.3); at most params.max_steps steps; it stops early at a local optimum (no
// step accepted after params.max_halvings halvings) or when C improves by less than params.tolerance.
// On return scratch.centroids hold the final posture's centroids.
BalanceResult optimize_balance(const Skeleton& skeleton, const BalanceModel& model, const BalanceParams& params,
                               const BalanceTargets& targets, Pose& pose, BalanceScratch& scratch);

}  // namespace prep
