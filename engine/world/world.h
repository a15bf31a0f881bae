// The world (Sec. 7.2): characters, objects, goals and sources of influence, and the fixed-step
// simulation loop every front end drives (RuntimeParams::fixed_dt).
//
// Per tick and per character:
//   source of influence (kick: the ball; fight: the closest opponent; obstacles: the closest obstacle in the
//   facing direction) -> controller (a = {m, alpha}, Sec. 6, one decision per action) -> Gaussian-smoothed
//   alpha -> the motion stream plays m through the motion graph -> Synthesizer::step (blend toward the T_p of
//   the action the source calls for, trajectory, foot IK, balance) -> pose.
//
// Where each part lives: world.cpp the tick (control, launches, kept preparation, goals); world_steering.cpp
// where each character makes for and its tight turns and squaring up (the geometry in steering.h);
// sources.cpp the sources of influence, launch points, the approach and the arrival; target_motions.cpp the
// assets (T_p, reach, release and advance of each target clip); summary.cpp the run summaries; bodies.cpp
// the obstacle fit of a pose and characters kept apart.
//
// Choices where the paper leaves it open (each also stated where it is coded):
// - The source point the controller sees is the launch point of the object: where the character must
//   stand, facing the object, for the target clip entered at its T_p frame to meet the object (a bar
//   passes over the crawl, the foot meets the ball). The controller's state there is the training's:
//   within RewardParams::source_radius of it the state's alpha is 1 (controller.h).
// - Arrival (engine/control/arrival.h): once the launch point, ahead, is within the arrival radius, the
//   played alpha is forced to 1 (Sec. 6.2's forcing "when the character reaches the source"); the
//   smoothed alpha rises, Eq. 3-4 fade the stride out and the character glides to a stop on the launch
//   point. No decisions are taken meanwhile. The arrival ends when the source changes or moves out of the
//   radius.
// - A launch (user or auto) restarts the character's stream at the target clip's T_p frame, root placed
//   where the character stands and facing where it faces: the prepared posture is T_p (alpha -> 1), so
//   this entry is continuous; the remaining difference is cross-faded over GraphParams::blend_s. The
//   target clip then returns to locomotion through a graph edge after T_t (MotionStream).
// - Auto launch: with the object ahead (within 45 degrees of the facing), when the character is on its
//   launch point (its distance along the approach is at most the action's reach, the distance from the T_p
//   root to the object in the clip) or, arrived, as soon as its smoothed alpha reaches
//   RuntimeParams::launch_alpha. So alpha_at_launch is what the approach delivered: a character that
//   comes in fast passes the point before the forcing has raised its alpha.
// - Kept preparation (Sec. 7.2 and 8, "the character maintains the preparation style if there are remaining
//   targets nearby"): when the next source is in range (RuntimeParams::preparation_range) once the target
//   movement is over (TargetMotion::release_frame), the character leaves the target clip there, before its
//   get-up or walk-out, for the core walk entered at its best-matching frame and cross-faded over
//   kKeptFadeSeconds, and the controller resumes at RuntimeParams::kept_alpha with the Gaussian filter
//   restarted there: the body stays low between two close obstacles and the next launch point, which may lie
//   inside the previous clip's walk-out, is met by locomotion that can stop on it. A clip whose graph edge
//   comes first returns through it, at the kept level when the next source is in range. An obstacle whose
//   launch point is already behind is entered straight out of the clip, at the frame that has come as far:
//   at the release frame, or sooner where the clip played on would rise into it (a crawl's get-up under a
//   second bar 1.5 m on), as soon as the next clip stands clear of the obstacle being left.
// - Otherwise, after a target motion the controller resumes at alpha 0: the clip's graph edge leads into
//   the plain core locomotion, which is what alpha 0 plays.
// - Relaxation (RuntimeParams::relax_without_source): with no source in range the played alpha is 0 while
//   the controller decides as in the paper (controller.h, tick): the smoothed alpha falls to 0 within the
//   filter's 3 sigma, and rises back to the policy's level when a source comes into range.
// - Tight turns and waypoints (steering.h): a goal inside the walking turns' circle, or behind with no
//   source in range, is turned toward about the stance foot; a waypoint other than the last counts as
//   passed when the character goes by it.
// - Bodies kept clear (clearance.h measures it): an obstacle is launched at facing its crossing (the arrival
//   turns the character; one standing still off square launches, the rest of the turn in the cross-fade),
//   and the clip is slid onto the obstacle (short of, past or beside its launch point) before the body
//   reaches it, then fitted to its height (obstacle_fit.h); the launch lines up along the obstacle where
//   its clip has room before the next obstacle, and the next obstacle's clip room to follow on out of it
//   (launch_lateral), and out of a previous clip, within a
//   metre of the next launch point, the character squares up to it already (steering.h); a kick's wind-up is slid onto the ball; an
//   obstacle the way to the goal crosses near its end is a source, walked along to; a body that gets into
//   an obstacle anyway is set back out of it (RuntimeParams::keep_clear). Opponents hold short of striking
//   distance and strike once the user is within their reach; one struck at counters after the strike
//   (striking_at); a defeated one steps aside; roots stay kPersonalSpace apart, kFacingSpace facing
//   (bodies.cpp). An opponent waits while the user crosses an obstacle between them or kicks a ball on its
//   way (waits_its_turn); one the set has no strike for stands aside (stands_aside). A kicked ball bounces
//   off what it meets (rolling_balls.cpp).
// - No source: the controller is shown one 100 m behind the character, a source it walks away from and
//   never reaches (beyond the last distance bin, behind), the state in which training learned that
//   nothing calls for preparation. (One 100 m ahead would share its state with every source beyond the
//   quantized range, 1.6 m or more ahead, for which the policy has learned to start preparing.)
// - Objects are used once (a kicked ball rolls away; a punched opponent stops fighting); obstacles behind
//   the character or already passed stop being sources, unless the way on leads back over one that was
//   crossed (a waypoint on its far side): then it is crossed again. A crossing that ended on the side it
//   began is not tried again: a clip that does not carry the body across would try for ever.
// - Opponents: their own controller (the same policy) with the user's character as goal and source
//   (the point at punch reach in front of it); they arrive and launch by the same rules, at most once per
//   OpponentRules::cooldown_s. For a source that moves (an opponent for the user, the user for an
//   opponent) the arrival radius grows by what it covers toward the character meanwhile (arrival.h).
// - Unattended (auto on), a user whose source is an opponent takes that opponent's launch point as its goal
//   until it is defeated, as a player steering with the keys would (Sec. 7.2: "the user uses the keyboard
//   to indicate the goal"); the scenario's goal comes back after. The controller's goal is only its own
//   steering; reaching the scenario's goal is still judged on the scenario's goal.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <chrono>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "engine/control/controller.h"
#include "engine/control/policy.h"
#include "engine/graph/motion_graph.h"
#include "engine/motion/motion_set.h"
#include "engine/motion/support_polygon.h"
#include "engine/synthesis/synthesizer.h"
#include "engine/world/object_solids.h"
#include "engine/world/obstacle_fit.h"
#include "engine/world/scenario.h"

