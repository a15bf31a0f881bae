// Sec. 5.3, balancing the character: a posture cost (Eq. 6-10) and gradient descent over the upper-body
// joints that keeps the centre of mass over the support polygon.
#pragma once

#include <glm/gtc/quaternion.hpp>
#include <glm/vec2.hpp>
#include <array>
#include <glm/vec3.hpp>
#include <vector>

#include "engine/motion/body_map.h"
#include "engine/motion/center_of_mass.h"
#include "engine/motion/pose.h"
#include "engine/motion/skeleton.h"
#include "engine/params/params.h"

namespace prep {

constexpr int kMaxOptimizedJoints = 32;  // upper-body joints a BalanceCorrection can remember

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
  // The upper-body joints (Sec. 5.3: only they are adjusted) whose rotation moves some body part: a
  // finger or an eye carries no point of the mass table, its gradient is identically zero, so it is left
  // out (the result is the same; the optimizer does less work).
  std::vector<int> optimized;
  // The joints whose world position or rotation a change of the optimized joints can move and that the
  // mass table reads (the optimized joints and the joints below them on a path to a body part's point),
  // parents first, level by level (breadth_first): a trial posture re-runs forward kinematics on these
  // only, and the gradient's backward pass takes them in reverse.
  std::vector<int> moved;
  std::vector<int> moved_parts;     // the body parts that have a point a change of the optimized joints moves
  std::vector<int> optimized_index; // per joint: its index in `optimized`, or -1
  std::vector<char> is_moved;       // per joint: listed in `moved`
  std::vector<char> end_point;      // per joint: its End Site is a point of the mass table
  // The COM as a weighted sum of joint positions and End Sites: COM = sum_j joint_mass[j] * x_j +
  // end_mass[j] * e_j (from the parts' masses and centroid fractions), for the COM's response to a step.
  std::vector<float> joint_mass, end_mass;
  // Throws std::invalid_argument for a mass model naming joints the skeleton lacks, with no mass, or
  // with more optimized joints than kMaxOptimizedJoints.
  static BalanceModel build(const Skeleton& skeleton, const BodyMap& body, const MassModel& mass);
};

// The optimizer's correction of one frame, kept for the next (one character's memory, plain data): the
// rotation each optimized joint was turned by in its parent's frame (optimized local rotation = offset *
// blended local rotation, offset.w >= 0), in the order of BalanceModel::optimized.
struct BalanceCorrection {
  bool valid = false;
  std::array<glm::quat, kMaxOptimizedJoints> offset{};
};

