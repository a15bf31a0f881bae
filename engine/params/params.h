// One source of truth for every tunable of prep, with the paper's defaults.
//
// Every stage of the pipeline reads its constants from here; the demo's panels edit a Params live,
// the tools load it from JSON (`--params FILE`). Sub-structs follow the paper's sections. Where the paper
// is vague or inconsistent, the default chosen is explained beside the field.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace prep {

// Sec. 4 data: per-frame foot contacts (heel and toe) from heights and speeds, with hysteresis.
struct ContactParams {
  // Heights count from where the point rests when planted (contacts.h). Tuned on the CMU walks (daz43
  // and cmu31): 55-72% of frames per foot, alternating single and double support. A planted foot rolls
  // (heel rise, toe pivot) at up to ~0.6 m/s at its heel or toe; a swinging foot moves at 2-4 m/s.
  float height_on = 0.05f;   // m above the planted height: a point below this may enter contact
  float height_off = 0.08f;  // m: a point in contact leaves it only above this (hysteresis)
  float speed_on = 0.8f;     // m/s horizontal+vertical speed under which a point may enter contact
  float speed_off = 1.2f;    // m/s: a point in contact leaves it only above this
  float foot_width = 0.09f;  // m: lateral width of a footprint in the support polygon
};

// Sec. 4.1: hierarchical motion graph.
struct GraphParams {
  float window_s = 0.2f;          // s: window of frames over which the point-cloud distance is taken
  float threshold = 0.35f;        // distance (m, RMS over points) below which a local minimum is an edge
  float blend_s = 0.25f;          // s: duration of the transition blend across an edge
};

// Sec. 4.2: reference posture T_p.
struct ReferenceParams {
  // m^2: sum of squared leg-joint position differences to T_0 (hip, knee, ankle, toe tip of both legs,
  // in the root's floor frame). The paper leaves it open. Chosen below the difference between walking's
  // own two double supports (left foot ahead vs right foot ahead: 2.4-2.5 m^2 in the built-in walk), so
  // T_p's legs are never further from T_0 than one step of the walk, while the set-up stances the targets
  // are keyed with pass: the boxing guard (1.4), the gathered feet before the jump's crouch (0.7), the
  // kick's planted foot (1.8). Kneeling and deep crouches (2.1-3.2) do not.
  float legs_threshold = 2.0f;
};

// Sec. 5.1: movement style synthesis, Eq. 1-2.
struct BlendParams {
  // Eq. 1: w_i = c_i * sqrt(1 - (1 - alpha)^C_i). With Eq. 1 as printed a larger C_i rises faster, so the
  // paper's printed values (legs 1.0, upper body 0.5) would make the legs lead, the opposite of what
  // Sec. 5.1 and Fig. 6 describe. We keep the described behaviour: the upper body gets the fast curve.
  float C_upper = 1.0f;           // arms, torso, neck, head: adapt first
  float C_lower = 0.5f;           // root and legs: adapt over a longer period (also slows the stride, Eq. 3-4)
  float c_scale = 1.0f;           // c_i (undefined in the paper): a per-joint scale, 1 so that alpha = 1 reaches T_p
  std::map<std::string, float> C_override;  // per-joint C_i by joint name
  std::map<std::string, float> c_override;  // per-joint c_i by joint name
  std::string method = "ours";    // "ours" (per-joint curves) or "linear" (one weight alpha for all joints)
};

// Sec. 5.2: foot inverse kinematics.
struct IkParams {
  float knee_soft_start = 0.97f;  // fraction of full leg length where the reach starts being softened
  float reach_limit = 0.999f;     // fraction of full leg length the softened reach tends to: the knee keeps ~5 deg
  float release_s = 0.2f;         // s: after lift-off a foot's IK correction fades out over this time
  float pivot_speed = 0.15f;      // m/s: heel and toe both slower than this = a flat foot, both pinned
  float max_root_drop = 0.2f;     // m: the pelvis may be lowered at most this much to keep planted feet in reach
  float drop_recovery_speed = 0.3f;  // m/s: how fast that drop recovers when no longer needed
  bool enabled = true;
};