namespace prep {

class BodyVolumes;
class MotionStream;

constexpr int kTargetActionCount = 6;

// What the world knows about one target action of the motion set.
struct TargetMotion {
  TargetAction action = TargetAction::Kick;
  int clip = -1;              // the target clip (graph node); -1: the set has none
  int reference_frame = 0;    // T_p (Sec. 4.2)
  Pose reference;             // T_p's pose
  float reach = 0.0f;         // m: from the root at T_p, along its facing, to where the clip meets the object
  float lateral = 0.0f;       // m: that point's offset to the left of the facing
  // The first clip frame at which the target movement is over (the body has passed the obstacle, the
  // strike has landed): from here the character may leave the clip for prepared locomotion when another
  // source is near (world.h, "kept preparation"). -1: the clip always plays to its graph edge.
  int release_frame = -1;
  // m: how far the root has come along the T_p facing at release_frame: where, out of this clip, the root
  // stands when the next obstacle's clip may start (launch_room_short).
  float release_advance = 0.0f;
  // m: how far the root has come along the T_p facing at each frame from T_p to last_entry_frame (T_t, or
  // for an obstacle clip the frame its fit begins to fade in; advance[0] = 0 at T_p). A character that
  // reaches an obstacle already past its launch point (out of the previous target clip, between two close
  // obstacles, or turned to it late) enters the clip at the frame that has come as far (entry_frame).
  std::vector<float> advance;
  int last_entry_frame = 0;
  int entry_frame(float past_launch_point) const;
  // Kicks and punches: the frame at which the strike meets its target (the effector's fastest forward
  // movement before its farthest reach; -1: none) and the effector's speed there (m/s). A kick's reach and
  // lateral place the ball where the foot touches a ball of kBallDiameter at this frame; the ball leaves then.
  int strike_frame = -1;
  float strike_speed = 0.0f;
};

constexpr float kBallDiameter = 0.22f;  // m: a football; the kick's reach is for this size
// m: a launch point stays this far inside an obstacle's ends (launch_point): the crawl's hands reach 0.4 m
// to the side, and a crossing up to 10 degrees off square drifts 0.3 m more.
constexpr float kSpanMargin = 0.8f;
// m between two characters' roots on the floor, at least: two trunks, the arms swinging beside them and
// the feet of a stride.
constexpr float kPersonalSpace = 0.8f;
// m between the roots of two characters facing each other squarely: their guards' lead hands stay apart.
constexpr float kFacingSpace = 1.0f;
// m: without preparation, two characters of whom one strikes at the other are kept apart at most to this
// short of its launch point, so that it can reach it (World::keep_apart).
constexpr float kStrikeSlack = 0.05f;
// m/s: the fastest two characters kept apart are set back (World::keep_apart).
constexpr float kMaxShoveSpeed = 3.0f;
// m: an opponent holding short of its launch point strikes once the user has come this near to it.
constexpr float kOpponentStrikeSlack = 0.1f;
// s after a punch lands before its arm is back in guard (the built-in punch's recovery, 0.36 s); one
// punched at waits for it before it counters (World::try_auto_launch).
constexpr float kStrikeRecovery = 0.35f;
// rad: a character arrived at another keeps facing it within this (World::steer_tightly).
constexpr float kFacingSlack = 15.0f * 3.14159265f / 180.0f;
// m: a body set out of an obstacle (World::keep_clear_of_obstacles) is left this far clear of it.
constexpr float kClearSkin = 0.005f;
// m: two characters' bodies are kept this far apart (World::keep_bodies_apart).
constexpr float kBodyGap = 0.03f;
// m: nearer than this to its launch point at another character, a character makes for that character.
constexpr float kLaunchPointNear = 0.5f;
// m: a defeated opponent steps this far aside, out of the user's way (World::defeat).
constexpr float kStepAside = 2.0f;
// m: a character this far past an obstacle's line from the side it launched at it from has been carried
// across (WorldObject::carried_across): clear of the rail and of a root that ends under it.
constexpr float kCarriedAcross = 0.5f;
// m: an obstacle clip left early for the next crossing (World::leave_early_for_next_crossing) may enter the
// next clip this far short of its launch point; the launch slides the clip on by the rest.
constexpr float kEarlyChainSlack = 0.1f;
// m: a character standing reaches about this far around its root on the floor (World::body_on_crossing).
constexpr float kStandingRadius = 0.3f;
// m: stepping out of someone's way across an obstacle, a character leaves this much more (World::make_way).
constexpr float kMakeWayMargin = 0.5f;
// rad: it turns where it stands until its way aside is within this of its facing (World::turning_to_step_aside).
constexpr float kStepAsideTurn = 30.0f * 3.14159265f / 180.0f;

// Everything a world needs that does not depend on the scenario: the motion set, its graph, the
// synthesizer, the target motions and the controller's policy. Shared by worlds (and threads) read-only.
struct WorldAssets {
  Params params;
  std::shared_ptr<const MotionSet> set;
  std::shared_ptr<const MotionGraph> graph;
  std::shared_ptr<const Synthesizer> synthesizer;
  std::vector<TargetMotion> targets;   // indexed by TargetAction
  std::vector<ClipSweep> sweeps;       // indexed by TargetAction: the body over each obstacle clip (obstacle_fit.h)
  // Indexed by TargetAction: how far each obstacle clip's body reaches beyond T_p by the frame the character
  // may leave it (its release frame, else its end), by height (obstacle_fit.h).
  std::vector<BodyReach> body_reaches;
  std::vector<int> core_nodes;         // graph node of each policy core motion (index = policy motion)
  // The skeleton's body capsules (keep_clear_of_obstacles): one table for all worlds, so that a crowd
  // reads it from cache instead of each world its own copy.
  std::shared_ptr<const BodyVolumes> volumes;
  // The mass segments whose centroid moves when a foot is pitched about its ankle (the floor stage): after
  // such a tick the world takes only theirs again.
  std::vector<int> foot_segments;
  // Where characters stop: the idle clip (a set without one has a stand held from its walk, held_stand.h;
  // they start on the walk then), else the walk. Where they start otherwise.
  int idle_node = -1;
  std::shared_ptr<const Policy> policy;

