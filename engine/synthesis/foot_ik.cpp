#include "engine/synthesis/foot_ik.h"

#include <algorithm>
#include <cmath>

#include "engine/motion/kinematics.h"
#include "engine/motion/quaternion_ops.h"
#include "engine/motion/vector_ops.h"

namespace prep {
namespace {

// The shortest rotation taking direction `from` to direction `to` (both non-zero): the half-angle
// quaternion normalize(1 + cos, sin * axis) = normalize(1 + f.t, f x t), exact without trigonometry.
glm::quat rotation_between(V3 from, V3 to) {
  const V3 f = normalize(from);
  const V3 t = normalize(to);
  const float d = dot(f, t);
  if (d > 0.999999f) return glm::quat(1, 0, 0, 0);
  const V3 axis = cross(f, t);
  if (d < -0.999999f || dot(axis, axis) < 1e-12f) {  // opposite: a half turn about an axis perpendicular to f
    const glm::vec3 half_turn =
        normalize(cross(f, V3::load(std::abs(f.x()) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0)))).vec();
    return glm::quat(0.0f, half_turn.x, half_turn.y, half_turn.z);
  }
  return quat::normalize(1.0f + d, axis.x(), axis.y(), axis.z());
}
glm::quat rotation_between(glm::vec3 from, glm::vec3 to) { return rotation_between(V3::load(from), V3::load(to)); }

// An angle in [0, pi] by its cosine and sine.
struct Angle {
  float cos = 1.0f, sin = 0.0f;
};
Angle angle_between_unit(V3 a, V3 b) {
  return {std::clamp(dot(a, b), -1.0f, 1.0f), length(cross(a, b))};  // the sine exact near 0 and pi
}
Angle angle_of_cosine(float cosine) {
  const float c = std::clamp(cosine, -1.0f, 1.0f);
  return {c, std::sqrt(std::max(0.0f, 1.0f - c * c))};
}
// The rotation by `to` - `from` about the unit `axis`: cos and sin of the difference by the angle-difference
// identities, then the half-angle quaternion normalize(1 + cos, sin * axis); no trigonometry.
glm::quat turn_between(Angle from, Angle to, glm::vec3 axis) {
  const float c = to.cos * from.cos + to.sin * from.sin;
  const float s = to.sin * from.cos - to.cos * from.sin;
  if (1.0f + c < 1e-7f) return glm::quat(0.0f, axis.x, axis.y, axis.z);  // a half turn
  return quat::normalize(1.0f + c, s * axis.x, s * axis.y, s * axis.z);
}

// m: how far above the floor an ankle joint is kept, so that its toe can be pitched up to the floor.
constexpr float kAnkleClearance = 0.01f;

glm::vec3 toe_tip(const Skeleton& skeleton, const LegChain& leg, const std::vector<glm::vec3>& wp,
                  const std::vector<glm::quat>& wr) {
  return end_site_position(skeleton, leg.toe_tip_joint, wp, wr);
}

float smoothstep01(float x) {
  const float t = std::clamp(x, 0.0f, 1.0f);
  return t * t * (3.0f - 2.0f * t);
}

}  // namespace