// Sec. 5.3: balance optimizer, Eq. 6-10.
struct BalanceParams {
  float w_b = 2.0f;               // Eq. 10 balance weight (the paper's "w_d" is a typo for w_b)
  float w_s = 1.0f;               // Eq. 10 postural style weight
  float w_m = 0.25f;              // Eq. 10 smoothness weight
  int max_steps = 10;             // gradient-descent steps at most
  float alpha_threshold = 0.3f;   // no optimization below this level of preparation
  float step_size = 0.5f;         // initial gradient step (radians per unit gradient)
  float tolerance = 1e-5f;        // stop when the cost improves by less than this (a local optimum)
  int max_halvings = 4;           // backtracking line search: halve the step at most this often per step
  float norm_smoothing = 1e-3f;   // m: |x| is taken as sqrt(|x|^2 + e^2) - e so the cost is differentiable at 0
  // Trust region of the correction (balance.h explains why Eq. 6-10 need one): no body-part centroid moves
  // further than this from the blended posture (m), nor faster than max_shift_speed from where the
  // previous frame's correction left it (m/s). A value <= 0 removes the bound.
  float max_part_shift = 0.06f;
  float max_shift_speed = 0.3f;
  bool warm_start = true;         // start each frame's descent from the previous frame's correction
  bool enabled = true;
};

// Sec. 6.1, Table I: quantization of the state s = {alpha, m, d_g, theta_g, d_i, theta_i}.
struct QuantizationParams {
  float d_step = 0.4f;            // m, for d_g and d_i
  int d_g_bins = 5;
  int d_i_bins = 5;
  float theta_g_step_deg = 45.0f;
  int theta_g_bins = 8;
  float theta_i_step_deg = 90.0f;
  int theta_i_bins = 4;
  float alpha_step = 0.2f;
  int alpha_levels = 6;           // 0, 0.2, ..., 1.0: 6 levels give the paper's 19,200 states (Table I prints 5)
  // The top level (alpha = 1) is the forcing's alone (Eq. 13 at the source): actions choose among the
  // levels below it, Table I's 5 samples (0, 0.2, ..., 0.8), while the state has all 6 (state.h). At
  // alpha = 1 Eq. 3-4 leave no stride, so an action at 1 is standing still, which with the discount of
  // 0.3 is worth more to the learner than walking the last metres to the launch point (reward.h).
  bool forced_top_level = true;
  // The graph's core locomotion nodes the controller plays (the m of Eq. 11-12; the paper has four). Each
  // entry is a role (the set's first cyclic clip of it) or a clip name. Empty (the default) is the set's
  // own: its walk, its turns both ways and its slow walk when it has one (default_core_clips in
  // action_effects.h), so a motion set needs no Params file of its own. The paper's core nodes are "the
  // cyclic walking motions": walking, turning both ways and a slower walk. Standing (idle) is left out on
  // purpose: Eq. 17 pays 0.85 of its 1.0 for standing still facing the goal, so with the discount of 0.3
  // a learner that can stand stays where it is rather than pay Eq. 16 on the way in (sarsa.h).
  std::vector<std::string> core_roles;
  // An action (Eq. 12) plays its core motion for this many footsteps: 2 = one gait cycle, one loop of a
  // walk, which is where a hierarchical motion graph passes from one core node to another, and a turn of
  // one theta_g bin (45 degrees) for the built-in turns. action_effects.h explains why not one footstep.
  int footsteps_per_action = 2;
};

// Sec. 6.2: reward, Eq. 14-17.
struct RewardParams {
  float theta_norm_deg = 180.0f;
  float d_norm = 1.0f;            // m
  float C_alpha = 2.0f;
  float w_theta = 0.1f;
  float w_d = 0.3f;
  float w_alpha = 0.6f;
  float goal_radius = 0.4f;       // m: the goal counts as reached within this distance
  // m: within this radius of the source the character has "reached" it: alpha is forced to 1 (Eq. 13),
  // in training and, for the controller's state, at run time. Chosen in engine/control/reward.h.
  float source_radius = 1.0f;
};

