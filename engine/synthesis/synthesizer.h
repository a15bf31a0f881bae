// Sec. 5 as one unit: locomotion pose + contacts, the reference posture T_p and the level of preparation
// alpha in, the prepared pose out. The player, the controller, the demo and the tools all synthesize
// through this class.
//
// Per frame: blending (Eq. 1-2, blending.h) -> trajectory (Eq. 3-5, trajectory.h) -> foot IK (foot_ik.h)
// -> balance optimization (Eq. 6-10, balance.h).
//
// Memory: a Synthesizer holds what depends only on the skeleton and Params (shared by every character on
// that skeleton). A SynthesisState is one character's memory between frames: plain data, no heap, 1.3
// kilobytes (half of it the balance optimizer's correction for the warm start). A SynthesisScratch holds
// working buffers (one per thread). step() allocates nothing.
#pragma once

#include <array>
#include <memory>
#include <cstdint>
#include <vector>

#include "engine/motion/body_map.h"
#include "engine/motion/center_of_mass.h"
#include "engine/motion/contacts.h"
#include "engine/motion/kinematics.h"
#include "engine/motion/motion_set.h"
#include "engine/motion/pose.h"
#include "engine/motion/skeleton.h"
#include "engine/motion/support_polygon.h"
#include "engine/params/params.h"
#include "engine/synthesis/balance.h"
#include "engine/synthesis/blending.h"
#include "engine/synthesis/foot_ik.h"

namespace prep {

constexpr int kMaxBodyParts = 24;  // body parts of the mass model the state can remember (de Leva has 14-16)

// One character's synthesis memory.
struct SynthesisState {
  bool started = false;
  glm::vec3 previous_locomotion_root{0.0f};  // to take the locomotion's per-frame displacement (Eq. 3-4)
  glm::vec2 root_xz{0.0f};                   // the synthesized root's accumulated floor position
  FootPlants feet;                           // planted feet (foot IK)
  float root_drop = 0.0f;                    // pelvis lowered by the foot IK to keep planted feet in reach (m)
  FootPoints previous_locomotion_feet{};     // the locomotion's heel and toe points at the previous frame
  bool locomotion_feet_known = false;        // ... once a frame has been through the IK stage
  int history = 0;                           // optimized frames remembered (0-2), for Eq. 8-9
  std::array<glm::vec3, kMaxBodyParts> previous{};         // body-part centroids at t-1
  std::array<glm::vec3, kMaxBodyParts> before_previous{};  // ... at t-2
  BalanceCorrection correction;              // the last optimized frame's correction (warm start)
};

struct SynthesisInput {
  const Pose* locomotion = nullptr;  // the locomotion pose L at this frame (world root position)
  FrameContacts contacts{};          // the locomotion's foot contacts at this frame (kept in the output, Sec. 5.2)
  const Pose* reference = nullptr;   // T_p
  float alpha = 0.0f;                // level of preparation
  float dt = 1.0f / 30.0f;           // frame time (s)
  // The locomotion's root displacement since the previous frame. When not given it is taken from the
  // previous call's locomotion root (state.previous_locomotion_root); give it when the locomotion jumps
  // (e.g. the player re-aligned it) or on the first frame of a moving stream.
  bool has_displacement = false;
  glm::vec3 displacement{0.0f};
  // step() ends with stage_floor. A caller that changes the pose further (a cross-fade) and then runs
  // stage_floor itself sets this false, so that the toes are not lifted (and the body's forward kinematics
  // computed) twice.
  bool keep_toes_above_floor = true;
};

struct SynthesisReport {
  float alpha = 0.0f;
  float w_root = 0.0f;
  bool has_support = false;           // some foot in contact
  bool balanced = false;              // the optimizer ran
  bool warm_started = false;          // ... starting from the previous frame's correction
  int balance_steps = 0;
  float balance_shift = 0.0f;         // the largest move of a body-part centroid by the optimizer (m)
  float com_distance_before = 0.0f;   // |COM - support centre| on the floor before optimization (m)
  float com_distance_after = 0.0f;    // ... after
  bool com_inside_before = false;     // COM inside the support polygon before / after optimization
  bool com_inside_after = false;
  FootPoints feet{};                  // heel and toe tips of the output pose (world)
  FrameContacts pinned{};             // the contact points the foot IK held in place (select_pinned_points)
};

struct SynthesisScratch {
  std::vector<float> weights;
  // Eq. 1's weights above are for this alpha and these curves (BlendCurves::id; 0: none yet): a level held
  // from tick to tick does not take them again.
  float weights_alpha = 0.0f;
  std::uint64_t weights_curves = 0;
  std::vector<glm::vec3> positions;
  std::vector<glm::quat> rotations;
  FrameContacts pinned{};
  glm::vec3 locomotion_jump{0.0f};  // how far the locomotion stream was moved this frame beyond its displacement
  SupportPolygon support;
  // `support` is that of the pose the last step() or stage_floor() returned: its feet and contacts are
  // those the balance stage saw (the floor stage changed nothing), and the stage took it (the optimizer
  // could run, or a report asked for it).
  bool support_of_output = false;
  // SynthesisState::previous holds the body-part centroids of that pose.
  bool centroids_of_output = false;
  // The pose the last step() or stage_floor() returned differs from the one the balance stage left only by
  // feet pitched up about their ankles (stage_floor): the body-part centroids it kept (SynthesisState::
  // previous) still stand for every part whose joints are above the ankles.
  bool centroids_but_feet_of_output = false;
};

class Synthesizer {
 public:
  Synthesizer(std::shared_ptr<const Skeleton> skeleton, BodyMap body, const MassModel& mass, const Params& params);
  Synthesizer(const MotionSet& set, const Params& params)
      : Synthesizer(set.skeleton, set.body, set.mass, params) {}