namespace {

// One leg's solve in flight, passed from phase to phase. solve_leg runs the phases one after another;
// apply_foot_ik runs each phase for both legs before the next. A phase is a chain of square roots and
// divisions, each waiting on the one before; the other leg's chain, next to it, fills the wait. Each
// leg's arithmetic is the same either way, to the bit.
struct LegSolve {
  size_t hip = 0, knee = 0, ankle = 0;
  V3 a, b, c;         // hip, knee and ankle, shifted with the body
  float upper = 0.0f, lower = 0.0f, reach = 0.0f;
  V3 to_target;       // hip to the target brought within reach
  glm::vec3 axis{0.0f};  // the knee's bending axis
  glm::quat r0, r1;   // the bend: at the hip and at the knee, in world
  V3 bent;            // hip to ankle, the knee bent
  glm::quat r2;       // the swing about the hip onto the target
  glm::quat hip_world, knee_world;  // the hip's and knee's new world rotations
};

// How far the hip must reach: the target within the leg's softened reach.
void leg_reach(const LegChain& leg, const IkParams& params, const std::vector<glm::vec3>& wp, glm::vec3 target,
               glm::vec3 body_shift, LegSolve& l) {
  l.hip = static_cast<size_t>(leg.hip), l.knee = static_cast<size_t>(leg.knee), l.ankle = static_cast<size_t>(leg.ankle);
  const V3 shift = V3::load(body_shift);
  const V3 a = V3::load(wp[l.hip]) + shift, b = V3::load(wp[l.knee]) + shift, c = V3::load(wp[l.ankle]) + shift;
  const float upper = length(b - a), lower = length(c - b);
  const float full = upper + lower;
  const float eps = 1e-5f * full;

  // Softened reach: exact up to `soft`; beyond it the reach tends to (but never reaches) full length.
  V3 to_target = V3::load(target) - a;
  const float wanted = length(to_target);
  const float current = length(c - a);
  const float limit = std::min(params.reach_limit * full, full - eps);
  const float soft = std::min(std::max(params.knee_soft_start * full, current), limit);
  float reach = wanted;
  if (wanted > soft) {
    const float band = limit - soft;
    reach = band > 1e-7f ? soft + band * (1.0f - std::exp(-(wanted - soft) / band)) : soft;
  }
  reach = std::max(reach, std::abs(upper - lower) + eps);
  // The target brought within reach (a degenerate request keeps the ankle), as seen from the hip.
  l.to_target = (wanted > 1e-7f ? a + (reach / wanted) * to_target : c) - a;
  l.a = a, l.b = b, l.c = c;
  l.upper = upper, l.lower = lower, l.reach = reach;
}

// Knee: set the hip-ankle distance to the reach by the law of cosines, bending in the knee's current plane.
void leg_bend(glm::vec3 forward, LegSolve& l) {
  const V3 a = l.a, b = l.b, c = l.c;
  const float upper = l.upper, lower = l.lower, reach = l.reach;
  const V3 ac = normalize(c - a);
  V3 axis = cross(c - a, b - a);
  if (dot(axis, axis) < 1e-8f * upper * upper * lower * lower) axis = cross(c - a, V3::load(forward));
  axis = normalize(axis);
  const V3 ab = normalize(b - a);
  const Angle ac_ab_0 = angle_between_unit(ac, ab);
  const Angle ba_bc_0 = angle_between_unit(-ab, normalize(c - b));
  const Angle ac_ab_1 = angle_of_cosine((lower * lower - upper * upper - reach * reach) / (-2.0f * upper * reach));
  const Angle ba_bc_1 = angle_of_cosine((reach * reach - upper * upper - lower * lower) / (-2.0f * upper * lower));
  l.axis = axis.vec();
  l.r0 = turn_between(ac_ab_0, ac_ab_1, l.axis);  // at the hip, in world
  l.r1 = turn_between(ba_bc_0, ba_bc_1, l.axis);  // at the knee, in world
}

// Then swing the whole leg about the hip so that the (new) ankle direction points at the target.
void leg_swing(LegSolve& l) {
  const glm::quat r01 = quat::mul(l.r0, l.r1);
  l.bent = rotate(l.r0, l.b - l.a) + rotate(r01, l.c - l.b);
  l.r2 = rotation_between(l.bent, l.to_target);
}

// The new world rotations, then the local ones, in two phases (see LegSolve). The world rotations are
// unit quaternions (normalized here), so their inverses are their conjugates.
void leg_world_rotations(const std::vector<glm::quat>& wr, LegSolve& l) {
  const glm::quat r20 = quat::mul(l.r2, l.r0);
  l.hip_world = quat::normalize(quat::mul(r20, wr[l.hip]));
  l.knee_world = quat::normalize(quat::mul(quat::mul(r20, l.r1), wr[l.knee]));
}
// Returns the ankle position reached.
glm::vec3 leg_local_rotations(const Skeleton& skeleton, Pose& pose, const std::vector<glm::quat>& wr,
                              const glm::quat& foot_world, const LegSolve& l) {
  const int hip_parent = skeleton.joints[l.hip].parent;
  const glm::quat parent_world = hip_parent >= 0 ? wr[static_cast<size_t>(hip_parent)] : glm::quat(1, 0, 0, 0);
  pose.rotations[l.hip] = quat::normalize(quat::conjugate_mul(parent_world, l.hip_world));
  pose.rotations[l.knee] = quat::normalize(quat::conjugate_mul(l.hip_world, l.knee_world));
  // The shin may not be the ankle's direct parent in every skeleton: compose the joints between them.
  glm::quat between(1, 0, 0, 0);
  for (int j = skeleton.joints[l.ankle].parent; j != static_cast<int>(l.knee); j = skeleton.joints[static_cast<size_t>(j)].parent) {
    between = quat::mul(pose.rotations[static_cast<size_t>(j)], between);
  }
  const glm::quat above_ankle = quat::mul(l.knee_world, between);
  pose.rotations[l.ankle] = quat::normalize(quat::inverse_mul(above_ankle, foot_world));
  return (l.a + rotate(l.r2, l.bent)).vec();
}

}  // namespace

glm::vec3 solve_leg(const Skeleton& skeleton, const LegChain& leg, const IkParams& params, Pose& pose,
                    const std::vector<glm::vec3>& wp, const std::vector<glm::quat>& wr, glm::vec3 target,
                    const glm::quat& foot_world, glm::vec3 forward, glm::vec3 body_shift) {
  LegSolve l;
  leg_reach(leg, params, wp, target, body_shift, l);
  leg_bend(forward, l);
  leg_swing(l);
  leg_world_rotations(wr, l);
  return leg_local_rotations(skeleton, pose, wr, foot_world, l);
}