// Sec. 6.3-6.4: SARSA, Eq. 18-19.
struct SarsaParams {
  float learning_rate = 0.7f;     // lambda in Eq. 19 (the paper's "rate of learning")
  float discount = 0.3f;          // gamma in Eq. 18-19
  float epsilon = 0.1f;           // epsilon-greedy
  float convergence_fraction = 0.02f;  // stop when Q updates per episode < this fraction of the states ...
  int convergence_episodes = 5000;     // ... in a round of this many episodes (sarsa.h)
  float update_tolerance = 1e-4f; // a Q change smaller than this does not count as an update
  std::uint64_t seed = 1;
  std::int64_t max_steps = 200000000;
  int threads = 2;
  int max_episode_steps = 200;
  // Sec. 6.1: goal and source are "usually identical"; this fraction of the training episodes puts the
  // source on the goal, the rest place it independently (Fig. 9), so both kinds of state are explored.
  float source_at_goal_fraction = 0.5f;
  // Exploring starts in the last distance bin ("that far or farther") are drawn out to this multiple of
  // the quantized range (d_step x bins), the distances prep evaluate-policy starts from (environment.h).
  float far_start_range = 2.0f;
};

// Sec. 6 at run time and the simulation loop.
struct RuntimeParams {
  float alpha_sigma_s = 0.25f;    // s: sigma of the Gaussian filter over alpha
  float fixed_dt = 1.0f / 60.0f;  // s: engine tick
  // Arrival at the source (engine/control/arrival.h): the smoothed alpha at which a character that has
  // come to its launch point is prepared enough to launch the target motion where it stands.
  float launch_alpha = 0.9f;
  // Beyond the paper, each switchable (off = the paper's behaviour exactly, for comparison):
  // m: a source of influence calls for preparation when its launch point lies at most this far ahead along
  // the approach (engine/world/world.h, "in range"). About 4 s of walking at 1.4 m/s: the policy raises
  // alpha from 0 to its approach level (0.8) a level or two per gait cycle (Eq. 16 penalises jumps), and an
  // opponent walks toward the character meanwhile. On 200 random courses (prep evaluate --random 200
  // --seed 1) 4 m left 84% of the launches at alpha >= 0.5 one metre before and a median path 1.153 x the
  // straight route (the policy, relaxed too late, turned for sources still far); 6 m gave 86% and 1.142.
  float preparation_range = 6.0f;
  // Relaxation: with no source in range the alpha played is 0 whatever level the controller chose (its
  // decisions and state stay the paper's), so the smoothed alpha falls to 0 after the filter's 3 sigma and
  // stays there while the character stands at its goal. Nothing in Eq. 14-17 lowers alpha when nothing is
  // near (Eq. 16 only penalises change). Restricting the policy to its level-0 actions instead met values
  // training rarely refined: a character turned away from an opponent 8 m ahead.
  bool relax_without_source = true;
  // Kept preparation (Sec. 7.2 and 8: "the character maintains the preparation style if there are remaining
  // targets nearby"): coming back from a target motion with the next source in range, the controller
  // resumes at this level instead of 0. Negative: resume at 0, as the paper's graph edge into plain
  // locomotion implies.
  float kept_alpha = 0.8f;
  // Tight turns: when the goal lies inside the circle of the walking turns (closer than their turning radius
  // allows) or behind the character, the stride shortens and the heading turns toward the goal at up to
  // this rate on top of the played motion, about the foot the character stands on
  // (engine/world/steering.h). 180 deg/s pivots a quarter turn in a step of half a second, as people do in
  // a sharp turn. 0: off.
  float tight_turn_deg_per_s = 180.0f;
  // m: a waypoint that is not the last counts as passed when the character goes by it within this distance
  // (it is beside or behind the character: steering.h, passed_waypoint), as well as on entering
  // RewardParams::goal_radius. 0: only the goal radius.
  float waypoint_pass_radius = 1.0f;
  // A source that closes in (an opponent walking up) is shown to the controller where a still one would
  // leave the same time to prepare: training's sources stand still, so the policy reads distance as time
  // at the character's own pace (engine/world/world.h).
  bool anticipate_closing = true;
  // A turn action toward the goal ends, and the controller decides again, once the goal's bearing has
  // crossed to the other side. An action plays its clip's whole gait cycle (Sec. 6), and a turn begun a few
  // degrees off the goal swings the heading past it into the next bin of theta_g, whose action turns back:
  // on a quarter of 200 random built-in courses the turns went left, right, left within 3 s (weaving).
  bool end_turn_at_goal_bearing = true;
  // A source ahead is not turned away from: while the source lies within 45 degrees of the facing (within
  // preparation_range or beyond it), the controller passes over the turn actions that would leave both it
  // and the goal further off the facing than they are (a turn away, or one toward that swings past by more
  // than they are off). The policy values a turn away from a source dead ahead within a few per cent of
  // walking on (built-in kick, 4 m: Q 1.26 for turn_right against 1.20 for walk), and played, the turn's
  // gait cycle swings the approach out and back: the built-in kick scenario walked an S of -70 to +57
  // degrees on its way to the ball straight ahead, and 10 of 12 such approaches in the tests swung out past
  // 45 degrees.
  bool keep_source_ahead = true;
  // The level of preparation is chosen again, for the motion playing, whenever the source comes a distance
  // bin nearer (the state's d_i, QuantizationParams::d_step) than where the last choice was made. An action
  // plays its motion's whole gait cycle (Sec. 6), and even at a prepared pace a cycle covers more than a
  // bin (at alpha 0.4 a cycle of the built-in walk goes 0.80 m, cmu31's 0.57 m; the bins are 0.4 m), so a
  // level chosen two bins out was kept until the source was within a metre: on 200 random cmu31 courses
  // with varied sizes (seed 1) 10.7% of the launches were still below alpha 0.5 a metre before. Only the
  // level changes, as the policy chooses it in the state the character is now in; the motion keeps its
  // cycle (the graph passes between core nodes at their loops), and the next decision comes when the action
  // ends, as before.
  bool level_per_source_bin = true;
  // Unattended (a scenario's "auto"), the user makes for a ball that is its source in range and nearer than
  // the waypoint or goal it makes for, as a player steering with the keys would, and kicks it. The policy
  // is rewarded for the goal alone (Eq. 14-17): it walked on toward a goal to one side of a ball and left the
  // ball on the other, even after turning to it and preparing (22 of 24 generated balls 25-55 degrees to
  // one side, the goal to the other; on the random built-in courses 1-9 objects of each set of 200 were
  // never acted on, and none are with it). With it, too, a ball on the way to the goal is not passed as
  // behind a character turned off its way (a fight leaves it facing where the opponent stood).
  bool make_for_ball_source = true;
  // Bodies kept out of obstacles: a body that has gone into an obstacle it is not crossing with a target
  // motion (a leg swung into a hurdle's board by a turn just after it, a head walked into a rail) is set
  // back out along the obstacle's crossing direction (engine/world/bodies.cpp); a kicked ball bounces off
  // the obstacles, bodies and balls it meets (engine/world/rolling_balls.cpp). Off: both go through.
  bool keep_clear = true;
};