// Working buffers, sized once (no allocation per frame); one per thread, shared by any number of characters.
struct BalanceScratch {
  std::vector<glm::vec3> positions, trial_positions;  // joint world positions
  std::vector<glm::quat> rotations, trial_rotations;  // joint world rotations
  std::vector<glm::vec3> centroids, trial_centroids;  // body-part centroids
  std::vector<glm::vec3> start_centroids;             // centroids where this frame's descent started
  std::vector<glm::vec3> style;                       // the blended posture's centroids (Eq. 7's targets)
  std::vector<glm::vec3> part_gradient;               // dC/d(centroid)
  std::vector<float> smooth_term;                     // each part's Eq. 8-9 term at the blended posture
  std::vector<glm::vec3> joint_point_gradient;        // dC/d(joint position)
  std::vector<glm::vec3> end_point_gradient;          // dC/d(End Site position)
  std::vector<glm::vec3> subtree_force, subtree_torque;
  std::vector<float> subtree_mass;                    // COM weight carried below each joint
  std::vector<glm::vec3> subtree_moment;              // sum of weight * point below each joint
  std::vector<glm::vec3> joint_gradient;              // dC/d(world rotation vector at the joint)
  std::vector<glm::vec3> angular, linear;             // a step's first-order joint motion (step_motion)
  std::vector<glm::quat> base;                        // the blended rotations of the optimized joints
  std::vector<glm::quat> local, trial_local;          // the optimized joints' local rotations (current, trial)
  std::vector<glm::quat> offset;                      // the warm start's correction being tried
  std::vector<glm::quat> step_rotation;               // a line search trial's turn of each optimized joint
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
  glm::vec3 com{0.0f};        // p_com, the centre of mass the cost was taken at
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

// balance_gradient as the optimizer computes it: the same values at the optimized joints (and the subtree
// sums com_response reads), over the moved joints and parts only. Other joints' entries are not written.
void optimized_balance_gradient(const Skeleton& skeleton, const BalanceModel& model, const BalanceParams& params,
                                const BalanceTargets& targets, BalanceScratch& scratch);

// First-order motion of the COM when every optimized joint j turns by the world rotation vector
// -joint_gradient[j] (the steepest-descent direction): sum_j -g_j x (Q_j - M_j x_j), with M_j and Q_j the
// COM weight and weighted point sum below j. Used to size the first trial step of each line search so the
// COM would land on the support centre (Sec. 5.3's gradient descent, with a better first guess).
glm::vec3 com_response(const BalanceModel& model, const BalanceScratch& scratch);

struct BalanceResult {
  bool optimized = false;       // false when skipped (alpha below the threshold, disabled, no support)
  bool warm_started = false;    // the descent started from the previous frame's correction (or a part of it)
  int steps = 0;                // accepted gradient steps
  float largest_shift = 0.0f;   // the largest distance (m) a body-part centroid was moved from the blended posture
  BalanceCost before, after;
};

// Gradient descent on the upper-body joints of `pose` (the blended, IK-solved posture, whose centroids
// must be targets.style: they are not computed again), minimizing Eq. 10 (balance_cost). The paper's rule: at most params.max_steps steps,
// stopping early at a local optimum (no step accepted after params.max_halvings halvings, or C improving by
// less than params.tolerance).
//
// Each step follows the negative gradient (optimized_balance_gradient). The first trial step is where the
// linearized COM comes closest to the support centre along that direction (com_response), capped at
// params.step_size and shortened so that the centroids' first-order motion stays inside the trust region;
// a backtracking line search halves it until the step is accepted. A step is accepted only if it lowers C
// and stays inside the trust region of the correction:
//  - the COM ends no further from the support centre than it was in the blended posture (balance is the
//    optimizer's purpose, Sec. 5.3);
//  - no body-part centroid moves more than params.max_part_shift from the blended posture;
//  - no centroid moves more than params.max_shift_speed * dt from where this frame's descent started.
// It also stops when less than a tenth of the tighter bound is left to the edge of the trust region.
// Why the trust region: Eq. 6 and 7 are norms, not squares, so along a lean C falls at a constant rate
// (w_b times how far the COM moves) and rises at a constant rate (w_s times how far the parts move, on
// average over all parts, the legs included); for a lean of the trunk the first wins (the COM carries
// most of the body's mass along, while the mean over the parts is diluted by the legs that stay), and C
// keeps falling until the COM sits on the support centre however far that is. In walking single support
// the COM passes 5-40 cm from the stance foot's centre; with the bounds off the optimizer follows it
// with a trunk lean of up to 62 degrees that swings from one foot to the other at every step, the arms
// flung up to 0.68 m (built-in walk -> duck; 4.9 degrees with the bounds; the test "balance optimizer:
// the trust region keeps the lean slight ..." in tests/synthesis/preparation_run_test.cpp). The paper's
// "slight" lean (Fig. 8) comes from stopping after 10 small steps; the trust region makes that explicit
// and independent of step sizes.
// The defaults: 6 cm, the head's move in a trunk lean of about 6 degrees; 0.3 m/s, a quarter of the
// head's own speed in a walk, so the correction never outpaces the motion it corrects.
//
// Warm start (`memory`, may be null): the descent starts from the previous frame's correction when that is
// at least as good as the blended posture itself (lower C, COM no further from the centre, within the
// trust region); else from half of it, a quarter, ..., else from the blended posture. So the correction
// evolves with the motion instead of being rebuilt from nothing (and thrown away) every frame. On return
// `memory` holds this frame's correction.
// kinematics_given: scratch.positions / rotations already hold the forward kinematics of `pose` (the
// synthesizer's IK stage computes it anyway), else it is computed here.
// On return scratch.centroids hold the final posture's centroids. scratch.positions / rotations hold its
// forward kinematics for the joints the mass table reads (not for fingers or eyes).
BalanceResult optimize_balance(const Skeleton& skeleton, const BalanceModel& model, const BalanceParams& params,
                               const BalanceTargets& targets, Pose& pose, BalanceScratch& scratch,
                               BalanceCorrection* memory = nullptr, float dt = 1.0f / 30.0f,
                               bool kinematics_given = false);

}  // namespace prep