  const TargetMotion& target(TargetAction a) const { return targets[static_cast<size_t>(a)]; }
};

class ArrivalModel;

// Builds the graph, the T_p and reach of every target action and the synthesizer. The policy is set apart
// (policy_cache.h). Throws InputError naming the set when a core role has no cyclic clip.
WorldAssets make_world_assets(std::shared_ptr<const MotionSet> set, const Params& params);
// The motion set a scenario names ("builtin" or a manifest path relative to the repository root).
std::shared_ptr<const MotionSet> load_scenario_motions(const Scenario& scenario, const Params& params);
// The Params a scenario names (its "params" file) or the defaults.
Params load_scenario_params(const Scenario& scenario);
// Whether two Params make the same assets (the motion graph, T_p, the core motions): their contacts, graph,
// reference and quantization sections are equal. Other changes apply to a running world (set_params).
bool same_world_assets_params(const Params& a, const Params& b);
// All of it, blocking: the scenario's motions, the assets, and the policy from the cache folder or trained
// now (policy_cache.h). `trained` tells whether training ran.
std::shared_ptr<const WorldAssets> prepare_world_assets(const Scenario& scenario, const Params& params,
                                                        const std::string& cache_dir, bool* trained = nullptr);

struct LaunchRecord {
  int character = -1;
  TargetAction action = TargetAction::Kick;
  int object = -1;            // the object it was launched at (-1: none)
  int target_character = -1;  // the character it was launched at (fights; -1: none)
  float alpha_at_launch = 0;  // the smoothed alpha synthesis used on the tick of the launch
  float time = 0;             // world time (s)
  bool automatic = false;     // by the scenario's auto flag or an opponent's rules (not the user)
  // The approach, for judging the preparation behind alpha_at_launch (-1: not seen for this source):
  float level_at_arrival = -1;  // the level the controller had chosen itself when the arrival began
  float alpha_at_1m = -1;       // the smoothed alpha when the launch point first came within 1 m
  float miss = 0;               // m: distance still to go to the launch point (< 0: past it) at the launch
  // m: how far the launch slid the clip onto its object (World::start_target): along the facing (< 0: held
  // back) and to the side.
  float slide_forward = 0, slide_side = 0;
  float turn = 0;  // rad: the turn taken in the launch's cross-fade to face the obstacle's crossing or the ball
};

struct OpponentRules {
  float cooldown_s = 2.5f;    // between two punches of one opponent
};

struct WorldObject {
  ScenarioObject spec;
  glm::vec3 position{0.0f};   // where it stands now (a kicked ball rolls)
  glm::vec2 velocity{0.0f};   // m/s on the floor (a kicked ball)
  bool used = false;          // its action was launched at it
  // Across obstacles: the side (+1 along its crossing direction, -1 against) of its last launch, and whether
  // the character has since stood clear on the far side (the clip carried it across).
  float launched_from = 0.0f;
  bool carried_across = false;
  int character = -1;         // for opponents: the character it is
};

struct WorldCharacter {
  Control control = Control::User;
  TargetAction met_with = TargetAction::PunchRight;  // opponents: the action the user meets it with
  int object = -1;                                   // opponents: their object, if they came from one
  bool defeated = false;                             // opponents: punched, no longer fighting