FrameContacts select_pinned_points(const FrameContacts& contacts, const std::array<float, 2>& heel_speed,
                                   const std::array<float, 2>& toe_speed, const IkParams& params) {
  FrameContacts pinned{};
  for (size_t side = 0; side < 2; ++side) {
    const float h = heel_speed[side], t = toe_speed[side];
    const bool still = std::max(h, t) < params.pivot_speed;
    pinned[side].heel = contacts[side].heel && (!contacts[side].toe || still || h <= t);
    pinned[side].toe = contacts[side].toe && (!contacts[side].heel || still || t < h);
  }
  return pinned;
}

void apply_foot_ik(const Skeleton& skeleton, const BodyMap& body, const IkParams& params,
                   const FrameContacts& pinned, float dt, Pose& pose, const std::vector<glm::vec3>& wp,
                   const std::vector<glm::quat>& wr, FootPlants& plants, float& root_drop) {
  const glm::vec3 forward = quat::rotate(pose.rotations[static_cast<size_t>(body.root)], glm::vec3(0.0f, 0.0f, 1.0f));
  std::array<glm::vec3, 2> heel{}, foot_vector{}, target{};
  std::array<glm::quat, 2> foot_world{};
  float required_drop = 0.0f;
  for (size_t side = 0; side < 2; ++side) {
    const LegChain& leg = body.legs[side];
    const FootContact& contact = pinned[side];
    FootPlant& plant = plants[side];
    if (!contact.heel) plant.heel_planted = false;
    if (!contact.toe) plant.toe_planted = false;

    heel[side] = wp[static_cast<size_t>(leg.ankle)];
    glm::vec3 heel_to_toe = toe_tip(skeleton, leg, wp, wr) - heel[side];
    const bool toe_is_child = leg.toe >= 0 && leg.toe_tip_joint == leg.toe &&
                              skeleton.joints[static_cast<size_t>(leg.toe)].parent == leg.ankle;
    if (!(plant.heel_planted && plant.toe_planted && toe_is_child)) plant.toe_held = false;
    if (plant.toe_held) {
      const Joint& toe = skeleton.joints[static_cast<size_t>(leg.toe)];
      pose.rotations[static_cast<size_t>(leg.toe)] = plant.toe_local;
      heel_to_toe = quat::rotate(wr[static_cast<size_t>(leg.ankle)], toe.offset + quat::rotate(plant.toe_local, toe.end_site));
    }
    foot_world[side] = wr[static_cast<size_t>(leg.ankle)];
    foot_vector[side] = heel_to_toe;
    if (plant.heel_planted) {
      target[side] = plant.heel_anchor;
      if (plant.toe_planted && glm::length(plant.toe_anchor - plant.heel_anchor) > 1e-4f) {
        // Flat foot: turn the foot (smallest rotation) so that its toe tip points at its anchor too.
        const glm::quat align = rotation_between(heel_to_toe, plant.toe_anchor - plant.heel_anchor);
        foot_world[side] = quat::normalize(quat::mul(align, foot_world[side]));
        foot_vector[side] = quat::rotate(align, heel_to_toe);
      }
    } else if (plant.toe_planted) {
      target[side] = plant.toe_anchor - heel_to_toe;  // heel off: the foot rolls about its planted toe
    } else {
      // Free foot: the correction it had when it lifted off fades out, so the swing joins the blended pose
      // without a jump. It keeps its height when the pelvis is lowered below (its hip comes closer, so it
      // stays in reach): carried down with the body it would swing through the floor and land as far below
      // it, and the next stance, planted there, would ask for a deeper drop, step after step.
      plant.fade = std::max(0.0f, plant.fade - (params.release_s > 0.0f ? dt / params.release_s : 1.0f));
      target[side] = heel[side] + plant.offset * smoothstep01(plant.fade);
      continue;
    }
    // A planted foot the leg cannot reach without straightening the knee past the soft start (the body
    // was slowed by Eq. 3-4 or the legs blended toward T_p): lower the pelvis just enough.
    const glm::vec3 hip = wp[static_cast<size_t>(leg.hip)];
    const float full = glm::length(wp[static_cast<size_t>(leg.knee)] - hip) +
                       glm::length(wp[static_cast<size_t>(leg.ankle)] - wp[static_cast<size_t>(leg.knee)]);
    const float soft = std::min(std::max(params.knee_soft_start * full, glm::length(heel[side] - hip)),
                                params.reach_limit * full);
    const glm::vec3 v = hip - target[side];
    const float horizontal2 = v.x * v.x + v.z * v.z;
    const float drop = horizontal2 < soft * soft ? v.y - std::sqrt(soft * soft - horizontal2) : v.y;
    required_drop = std::max(required_drop, drop);
  }
  // The drop follows what the planted feet need at once and recovers at a bounded speed, so the pelvis
  // does not pop up when a foot lifts off.
  root_drop = std::clamp(std::max(required_drop, root_drop - params.drop_recovery_speed * dt), 0.0f, params.max_root_drop);
  pose.root_position.y -= root_drop;
  const glm::vec3 body_shift(0.0f, -root_drop, 0.0f);

  // solve_leg for both legs, phase by phase (LegSolve).
  std::array<LegSolve, 2> legs;
  for (size_t side = 0; side < 2; ++side) leg_reach(body.legs[side], params, wp, target[side], body_shift, legs[side]);
  for (size_t side = 0; side < 2; ++side) leg_bend(forward, legs[side]);
  for (size_t side = 0; side < 2; ++side) leg_swing(legs[side]);
  std::array<glm::vec3, 2> solved{};
  for (size_t side = 0; side < 2; ++side) leg_world_rotations(wr, legs[side]);
  for (size_t side = 0; side < 2; ++side) solved[side] = leg_local_rotations(skeleton, pose, wr, foot_world[side], legs[side]);

  for (size_t side = 0; side < 2; ++side) {
    const LegChain& leg = body.legs[side];
    FootPlant& plant = plants[side];
    const glm::vec3 reached = solved[side];
    if (plant.heel_planted && plant.toe_planted) {
      // Flat foot: the toe tip follows the heel along the anchored direction; if the toe joint bent a little
      // the tip moved along it, and the anchor goes with it so a later heel-off pivots about where it is.
      plant.toe_anchor = reached + foot_vector[side];
    }
    if (pinned[side].heel && !plant.heel_planted) {
      plant.heel_planted = true;
      plant.heel_anchor = reached;
    }
    if (pinned[side].toe && !plant.toe_planted) {
      plant.toe_planted = true;
      plant.toe_anchor = reached + foot_vector[side];
    }
    const bool toe_is_child = leg.toe >= 0 && leg.toe_tip_joint == leg.toe &&
                              skeleton.joints[static_cast<size_t>(leg.toe)].parent == leg.ankle;
    if (plant.heel_planted && plant.toe_planted && toe_is_child && !plant.toe_held) {
      plant.toe_held = true;
      plant.toe_local = pose.rotations[static_cast<size_t>(leg.toe)];
    }
    if (plant.heel_planted || plant.toe_planted) {
      plant.offset = reached - heel[side];
      plant.fade = 1.0f;
    }
  }
}

