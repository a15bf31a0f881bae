#include "engine/synthesis/synthesizer.h"

#include <cmath>
#include <cstring>
#include <stdexcept>

#include "engine/motion/kinematics.h"
#include "engine/synthesis/trajectory.h"

namespace prep {
namespace {

// Kinematics of the locomotion's legs, per thread and joint count: read for its feet only, so no character
// keeps them.
struct LocomotionKinematics {
  std::vector<glm::vec3> positions;
  std::vector<glm::quat> rotations;
};
LocomotionKinematics& thread_locomotion_kinematics(size_t joints) {
  thread_local LocomotionKinematics k;
  if (k.positions.size() < joints) {
    k.positions.resize(joints);
    k.rotations.resize(joints);
  }
  return k;
}

// The balance optimizer's working buffers, one per thread and skeleton size (BalanceScratch keeps nothing
// from one call to the next). A crowd's thousands of characters share their thread's, which stays in its
// cache, instead of each carrying 6 KB of its own (built-in body) through it every frame.
BalanceScratch& thread_balance_scratch(int joints, int parts) {
  struct Sized {
    int joints = 0, parts = 0;
    BalanceScratch scratch;
  };
  thread_local std::vector<std::unique_ptr<Sized>> sized;  // one per skeleton in use: a few at most
  for (const auto& s : sized)
    if (s->joints == joints && s->parts == parts) return s->scratch;
  sized.push_back(std::make_unique<Sized>());
  sized.back()->joints = joints;
  sized.back()->parts = parts;
  sized.back()->scratch.resize(joints, parts);
  return sized.back()->scratch;
}

}  // namespace

Synthesizer::Synthesizer(std::shared_ptr<const Skeleton> skeleton, BodyMap body, const MassModel& mass,
                         const Params& params)
    : skeleton_(std::move(skeleton)), body_(std::move(body)), params_(params) {
  if (!skeleton_) throw std::invalid_argument("Synthesizer: no skeleton");
  balance_model_ = BalanceModel::build(*skeleton_, body_, mass);
  if (balance_model_.parts.size() > static_cast<size_t>(kMaxBodyParts)) {
    throw std::invalid_argument("Synthesizer: the mass model has more body parts than kMaxBodyParts");
  }
  curves_ = make_blend_curves(*skeleton_, body_, params_.blend);
  std::vector<int> leg_joints, all_joints, foot_joints, balance_stale;
  std::vector<char> leg(static_cast<size_t>(skeleton_->size()), 0);
  for (const LegChain& chain : body_.legs) {
    for (int j : {chain.hip, chain.knee, chain.ankle, chain.toe, chain.toe_tip_joint}) {
      for (; j >= 0; j = skeleton_->joints[static_cast<size_t>(j)].parent) leg[static_cast<size_t>(j)] = 1;
    }
  }
  for (int j = 0; j < skeleton_->size(); ++j) {
    if (leg[static_cast<size_t>(j)]) leg_joints.push_back(j);
    all_joints.push_back(j);
  }
  std::vector<char> foot(static_cast<size_t>(skeleton_->size()), 0);
  for (const LegChain& chain : body_.legs) {
    if (chain.ankle >= 0) foot[static_cast<size_t>(chain.ankle)] = 1;
  }
  for (int j = 0; j < skeleton_->size(); ++j) {
    const int parent = skeleton_->joints[static_cast<size_t>(j)].parent;
    if (parent >= 0 && foot[static_cast<size_t>(parent)]) foot[static_cast<size_t>(j)] = 1;
    if (foot[static_cast<size_t>(j)]) foot_joints.push_back(j);
  }
  // Below an optimized joint but read by no body part: the optimizer's trial kinematics skip them.
  std::vector<char> below(static_cast<size_t>(skeleton_->size()), 0);
  for (int j = 0; j < skeleton_->size(); ++j) {
    const size_t jj = static_cast<size_t>(j);
    const int parent = skeleton_->joints[jj].parent;
    below[jj] = balance_model_.optimized_index[jj] >= 0 || (parent >= 0 && below[static_cast<size_t>(parent)]);
    if (below[jj] && !balance_model_.is_moved[jj]) balance_stale.push_back(j);
  }
  // The kinematics passes run level by level (breadth_first): the two legs side by side.
  leg_pass_ = JointPass(*skeleton_, breadth_first(*skeleton_, leg_joints));
  all_pass_ = JointPass(*skeleton_, breadth_first(*skeleton_, all_joints));
  foot_pass_ = JointPass(*skeleton_, breadth_first(*skeleton_, foot_joints));
  balance_stale_pass_ = JointPass(*skeleton_, breadth_first(*skeleton_, balance_stale));
}

void Synthesizer::set_params(const Params& params) {
  curves_ = make_blend_curves(*skeleton_, body_, params.blend);
  params_ = params;
}

SynthesisScratch Synthesizer::make_scratch() const {
  SynthesisScratch s;
  const size_t n = static_cast<size_t>(skeleton_->size());
  s.weights.resize(n);
  s.positions.resize(n);
  s.rotations.resize(n);
  s.support.hull.reserve(16);
  return s;
}

void Synthesizer::stage_blend(const SynthesisInput& in, SynthesisScratch& s, Pose& out) const {
  if (s.weights_curves != curves_.id || std::memcmp(&s.weights_alpha, &in.alpha, sizeof in.alpha) != 0) {
    blend_weights(curves_, in.alpha, s.weights.data());                                    // Eq. 1
    s.weights_alpha = in.alpha;
    s.weights_curves = curves_.id;
  }
  blend_joint_rotations(*in.locomotion, *in.reference, s.weights.data(), out);             // Eq. 2
  const size_t r = static_cast<size_t>(body_.root);
  out.rotations[r] = blend_root_rotation(in.locomotion->rotations[r], in.reference->rotations[r], s.weights[r]);
  out.root_position = in.locomotion->root_position;
}

void Synthesizer::stage_trajectory(const SynthesisInput& in, SynthesisState& state, SynthesisScratch& s,
                                   Pose& out) const {
  const glm::vec3 loco_root = in.locomotion->root_position;
  glm::vec3 displacement(0.0f);
  s.locomotion_jump = glm::vec3(0.0f);
  if (in.has_displacement && state.started) s.locomotion_jump = loco_root - in.displacement - state.previous_locomotion_root;
  if (in.has_displacement) displacement = in.displacement;
  else if (state.started) displacement = loco_root - state.previous_locomotion_root;
  if (!state.started) state.root_xz = glm::vec2(loco_root.x, loco_root.z) - glm::vec2(displacement.x, displacement.z);
  const float w_root = s.weights[static_cast<size_t>(body_.root)];
  state.root_xz = advance_root(state.root_xz, displacement, w_root);  // Eq. 3-4
  float dy_left = 0.0f, dy_right = 0.0f;
  foot_height_changes(*skeleton_, body_, *in.locomotion, out, dy_left, dy_right);
  out.root_position = glm::vec3(state.root_xz.x, adjust_root_height(loco_root.y, dy_left, dy_right),  // Eq. 5
                                state.root_xz.y);
  state.previous_locomotion_root = loco_root;
  state.started = true;
}

void Synthesizer::stage_ik(const SynthesisInput& in, SynthesisState& state, SynthesisScratch& s, Pose& out) const {
  // The locomotion's own heel and toe speeds decide which flagged points the foot stands on. (The IK reads
  // only the legs and their ancestors: forward kinematics of those, then of everything once solved.) The
  // locomotion's legs and the blended ones are taken together.
  LocomotionKinematics& loco = thread_locomotion_kinematics(s.positions.size());
  if (params_.ik.enabled) {
    leg_pass_.run_two(*in.locomotion, loco.positions, loco.rotations, out, s.positions, s.rotations);
  } else {
    leg_pass_.run(*in.locomotion, loco.positions, loco.rotations);
  }
  const FootPoints loco_feet = foot_points(*skeleton_, body_, loco.positions, loco.rotations);
  std::array<float, 2> heel_speed{0.0f, 0.0f}, toe_speed{0.0f, 0.0f};
  if (state.locomotion_feet_known && in.dt > 0.0f) {
    const glm::vec3 shift = s.locomotion_jump;  // a re-aligned stream moves every point alike
    for (size_t side = 0; side < 2; ++side) {
      heel_speed[side] = glm::length(loco_feet.heel[side] - shift - state.previous_locomotion_feet.heel[side]) / in.dt;
      toe_speed[side] = glm::length(loco_feet.toe[side] - shift - state.previous_locomotion_feet.toe[side]) / in.dt;
    }
  }
  state.previous_locomotion_feet = loco_feet;
  state.locomotion_feet_known = true;
  s.pinned = select_pinned_points(in.contacts, heel_speed, toe_speed, params_.ik);

  if (!params_.ik.enabled) {
    all_pass_.run(out, s.positions, s.rotations);
    return;
  }
  apply_foot_ik(*skeleton_, body_, params_.ik, s.pinned, in.dt, out, s.positions, s.rotations, state.feet, state.root_drop);
  all_pass_.run(out, s.positions, s.rotations);
}

bool Synthesizer::stage_balance(const SynthesisInput& in, SynthesisState& state, SynthesisScratch& s, Pose& out,
                                SynthesisReport* report) const {
  // Needs s.positions / s.rotations = forward kinematics of `out` (stage_ik leaves them so).
  const BalanceParams& bp = params_.balance;
  if (!bp.enabled) {
    // Nothing below shapes the pose. The centroid history of Eq. 8-9 restarts when balance is turned on
    // again, as for a new character, rather than being kept up for an optimizer that is off; the support
    // polygon and COM are taken only for a report that asks for them.
    state.history = 0;
    state.correction.valid = false;
    if (!report) {
      s.support_of_output = false;
      s.centroids_of_output = false;
      s.centroids_but_feet_of_output = false;
      return false;
    }
  }
  // The support polygon serves the optimizer (Eq. 6) and a report; below the optimizer's alpha threshold
  // without a report nothing reads it. The body-part centroids are taken every frame: they are the
  // smoothness term's history (Eq. 8-9) when the optimizer runs on the next ones.
  const bool may_optimize = bp.enabled && in.alpha >= bp.alpha_threshold && bp.max_steps > 0;
  const bool take_support = may_optimize || report;
  FootPoints feet{};
  if (take_support) {
    feet = foot_points(*skeleton_, body_, s.positions, s.rotations);
    support_polygon(feet, in.contacts, params_.contacts, s.support);
  }
  const size_t n_parts = balance_model_.parts.size();
  BalanceScratch& b = thread_balance_scratch(skeleton_->size(), static_cast<int>(n_parts));
  part_centroids(*skeleton_, balance_model_, s.positions, s.rotations, b.style.data());

  BalanceTargets targets;
  targets.style = b.style.data();
  if (state.history >= 2) {
    targets.previous = state.previous.data();
    targets.before_previous = state.before_previous.data();
  }
  const bool has_support = take_support && !s.support.empty();
  if (has_support) targets.support_centre = s.support.center();
  const bool optimize = may_optimize && has_support;

  BalanceResult result;
  const glm::vec3* final_centroids = b.style.data();
  if (optimize) {
    // The IK stage's forward kinematics of `out` are handed to the optimizer and its final ones taken back
    // by exchanging buffers, not copying them (both hold one entry per joint of this skeleton).
    b.positions.swap(s.positions);
    b.rotations.swap(s.rotations);
    result = optimize_balance(*skeleton_, balance_model_, bp, targets, out, b, &state.correction, in.dt, true);
    final_centroids = b.centroids.data();
    // The optimizer's kinematics are those of the final posture but for the joints it does not read
    // (fingers, eyes): those are brought up to date, and stage_floor needs no pass of its own.
    s.positions.swap(b.positions);
    s.rotations.swap(b.rotations);
    balance_stale_pass_.run(out, s.positions, s.rotations);
  } else {
    state.correction.valid = false;  // the next optimized frame starts from its blended posture
  }

  if (report) {
    report->alpha = in.alpha;
    report->w_root = s.weights[static_cast<size_t>(body_.root)];
    report->has_support = has_support;
    report->balanced = result.optimized;
    report->balance_steps = result.steps;
    report->warm_started = result.warm_started;
    report->balance_shift = result.largest_shift;
    report->feet = feet;
    report->pinned = s.pinned;
    if (has_support) {
      // The blended posture's COM: the optimizer's starting cost took it from the same centroids.
      const glm::vec3 before = optimize ? result.before.com : model_center_of_mass(balance_model_, b.style.data());
      report->com_inside_before = s.support.contains({before.x, before.z});
      if (optimize) {
        const glm::vec3 after = model_center_of_mass(balance_model_, final_centroids);
        report->com_distance_before = result.before.com_distance;
        report->com_distance_after = result.after.com_distance;
        report->com_inside_after = s.support.contains({after.x, after.z});
      } else {  // the posture stands as blended (the same distance balance_cost gives)
        const glm::vec2 d(before.x - targets.support_centre.x, before.z - targets.support_centre.y);
        report->com_distance_before = report->com_distance_after = std::sqrt(glm::dot(d, d));
        report->com_inside_after = report->com_inside_before;
      }
    }
  }

  s.support_of_output = take_support;
  s.centroids_of_output = true;  // `state.previous` holds them (the World reads them)
  s.centroids_but_feet_of_output = false;
  std::copy(state.previous.begin(), state.previous.begin() + static_cast<long>(n_parts), state.before_previous.begin());
  std::copy(final_centroids, final_centroids + n_parts, state.previous.begin());
  state.history = bp.enabled ? std::min(state.history + 1, 2) : 0;
  return result.optimized;
}

bool Synthesizer::step(const SynthesisInput& in, SynthesisState& state, SynthesisScratch& scratch, Pose& out,
                       SynthesisReport* report) const {
  if (!in.locomotion || !in.reference) throw std::invalid_argument("Synthesizer::step: no locomotion or reference pose");
  stage_blend(in, scratch, out);
  stage_trajectory(in, state, scratch, out);
  stage_ik(in, state, scratch, out);
  const bool balanced = stage_balance(in, state, scratch, out, report);
  if (in.keep_toes_above_floor) stage_floor(scratch, out, true);
  return balanced;
}

void Synthesizer::stage_floor(SynthesisScratch& s, Pose& out, bool kinematics_given) const {
  if (!kinematics_given) {
    forward_kinematics(*skeleton_, out, s.positions, &s.rotations);  // sizes the buffers of any scratch
    s.support_of_output = false;  // a pose the stages before did not make
    s.centroids_of_output = false;
    s.centroids_but_feet_of_output = false;
  }
  const float root_height = out.root_position.y;
  // Usually nothing is below the floor and the kinematics stand. A body lifted is taken again whole; feet
  // pitched up about their ankles only from the ankles down (the joints above are as they were).
  const int turned = keep_toes_above_floor(*skeleton_, body_, out, s.positions, s.rotations);
  if (out.root_position.y != root_height) {
    all_pass_.run(out, s.positions, s.rotations);
    s.support_of_output = false;
    s.centroids_of_output = false;
    s.centroids_but_feet_of_output = false;
  } else if (turned > 0) {
    foot_pass_.run(out, s.positions, s.rotations);
    s.centroids_but_feet_of_output = s.centroids_of_output || s.centroids_but_feet_of_output;
    s.support_of_output = false;
    s.centroids_of_output = false;
  }
}

}  // namespace prep