  Pose pose;                  // the synthesized pose (world)
  glm::vec2 position{0.0f};   // root on the floor (x, z)
  float heading = 0.0f;
  float alpha = 0.0f;         // the Gaussian-smoothed level of preparation synthesis used this tick
  float chosen_alpha = 0.0f;  // the controller's last chosen level
  int motion = -1;            // the policy core motion chosen last
  int clip = -1;              // the clip playing now
  bool in_target = false;     // playing a target motion
  TargetAction playing = TargetAction::Kick;  // which, when in_target (the last one played, after)
  // The character a punch's striking arm is out at (-1: none): from the launch until the arm is back in
  // guard, at the clip's end or at the end of the cross-fade out of a clip left early (kept preparation).
  int arm_out_at = -1;

  bool has_source = false;
  glm::vec2 source{0.0f};               // the source point the controller sees (the launch point)
  glm::vec2 source_object_position{0.0f};  // the object or character that is the source
  int source_object = -1;               // index into objects(), or -1
  int source_character = -1;            // index into characters(), or -1
  TargetAction prepared_for = TargetAction::Kick;  // whose T_p the synthesis blends toward
  // Arrival at the launch point (engine/control/arrival.h): the distance still to go to it along the
  // approach (< 0: past it; infinite without a source), whether the source lies ahead, and whether the
  // character has arrived (its played alpha forced to 1).
  float to_launch = 0.0f;
  bool source_ahead = false;
  bool arrived = false;
  // The source calls for preparation: it lies ahead and its launch point is within
  // RuntimeParams::preparation_range along the approach. Without one in range the character relaxes.
  bool source_in_range = false;
  float level_at_arrival = -1.0f;  // for the launch record (LaunchRecord)
  float alpha_at_1m = -1.0f;