struct Params {
  ContactParams contacts;
  GraphParams graph;
  ReferenceParams reference;
  BlendParams blend;
  IkParams ik;
  BalanceParams balance;
  QuantizationParams quantization;
  RewardParams reward;
  SarsaParams sarsa;
  RuntimeParams runtime;
};

// JSON in/out. Missing fields keep their defaults; unknown fields and wrong types are errors that name
// the file and the field. Saving is atomic (temporary file + rename).
Params load_params(const std::string& path);
void save_params(const Params& params, const std::string& path);
std::string params_to_json(const Params& params);
Params params_from_json(const std::string& text, const std::string& source_name);

// The ranges loading checks (params_from_json calls it): every number at least 0 unless its use says
// otherwise, counts at least 1, steps and the tick above 0, fractions and probabilities within [0, 1], and the
// state space's own rules ((alpha_levels - 1) x alpha_step = 1; the angle bins cover 360 degrees). Throws
// InputError naming the source and the field, so a value no part of the engine can use never gets in.
void check_params(const Params& params, const std::string& source_name);

// A stable hash of the fields a trained policy depends on (quantization, reward, SARSA constants and the
// lower-body blend curve), written into policy files so that a mismatched policy is refused.
std::uint64_t policy_params_hash(const Params& params);

}  // namespace prep