int keep_toes_above_floor(const Skeleton& skeleton, const BodyMap& body, Pose& pose,
                          const std::vector<glm::vec3>& world_positions, const std::vector<glm::quat>& world_rotations) {
  // Ankles up to the floor first: a toe can only be pitched up about an ankle above it.
  float lift = 0.0f;
  for (const LegChain& leg : body.legs) lift = std::max(lift, kAnkleClearance - world_positions[static_cast<size_t>(leg.ankle)].y);
  lift = std::max(lift, 0.0f);
  int turned = 0;
  float still_below = 0.0f;  // a toe no pitch could lift (its foot pointing straight down): the body rises
  for (const LegChain& leg : body.legs) {
    const glm::vec3 up(0.0f, lift, 0.0f);
    const glm::vec3 ankle = world_positions[static_cast<size_t>(leg.ankle)] + up;
    const glm::vec3 toe = toe_tip(skeleton, leg, world_positions, world_rotations) + up;
    if (toe.y >= 0.0f) continue;
    const glm::vec3 foot = toe - ankle;
    const float length = glm::length(foot);
    const glm::vec2 ahead(foot.x, foot.z);
    if (glm::length(ahead) < 1e-4f || ankle.y >= length) {
      still_below = std::max(still_below, -toe.y);
      continue;
    }
    // The same foot, pitched up until its tip touches the floor.
    const float reach = std::sqrt(std::max(0.0f, length * length - ankle.y * ankle.y));
    const glm::vec2 along = glm::normalize(ahead) * reach;
    const glm::quat pitch = rotation_between(foot, glm::vec3(along.x, -ankle.y, along.y));
    const size_t a = static_cast<size_t>(leg.ankle);
    const int parent = skeleton.joints[a].parent;
    const glm::quat parent_world = parent >= 0 ? world_rotations[static_cast<size_t>(parent)] : glm::quat(1.0f, 0.0f, 0.0f, 0.0f);
    pose.rotations[a] = glm::normalize(glm::inverse(parent_world) * pitch * world_rotations[a]);
    ++turned;
  }
  pose.root_position.y += lift + still_below;
  return turned;
}

}  // namespace prep