  std::vector<glm::vec2> goal;  // waypoints left (front = current); empty when the last was reached
  bool reached_goal = false;
  float reached_time = -1.0f;

  // Balance (Sec. 5.3) of this tick's pose: kept while the world's balance view is on (set_balance_view).
  glm::vec3 com{0.0f};
  SupportPolygon support;
  bool com_in_support = false;
  FrameContacts contacts{};
  bool balanced = false;  // the balance optimizer shaped this tick's pose
  float last_attack = -1e9f;
};

// The read-only scene for a renderer (app/render converts it; the world stays GL-free).
struct WorldScene {
  struct Character {
    std::shared_ptr<const Skeleton> skeleton;
    const Pose* pose = nullptr;
    bool user = false;
    bool is_source = false;            // the user's source of influence
    float alpha = 0.0f;
    glm::vec3 com{0.0f};
    const SupportPolygon* support = nullptr;
  };
  struct Object {
    ObjectType type = ObjectType::Ball;
    TargetAction action = TargetAction::Kick;
    glm::vec3 position{0.0f};
    float heading = 0.0f;
    glm::vec3 size{0.0f};
    bool is_source = false;
    bool used = false;
  };
  std::vector<Character> characters;
  std::vector<Object> objects;          // opponents are characters, not objects, here
  std::vector<glm::vec3> goal;          // the user's waypoints left (front = current)
  float goal_radius = 0.4f;
  std::optional<glm::vec3> source;      // the user's source of influence (object or opponent position)
  std::optional<glm::vec3> launch_point;  // where the user will launch at it
  float source_radius = 0.4f;
  const std::vector<glm::vec2>* alpha_history = nullptr;  // the user's (time, alpha): World::alpha_history()
};

class World {
 public:
  static constexpr int kAlphaHistory = 600;  // ticks of alpha kept at least (10 s at 60 Hz)

  // The assets must hold a policy. Throws std::invalid_argument otherwise.
  World(const Scenario& scenario, std::shared_ptr<const WorldAssets> assets);
  ~World();
  World(const World&) = delete;
  World& operator=(const World&) = delete;

  void step();                  // one tick of assets().params.runtime.fixed_dt
  // Asks the processor for the memory the next step() reads, so that a caller stepping many worlds
  // overlaps one world's memory traffic with another's work (util/prefetch.h). The memory is a tree of
  // pointers; each level is what the level before points to: level 0 the world itself, then its arrays,
  // then the characters' state, and so on to kPrefetchLevels - 1. Level L of a world is asked for when
  // level L - 1 has had time to arrive (prefetch_ahead), so no level waits on a miss.
  static constexpr int kPrefetchLevels = 6;
  void prefetch(int level) const;
  void run(float seconds);      // ticks until `seconds` more have passed
  float time() const { return time_; }
  int ticks() const { return ticks_; }

  // User intent. launch(): the user character starts the target motion at once (false if it is already
  // playing one or the set has no clip for it). set_goal(): a new single goal for the user.
  bool launch(TargetAction action);
  void set_goal(glm::vec2 goal);
  void set_auto(bool on) { auto_launch_ = on; }
  bool auto_launch() const { return auto_launch_; }
  // Preparation off = the naive baseline (motion-graph concatenation): the controller still
  // picks motions, but synthesis gets alpha 0 and the characters' reported alpha is 0 until a launch.
  // The controller chooses among all its actions, as with preparation, and only the played stride is the
  // unprepared one: limited to level-0 actions it met Q values of states its training rarely reached
  // with alpha 0 near the source, and circled the ball instead of kicking it.
  void set_preparation(bool on) { preparation_ = on; }
  bool preparation() const { return preparation_; }
  // The user's source of influence picked by hand (the demo's mouse): objects()[object] (an opponent
  // object picks its character) is the source while it can still be acted on (unused, not defeated), then
  // the automatic choice resumes. -1 returns to the automatic choice at once. Out of range: ignored.
  void set_source(int object);
  int picked_source() const { return picked_source_; }
  // Changes Params live (the demo's panels): the synthesizer is rebuilt, the run-time rules read the new
  // values from the next tick, and a new alpha filter width reaches every controller; the policy stays
  // (retrain it through policy_cache.h when policy_params_hash changes, then set_policy).
  void set_params(const Params& params);
  void set_policy(std::shared_ptr<const Policy> policy);