  // Changes the constants (e.g. from the demo's panels); the blending curves are rebuilt.
  void set_params(const Params& params);
  const Params& params() const { return params_; }
  const Skeleton& skeleton() const { return *skeleton_; }
  const BodyMap& body() const { return body_; }
  const BlendCurves& curves() const { return curves_; }
  const BalanceModel& balance_model() const { return balance_model_; }

  SynthesisScratch make_scratch() const;
  Pose make_pose() const { return Pose(skeleton_->size()); }

  // One frame. `out` must have one rotation per joint (make_pose()). Returns whether the balance optimizer
  // shaped it (SynthesisReport::balanced, without the rest of a report).
  bool step(const SynthesisInput& in, SynthesisState& state, SynthesisScratch& scratch, Pose& out,
            SynthesisReport* report = nullptr) const;

  // The stages of step(), in order, for benchmarks and tests.
  void stage_blend(const SynthesisInput& in, SynthesisScratch& scratch, Pose& out) const;
  void stage_trajectory(const SynthesisInput& in, SynthesisState& state, SynthesisScratch& scratch, Pose& out) const;
  void stage_ik(const SynthesisInput& in, SynthesisState& state, SynthesisScratch& scratch, Pose& out) const;
  bool stage_balance(const SynthesisInput& in, SynthesisState& state, SynthesisScratch& scratch, Pose& out,
                     SynthesisReport* report) const;
  // A toe tip below the floor is pitched up to it (keep_toes_above_floor in foot_ik.h). kinematics_given:
  // scratch.positions / rotations already hold the forward kinematics of `out` (the stages before leave
  // them so; a caller that changed the pose since passes false). On return they hold those of the result
  // (every joint), for the caller's COM.
  void stage_floor(SynthesisScratch& scratch, Pose& out, bool kinematics_given = false) const;

 private:
  std::shared_ptr<const Skeleton> skeleton_;
  BodyMap body_;
  Params params_;
  BlendCurves curves_;
  BalanceModel balance_model_;
  // Partial kinematics passes, each level by level (breadth_first), over:
  JointPass all_pass_;            // every joint
  JointPass leg_pass_;            // the leg chains (hip to toe tip) and their ancestors
  JointPass foot_pass_;           // the ankles and every joint below them
  JointPass balance_stale_pass_;  // joints whose kinematics the balance optimizer leaves stale
};

}  // namespace prep