  const Scenario& scenario() const { return scenario_; }
  const WorldAssets& assets() const { return *assets_; }
  const Params& params() const { return params_; }
  const std::vector<WorldCharacter>& characters() const { return characters_; }
  const std::vector<WorldObject>& objects() const { return objects_; }
  const std::vector<LaunchRecord>& launches() const { return launches_; }
  int user() const { return user_; }
  bool goal_reached() const { return characters_[static_cast<size_t>(user_)].reached_goal; }
  // The run is done: the user's goal is reached and no character plays a target motion.
  bool done() const;
  // Steps until the run has been done for `after_done` seconds, or `max_seconds` have passed, calling
  // observe(*this) after every step (the evaluations' unattended runs).
  template <class Observe>
  void run_until_done(float max_seconds, float after_done, Observe&& observe) {
    const float dt = params_.runtime.fixed_dt;
    const int max_ticks = static_cast<int>(std::lround(max_seconds / dt));
    const int tail_ticks = static_cast<int>(std::lround(after_done / dt));
    int done_at = -1;
    for (int k = 0; k < max_ticks; ++k) {
      step();
      observe(*this);
      if (done_at < 0) {
        if (done()) done_at = ticks_;
      } else if (ticks_ >= done_at + tail_ticks) {
        break;
      }
    }
  }
  // The user's (time, alpha) of every tick, oldest first: the last kAlphaHistory ticks at least (up to
  // twice as many are kept, so that trimming it costs nothing per tick).
  const std::vector<glm::vec2>& alpha_history() const { return alpha_history_; }
  // Wall-clock milliseconds of the last step(), by stage, summed over the characters (the demo's timings).
  struct StageTimes {
    double control_ms = 0;    // source of influence, controller decision, Gaussian alpha
    double motion_ms = 0;     // the motion stream (graph player), target-motion bookkeeping
    double synthesis_ms = 0;  // Synthesizer::step (blend, trajectory, foot IK, balance) and cross-fades
    double balance_ms = 0;    // COM and support polygon of the pose, goals, auto launch
    double total_ms = 0;      // the whole step
  };
  const StageTimes& stage_times() const { return stage_times_; }
  // Whether step() times its stages (on by default, for the demo's timings). A crowd of thousands of worlds
  // turns it off: reading the clock five times per character was 3% of a tick.
  void set_stage_timing(bool on) { stage_timing_ = on; }
  // Whether step() keeps alpha_history() (on by default, for plots and tests). A crowd turns it off: its
  // thousands of worlds, started on the same tick, grew and trimmed their histories on the same ticks, and
  // those were the slowest frames (a crowd of 20,000: 80-126 ms against a median of 40).
  void set_alpha_history(bool on) {
    keep_alpha_history_ = on;
    if (!on) alpha_history_ = {};
  }
  // Whether step() keeps each character's com, support and com_in_support (on by default: the panels draw
  // them, evaluation counts them). A crowd, which shows neither, turns it off: they were 6% of its tick.
  // The synthesis is the same either way (its optimizer takes the support polygon and centroids it needs
  // itself), and so is every pose; turned on again, they are those of the next tick's pose.
  void set_balance_view(bool on) { balance_view_ = on; }
  // The next `ticks` steps take no decision (the characters play on what they play). The worlds of a
  // crowd, started on one tick, take their decisions on the same ticks ever after (the actions last
  // alike): a crowd of 20,000 took 13,000 decisions and 4,000 motion switches on one frame, 13 ms over its
  // neighbours. A crowd holds its worlds' first decisions back by a few ticks each instead.
  void hold_decisions(int ticks) { decisions_held_ = std::max(decisions_held_, ticks); }

  WorldScene scene() const;

 private:
  struct Runtime;
  void step_character(int index);
  void choose_source(int index);
  void control(int index);
  glm::vec2 control_source(int index) const;
  ControlInput control_input(int index) const;
  bool start_target(int index, TargetAction action, int object, int target_character, bool automatic);
  void try_auto_launch(int index);
  void update_goal(int index);
  void defeat(int opponent, int striker);
  // Another character standing on the way from character `index` to the across obstacle objects_[obstacle]
  // (between it and the obstacle's line, within the width the obstacle's clip sweeps): the clip, launched,
  // would run into that body. The nearest such, or -1.
  int body_on_crossing(int index, int obstacle) const;
  // A defeated opponent standing on someone's way across an obstacle steps out of it, sideways.
  void make_way(int standing, int crossing, int obstacle);
  // `striker` plays a strike at `target` that has not landed, or landed less than kStrikeRecovery ago.
  bool striking_at(int striker, int target) const;
  static glm::vec2 character_goal(const WorldCharacter& c);
  static bool turning_to_step_aside(const WorldCharacter& c);
  // The unused across obstacle (bar, beam, hurdle) nearest `from` whose span the straight way from `from` to
  // `to` crosses (or passes within kBesideEnd of its end), whose clip the set has; -1 if none. A user and an
  // opponent with one between them meet once the user has crossed it.
  int obstacle_between(glm::vec2 from, glm::vec2 to) const;
  // m: how far the body of `action`'s clip reaches past the object it is launched at (its BodyReach beyond
  // the clip's reach): an opponent waiting for the user to cross or kick keeps that far off, and more.
  float reach_past_object(TargetAction action) const;
  // An opponent that waits for the user on its own side of an obstacle between them, with room left for the
  // user's clip to come out of it (World::steering_goal).
  bool waiting_beyond_obstacle(const WorldCharacter& c) const;
  // The unused ball the user kicks before meeting the opponent it would meet `opponent_distance` away: ahead
  // (within 45 degrees of the facing), nearer than halfway to the opponent (the two walk toward each other),
  // with no obstacle between; the nearest such, or -1. An approaching opponent otherwise took the user past
  // a ball on its way, and once the fight was over the ball lay behind, never kicked.
  int ball_before_opponent(int index, float opponent_distance) const;
  // An opponent that waits while the user makes for a ball or kicks it (World::steering_goal), as far from
  // the ball as the kick's body reaches past it, its own strike's reach and two persons' space more: out of
  // the kick's way, and not so near that it would strike at the user in the kick. The ball, kicked along
  // the user's facing, may still come its way (rolling_balls.cpp).
  bool waiting_for_kick(const WorldCharacter& c) const;
  bool waits_its_turn(const WorldCharacter& c) const;  // either of the two
  // An opponent whose strike the set has no clip for (daz43 records no punch) takes no part: it is no one's
  // source and stands where it is. Fought, it could never be beaten, and the user circled it for good.
  bool stands_aside(const WorldCharacter& c) const;
  std::optional<glm::vec2> steering_goal(const WorldCharacter& c) const;
  void update_arrival(int index);
  // The COM and support of characters_[index].pose; kinematics_in_scratch: the runtime's synthesis scratch
  // already holds that pose's forward kinematics (stage_floor leaves it so).
  void update_balance(int index, bool kinematics_in_scratch);
  // The launch point at a character or ball (`object` its position), or at the across obstacle objects_[obstacle].
  glm::vec2 launch_point(int index, glm::vec2 object, TargetAction action) const;
  glm::vec2 launch_point(int index, int obstacle) const;
  // The lateral place along an across obstacle's span (m from its middle, along left_of its heading) where
  // the character launches at it: its own, kept kSpanMargin inside the ends and off the places with too
  // little room beyond for the clip (launch_room_short).
  float launch_lateral(int index, int obstacle) const;
  // How much room (m) a launch at `lateral` lacks beyond the obstacle (<= 0: enough): `body` for the clip's
  // own body before the next obstacle, `follow` for the next obstacle's clip to follow on out of it without
  // being slid back. `between`: what it lacks for another obstacle's rail or board lying between the T_p
  // root and the obstacle, the farthest of them starting `between_from` along the crossing from the T_p root;
  // it counts only while the character's body has not come that far (one past it enters the clip late).
  struct RoomShort {
    float body = 0.0f, follow = 0.0f;
    float between = 0.0f, between_from = 0.0f;
    float body_from(float body_front) const { return body_front < between_from ? std::max(body, between) : body; }
  };
  RoomShort launch_room_short(int obstacle, TargetAction action, glm::vec2 n, float lateral) const;
  // The approach to the character's source (set by choose_source): the distance still to go to its launch
  // point along the approach (< 0: past it; infinite without a source) and whether the source lies ahead.
  struct Approach {
    float to_launch = 0.0f;
    bool ahead = false;
    bool facing = false;  // an obstacle within kArrivalFacing of its crossing, a ball of the facing: arrived at
    bool square = false;  // ahead, and an obstacle within kSquareCrossing of its crossing: launched at
    bool beside = false;  // beside the part of an obstacle's span a launch may start from: to go there first
  };
  Approach approach(int index) const;
  bool next_source_in_range(int index) const;
  int kept_level() const;
  bool release_for_next_source(int index);
  // The next source an across obstacle ahead whose launch point is already behind (or no more than
  // short_of_launch_point ahead), with nobody on its crossing (and launches on for the user): its clip may
  // be entered straight out of the one playing, at the frame that has come as far
  // (chain_into_next_crossing; false when it cannot be started).
  bool may_chain_into_next_crossing(int index, float short_of_launch_point) const;
  bool chain_into_next_crossing(int index);
  bool leave_early_for_next_crossing(int index);
  // The obstacle clip playing, followed on from this frame to its release frame (its sweep, obstacle_fit.h,
  // placed where the body is now), reaches into objects_[obstacle]: above a rail's underside or below a
  // board's top within its depth where its line crosses the clip's way.
  bool clip_runs_into(int index, int obstacle) const;
  // The clip of objects_[next], entered now as a launch would enter it, has no capsule in objects_[obstacle].
  bool entry_clear_of(int index, int next, int obstacle) const;
  // The heading a launch at `object` starts its clip with: square to an across obstacle's crossing, else
  // toward the object (`otherwise` standing on it).
  float heading_to_launch_at(int index, int object, float otherwise) const;
  void steer_tightly(int index);
  void fit_pose(int index, Pose& pose);
  void keep_apart();
  void keep_bodies_apart();
  void place_body(int index, glm::vec2& low, glm::vec2& high);
  float closing_share(size_t i, size_t j, glm::vec2 dir) const;
  void keep_clear_of_obstacles(int index);
  // Kicked balls roll and bounce off what they meet (rolling_balls.cpp).
  void roll_balls();
  glm::vec2 ball_meets_objects(size_t ball, glm::vec3 centre, float radius);
  glm::vec2 ball_meets_bodies(size_t ball, glm::vec3 centre, float radius);
  void displace(int index, glm::vec2 offset);

  Scenario scenario_;
  std::shared_ptr<const WorldAssets> assets_;
  Params params_;
  std::shared_ptr<const Synthesizer> synthesizer_;
  std::shared_ptr<const Policy> policy_;
  bool auto_launch_ = false;
  bool preparation_ = true;
  float time_ = 0.0f;
  int ticks_ = 0;
  int user_ = 0;
  OpponentRules rules_;
  std::vector<WorldCharacter> characters_;
  std::vector<WorldObject> objects_;
  std::vector<std::vector<ObjectSolid>> solids_;  // per object, in its own frame (object_solids.h)
  std::shared_ptr<const BodyVolumes> volumes_;     // the bodies' capsules (WorldAssets::volumes)
  int decisions_held_ = 0;  // steps left without decisions (hold_decisions)
  std::vector<glm::vec2> shove_, body_low_, body_high_;  // keep_apart's and keep_bodies_apart's scratch
  std::vector<char> body_placed_;
  std::vector<std::unique_ptr<Runtime>> runtime_;
  std::vector<LaunchRecord> launches_;
  std::vector<glm::vec2> alpha_history_;
  int picked_source_ = -1;
  StageTimes stage_times_;
  bool stage_timing_ = true;
  bool keep_alpha_history_ = true;
  bool balance_view_ = true;
  std::chrono::steady_clock::time_point stage_now() const {
    return stage_timing_ ? std::chrono::steady_clock::now() : std::chrono::steady_clock::time_point{};
  }
  std::unique_ptr<ArrivalModel> arrival_;  // from the policy's table and the runtime Params
  float walking_turn_rate_ = 0.0f;          // rad/s: the policy's fastest level-0 turn (steering.h)
};

// Before stepping worlds[i] of a run of worlds[0 .. end): asks for level L of worlds[i + kPrefetchLevels - L],
// so that each world's memory has arrived, level by level, by the time its turn comes (World::prefetch).
void prefetch_ahead(const std::vector<std::unique_ptr<World>>& worlds, size_t i, size_t end);

// A headless run: the scenario for `seconds`, launches and goal (what `prep run` and `prep-demo --json` print).
struct RunSummary {
  std::string scenario;
  float seconds = 0;
  std::vector<LaunchRecord> launches;
  bool goal_reached = false;
  float goal_time = -1;
  std::vector<std::string> unused_objects;  // "bar at (0, 5)" for each object no action was launched at
};
RunSummary summarize(const World& world);
std::string summary_json(const RunSummary& summary, const World& world);  // pretty JSON text
std::string summary_text(const RunSummary& summary);

}  // namespace prep
