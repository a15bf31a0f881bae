#include "engine/world/world.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "engine/control/action_effects.h"
#include "engine/control/arrival.h"
#include "engine/graph/reference_posture.h"
#include "engine/library/builtin.h"
#include "engine/library/generated.h"
#include "engine/motion/kinematics.h"
#include "engine/synthesis/preparation_run.h"
#include "engine/util/error.h"
#include "engine/util/files.h"
#include "engine/world/motion_stream.h"
#include "engine/world/policy_cache.h"
#include "engine/world/steering.h"

namespace prep {

namespace {

constexpr float kPi = 3.14159265358979f;
const float kCos45 = std::cos(kPi / 4.0f);

glm::vec2 forward_of(float heading) { return {std::sin(heading), std::cos(heading)}; }
glm::vec2 left_of(float heading) { return {std::cos(heading), -std::sin(heading)}; }
glm::vec2 floor_xz(const glm::vec3& p) { return {p.x, p.z}; }

bool is_across(ObjectType t) { return t == ObjectType::Bar || t == ObjectType::Beam || t == ObjectType::Hurdle; }

using StageClock = std::chrono::steady_clock;
double ms_between(StageClock::time_point a, StageClock::time_point b) {
  return std::chrono::duration<double, std::milli>(b - a).count();
}

float smoothstep(float x) {
  x = std::clamp(x, 0.0f, 1.0f);
  return x * x * (3.0f - 2.0f * x);
}

// Where a target clip meets its object, in the clip's coordinates on the floor (x, z).
// - Built-in obstacle clips: the middle of the obstacle they were made for (library::obstacle_of).
// - Kicks and punches: the farthest point the striking foot (toe tips) or hand (wrist) reaches ahead of
//   the T_p root during the target movement (T_t to one second after it).
// - Other obstacle clips (a manifest's crawl, duck, jump): the root's position half a second after T_t,
//   about where the body passes the obstacle.
// `peak_frame` (optional) receives the frame where a striking effector reached that point (-1 otherwise).
glm::vec2 interaction_point(const MotionSet& set, const MotionClip& mc, TargetAction action, int reference_frame,
                            int* peak_frame = nullptr) {
  if (peak_frame) *peak_frame = -1;
  if (set.name == "builtin") {
    const library::Obstacle o = library::obstacle_of(mc.clip.name);
    if (o.height > 0.0f) return {0.0f, 0.5f * (o.z_near + o.z_far)};
  }
  const Clip& clip = mc.clip;
  const int t_t = std::clamp(mc.target_frame, 0, clip.frame_count() - 1);
  const int end = std::min(clip.frame_count() - 1, t_t + static_cast<int>(std::lround(clip.fps)));
  const Pose& ref = clip.frames[static_cast<size_t>(reference_frame)];
  const glm::vec2 origin = floor_xz(ref.root_position);
  const glm::vec2 fwd = forward_of(heading_of(ref.rotations[0]));
  std::vector<int> effectors;
  std::vector<bool> end_site;
  const BodyMap& body = set.body;
  if (action == TargetAction::Kick) {
    for (const auto& leg : body.legs)
      if (leg.toe_tip_joint >= 0) effectors.push_back(leg.toe_tip_joint);
  } else if (action == TargetAction::PunchLeft) {
    effectors.push_back(body.arms[kLeft].wrist);
  } else if (action == TargetAction::PunchRight) {
    effectors.push_back(body.arms[kRight].wrist);
  }
  effectors.erase(std::remove(effectors.begin(), effectors.end(), -1), effectors.end());
  if (effectors.empty()) {
    const int f = std::min(clip.frame_count() - 1, t_t + static_cast<int>(std::lround(0.5f * clip.fps)));
    return floor_xz(clip.frames[static_cast<size_t>(f)].root_position);
  }
  std::vector<glm::vec3> positions;
  std::vector<glm::quat> rotations;
  glm::vec2 best = origin;
  float best_forward = -std::numeric_limits<float>::infinity();
  for (int f = t_t; f <= end; ++f) {
    forward_kinematics(*set.skeleton, clip.frames[static_cast<size_t>(f)], positions, &rotations);
    for (int j : effectors) {
      const bool kick = action == TargetAction::Kick;
      const glm::vec3 p = kick && set.skeleton->joints[static_cast<size_t>(j)].has_end_site
                              ? end_site_position(*set.skeleton, j, positions, rotations)
                              : positions[static_cast<size_t>(j)];
      const float ahead = glm::dot(floor_xz(p) - origin, fwd);
      if (ahead > best_forward) {
        best_forward = ahead;
        best = floor_xz(p);
        if (peak_frame) *peak_frame = f;
      }
    }
  }
  return best;
}

std::optional<Role> role_of(TargetAction a) { return parse_role(role_name_of(a)); }

// rad/s: the fastest turn among the policy's unprepared actions (steering.h's turning radius).
float fastest_level0_turn(const ActionTable& table) {
  float rate = 0.0f;
  for (int m = 0; m < table.motions; ++m) {
    const ActionEffect& e = table.at(m * table.alpha_levels);
    if (e.duration > 0.0f) rate = std::max(rate, std::fabs(e.turn) / e.duration);
  }
  return rate;
}

constexpr float kArrivalFacing = 75.0f * kPi / 180.0f;  // rad off an obstacle's crossing (update_arrival)
constexpr float kMinApproachSpeed = 0.5f;  // m/s: the character's pace assumed when slower (control)
constexpr float kSourceKeptAngle = 2.0f * kPi / 3.0f;  // 120 degrees (choose_source)
constexpr float kSourceKeptWidth = 1.0f;                 // m beyond an obstacle's end (choose_source)
constexpr float kSpanMargin = 0.5f;  // m: a launch point stays this far inside an obstacle's ends (launch_point)

// Kept preparation's hand-over from a target clip to the walk (world.h).
constexpr float kKeptFadeSeconds = 0.5f;     // s: the cross-fade from the clip's frame into prepared walking
constexpr float kReleaseClearance = 0.1f;    // m: every joint this far beyond the obstacle's far side
constexpr float kReleaseAfterStrike = 0.2f;  // s after a strike's farthest reach (the hand or foot returning)
constexpr float kRailHalfDepth = 0.05f;      // m: half the depth of an obstacle's rail (scenario objects' 0.1)

// TargetMotion::release_frame. Obstacles (a bar, beam or hurdle is crossed along the T_p facing): the first
// frame after T_t at which every joint lies beyond the obstacle's far side by kReleaseClearance; the far side
// is the built-in clip's own obstacle, else the interaction point plus a rail's half depth. Strikes:
// kReleaseAfterStrike after the effector's farthest reach.
int release_frame_of(const MotionSet& set, const MotionClip& mc, TargetAction action, int reference_frame,
                     glm::vec2 interaction, int peak_frame) {
  const Clip& clip = mc.clip;
  const int t_t = std::clamp(mc.target_frame, 0, clip.frame_count() - 1);
  if (action == TargetAction::Kick || action == TargetAction::PunchLeft || action == TargetAction::PunchRight) {
    if (peak_frame < 0) return -1;
    const int f = peak_frame + static_cast<int>(std::lround(kReleaseAfterStrike * clip.fps));
    return f < clip.frame_count() ? f : -1;
  }
  const Pose& ref = clip.frames[static_cast<size_t>(reference_frame)];
  const glm::vec2 origin = floor_xz(ref.root_position);
  const glm::vec2 fwd = forward_of(heading_of(ref.rotations[0]));
  float far_side = glm::dot(interaction - origin, fwd) + kRailHalfDepth;
  if (set.name == "builtin") {
    const library::Obstacle o = library::obstacle_of(clip.name);
    if (o.height > 0.0f) far_side = glm::dot(glm::vec2(0.0f, o.z_far) - origin, fwd);
  }
  std::vector<glm::vec3> positions;
  for (int f = t_t; f < clip.frame_count(); ++f) {
    forward_kinematics(*set.skeleton, clip.frames[static_cast<size_t>(f)], positions);
    bool beyond = true;
    for (const glm::vec3& p : positions) beyond = beyond && glm::dot(floor_xz(p) - origin, fwd) > far_side + kReleaseClearance;
    if (beyond) return f;
  }
  return -1;
}

}  // namespace

// ---------------------------------------------------------------------------------------------------------
// Assets

std::shared_ptr<const MotionSet> load_scenario_motions(const Scenario& scenario, const Params& params) {
  if (scenario.motions == "builtin") return std::make_shared<const MotionSet>(make_builtin_motion_set(params));
  const std::string path = scenario.motions.front() == '/' ? scenario.motions : source_dir() + "/" + scenario.motions;
  return std::make_shared<const MotionSet>(load_motion_set(path, params));
}

Params load_scenario_params(const Scenario& scenario) {
  return scenario.params_file.empty() ? Params{} : load_params(scenario.params_file);
}

std::shared_ptr<const WorldAssets> prepare_world_assets(const Scenario& scenario, const Params& params,
                                                        const std::string& cache_dir, bool* trained) {
  auto assets = std::make_shared<WorldAssets>(make_world_assets(load_scenario_motions(scenario, params), params));
  assets->policy = load_or_train_policy(*assets->set, *assets->graph, params, cache_dir, {}, trained);
  return assets;
}

WorldAssets make_world_assets(std::shared_ptr<const MotionSet> set, const Params& params) {
  WorldAssets a;
  a.params = params;
  a.set = set;
  a.graph = std::make_shared<const MotionGraph>(MotionGraph::build(*set, params.graph));
  a.synthesizer = std::make_shared<const Synthesizer>(*set, params);
  const std::string source = set->manifest_path.empty() ? set->name : set->manifest_path;

  for (const MotionClip* c : core_clips(*set, params.quantization)) a.core_nodes.push_back(static_cast<int>(c - set->clips.data()));
  a.idle_node = find_cyclic_clip(*set, Role::Idle);
  if (a.idle_node < 0) a.idle_node = find_cyclic_clip(*set, Role::Walk);
  if (a.idle_node < 0) throw InputError(source, "the motion set has neither a cyclic idle nor a cyclic walk clip");

  a.targets.resize(kTargetActionCount);
  for (int k = 0; k < kTargetActionCount; ++k) {
    TargetMotion& t = a.targets[static_cast<size_t>(k)];
    t.action = static_cast<TargetAction>(k);
    const auto role = role_of(t.action);
    for (size_t i = 0; i < set->clips.size() && t.clip < 0; ++i)
      if (role && set->clips[i].role == *role && set->clips[i].target_frame >= 0) t.clip = static_cast<int>(i);
    if (t.clip < 0) continue;
    const MotionClip& mc = set->clips[static_cast<size_t>(t.clip)];
    t.reference_frame = find_reference_posture(*set, t.clip, params).frame;  // Sec. 4.2
    t.reference = mc.clip.frames[static_cast<size_t>(t.reference_frame)];
    const glm::vec2 origin = floor_xz(t.reference.root_position);
    const float h = heading_of(t.reference.rotations[0]);
    int peak_frame = -1;
    const glm::vec2 meets = interaction_point(*set, mc, t.action, t.reference_frame, &peak_frame);
    const glm::vec2 q = meets - origin;
    t.reach = glm::dot(q, forward_of(h));
    t.lateral = glm::dot(q, left_of(h));
    t.release_frame = release_frame_of(*set, mc, t.action, t.reference_frame, meets, peak_frame);
    for (int f = t.reference_frame; f <= std::max(t.reference_frame, mc.target_frame); ++f)
      t.advance.push_back(glm::dot(floor_xz(mc.clip.frames[static_cast<size_t>(f)].root_position) - origin, forward_of(h)));
  }
  return a;
}

int TargetMotion::entry_frame(float past_launch_point) const {
  for (size_t k = 0; k < advance.size(); ++k)
    if (advance[k] >= past_launch_point) return reference_frame + static_cast<int>(k);
  return reference_frame + static_cast<int>(advance.size()) - 1;  // T_t at the latest
}

// ---------------------------------------------------------------------------------------------------------
// Per-character runtime state

struct World::Runtime {
  explicit Runtime(const MotionGraph& graph) : stream(graph) {}
  MotionStream stream;
  std::unique_ptr<Controller> controller;
  SynthesisState synthesis;
  SynthesisScratch scratch;
  float next_decision = 0.0f;
  bool reseed = false;           // the next synthesized frame continues from the current position
  glm::vec3 last_displacement{0.0f};       // the locomotion's last step (m per tick)
  glm::vec3 synthesis_previous_root{0.0f};
  Pose fade_from;                // cross-fade from this pose ...
  float fade_left = 0.0f;        // ... over the remaining seconds
  float fade_total = 0.0f;
  int target_object = -1, target_character = -1;
  bool struck = false;           // the target movement (T_t) was reached
  // The source as last seen (for its speed toward the character and to notice a change of source).
  int source_key = -2;           // object index, or -(character index) - 3, or -2 for none
  glm::vec2 source_position{0.0f};
  float source_closing_speed = 0.0f;  // m/s toward the character (> 0 closing in)
  bool approach_seen = false, approach_from_far = false;  // the approach to it began more than 1 m away
  bool released = false;         // the target clip playing was left for prepared locomotion
  float speed = 0.0f;            // m/s over the floor, smoothed over about half a second (steering)
  float stride_scale = 1.0f;     // the tight turn's stride, following its target (steering.h)
  bool facing = false;           // the source obstacle is faced closely enough to arrive at (Approach)
  std::vector<glm::vec3> positions, centroids;
  std::vector<glm::quat> rotations;
};

World::World(const Scenario& scenario, std::shared_ptr<const WorldAssets> assets)
    : scenario_(scenario), assets_(std::move(assets)), params_(assets_->params), synthesizer_(assets_->synthesizer),
      policy_(assets_->policy), auto_launch_(scenario.auto_launch) {
  if (!policy_) throw std::invalid_argument("world: the assets hold no policy (train or load one first)");
  if (scenario_.user() < 0) throw std::invalid_argument("world: the scenario has no user character");
  arrival_ = std::make_unique<ArrivalModel>(policy_->table, policy_->quantization.alpha_step, params_.runtime);
  walking_turn_rate_ = fastest_level0_turn(policy_->table);

  auto add_character = [&](glm::vec2 position, float heading, Control control, TargetAction met_with, int object) {
    WorldCharacter c;
    c.control = control;
    c.met_with = met_with;
    c.object = object;
    c.position = position;
    c.heading = heading;
    c.goal = scenario_.goal;
    characters_.push_back(c);
    auto rt = std::make_unique<Runtime>(*assets_->graph);
    rt->controller = std::make_unique<Controller>(policy_, params_);
    const auto idle = std::find(assets_->core_nodes.begin(), assets_->core_nodes.end(), assets_->idle_node);
    rt->controller->reset(idle == assets_->core_nodes.end() ? 0 : static_cast<int>(idle - assets_->core_nodes.begin()), 0);
    rt->stream.start(assets_->idle_node, -1, position, heading);
    rt->scratch = synthesizer_->make_scratch();
    runtime_.push_back(std::move(rt));
  };
  for (const auto& c : scenario_.characters) {
    if (c.control == Control::User) user_ = static_cast<int>(characters_.size());
    add_character(c.position, c.heading, c.control, c.action, -1);
  }
  for (size_t i = 0; i < scenario_.objects.size(); ++i) {
    const ScenarioObject& o = scenario_.objects[i];
    WorldObject w;
    w.spec = o;
    w.position = {o.position.x, 0.0f, o.position.y};
    if (o.type == ObjectType::Opponent) {
      w.character = static_cast<int>(characters_.size());
      add_character(o.position, o.heading, Control::Opponent, o.action, static_cast<int>(i));
    }
    objects_.push_back(w);
  }
  for (size_t i = 0; i < characters_.size(); ++i) {
    characters_[i].pose = runtime_[i]->stream.pose();
    update_balance(static_cast<int>(i));
  }
}

World::~World() = default;

void World::set_params(const Params& params) {
  params_ = params;
  synthesizer_ = std::make_shared<const Synthesizer>(*assets_->set, params_);
  for (auto& rt : runtime_) rt->scratch = synthesizer_->make_scratch();
  arrival_ = std::make_unique<ArrivalModel>(policy_->table, policy_->quantization.alpha_step, params_.runtime);
}

void World::set_policy(std::shared_ptr<const Policy> policy) {
  if (!policy) throw std::invalid_argument("world: no policy given");
  policy_ = std::move(policy);
  arrival_ = std::make_unique<ArrivalModel>(policy_->table, policy_->quantization.alpha_step, params_.runtime);
  walking_turn_rate_ = fastest_level0_turn(policy_->table);
  for (size_t i = 0; i < runtime_.size(); ++i) {
    const int motion = runtime_[i]->controller->motion(), level = runtime_[i]->controller->alpha_level();
    runtime_[i]->controller = std::make_unique<Controller>(policy_, params_);
    runtime_[i]->controller->reset(std::min(motion, policy_->table.motions - 1), level);
  }
}

void World::set_goal(glm::vec2 goal) {
  WorldCharacter& u = characters_[static_cast<size_t>(user_)];
  u.goal.assign(1, goal);
  u.reached_goal = false;
  u.reached_time = -1.0f;
}

void World::set_source(int object) {
  picked_source_ = object >= 0 && object < static_cast<int>(objects_.size()) ? object : -1;
}

void World::run(float seconds) {
  const int n = static_cast<int>(std::lround(seconds / params_.runtime.fixed_dt));
  for (int k = 0; k < n; ++k) step();
}

void World::step() {
  const auto step_start = StageClock::now();
  stage_times_ = StageTimes{};
  const float dt = params_.runtime.fixed_dt;
  time_ += dt;
  ++ticks_;
  for (int i = 0; i < static_cast<int>(characters_.size()); ++i) step_character(i);
  // Kicked balls roll and slow down (rolling resistance of grass, about 1.5 m/s^2).
  for (auto& o : objects_) {
    const float speed = glm::length(o.velocity);
    if (speed <= 0.0f) continue;
    const float slower = std::max(0.0f, speed - 1.5f * dt);
    o.velocity *= slower / speed;
    o.position.x += o.velocity.x * dt;
    o.position.z += o.velocity.y * dt;
  }
  alpha_history_.push_back({time_, characters_[static_cast<size_t>(user_)].alpha});
  if (static_cast<int>(alpha_history_.size()) > kAlphaHistory) alpha_history_.erase(alpha_history_.begin());
  stage_times_.total_ms = ms_between(step_start, StageClock::now());
}

// The launch point for an action at an object: where the character stands when the action's clip, entered
// at T_p, meets the object. Across obstacles (bar, beam, hurdle) the approach is along the obstacle's
// normal, at the character's own lateral place along it (kept kSpanMargin inside the obstacle's ends); for balls and
// characters it is along the line from the character to the object.
glm::vec2 World::launch_point(int index, glm::vec2 object, float object_heading, bool across, TargetAction action,
                               float half_width) const {
  const WorldCharacter& c = characters_[static_cast<size_t>(index)];
  const TargetMotion& t = assets_->target(action);
  if (across) {
    glm::vec2 n = forward_of(object_heading);
    if (glm::dot(object - c.position, n) < 0.0f) n = -n;  // the approach runs from the character's side
    const glm::vec2 along = left_of(object_heading);
    float lateral = glm::dot(c.position - object, along);
    if (half_width > kSpanMargin) lateral = std::clamp(lateral, kSpanMargin - half_width, half_width - kSpanMargin);
    return object + lateral * along - t.reach * n;
  }
  const glm::vec2 d = object - c.position;
  const float len = glm::length(d);
  const glm::vec2 dir = len > 1e-4f ? d / len : forward_of(c.heading);
  return object - t.reach * dir;
}

// Sec. 7.2: the source of influence. User: the closest opponent still fighting (fight), else the closest
// unused object in the facing direction (within 90 degrees; an across obstacle also within its width).
// Opponents: the user's character.
void World::choose_source(int index) {
  WorldCharacter& c = characters_[static_cast<size_t>(index)];
  c.has_source = false;
  c.source_object = c.source_character = -1;
  const glm::vec2 fwd = forward_of(c.heading);
  if (c.control == Control::Opponent) {
    const WorldCharacter& u = characters_[static_cast<size_t>(user_)];
    if (c.defeated) return;
    c.has_source = true;
    c.source_character = user_;
    c.prepared_for = c.met_with;
    c.source_object_position = u.position;
    c.source = launch_point(index, u.position, 0.0f, false, c.met_with);
    return;
  }
  if (picked_source_ >= 0) {  // picked by hand (set_source): kept while it can still be acted on
    const WorldObject& o = objects_[static_cast<size_t>(picked_source_)];
    if (o.spec.type == ObjectType::Opponent && o.character >= 0) {
      const WorldCharacter& opponent = characters_[static_cast<size_t>(o.character)];
      if (!opponent.defeated) {
        c.has_source = true;
        c.source_character = o.character;
        c.prepared_for = opponent.met_with;
        c.source_object_position = opponent.position;
        c.source = launch_point(index, opponent.position, 0.0f, false, c.prepared_for);
        return;
      }
    } else if (!o.used && assets_->target(o.spec.action).clip >= 0) {
      c.has_source = true;
      c.source_object = picked_source_;
      c.prepared_for = o.spec.action;
      c.source_object_position = floor_xz(o.position);
      c.source = launch_point(index, c.source_object_position, o.spec.heading, is_across(o.spec.type), c.prepared_for,
                              0.5f * o.spec.size.x);
      return;
    }
    picked_source_ = -1;  // used or defeated: the automatic choice resumes
  }
  float best = std::numeric_limits<float>::infinity();
  for (int k = 0; k < static_cast<int>(characters_.size()); ++k) {
    const WorldCharacter& o = characters_[static_cast<size_t>(k)];
    if (o.control != Control::Opponent || o.defeated) continue;
    const float d = glm::length(o.position - c.position);
    if (d < best) {
      best = d;
      c.has_source = true;
      c.source_character = k;
      c.prepared_for = o.met_with;
      c.source_object_position = o.position;
    }
  }
  if (c.has_source) {
    c.source = launch_point(index, c.source_object_position, 0.0f, false, c.prepared_for);
    return;
  }
  for (int k = 0; k < static_cast<int>(objects_.size()); ++k) {
    const WorldObject& o = objects_[static_cast<size_t>(k)];
    if (o.used || o.spec.type == ObjectType::Opponent || assets_->target(o.spec.action).clip < 0) continue;
    const glm::vec2 p = floor_xz(o.position), d = p - c.position;
    // The source of the last tick is kept more loosely (kSourceKeptAngle, kSourceKeptWidth): a character
    // that weaves or turns on its approach does not lose it and find it again past its launch point.
    const bool kept = k == runtime_[static_cast<size_t>(index)]->source_key;
    float distance;
    if (is_across(o.spec.type)) {
      const glm::vec2 n = forward_of(o.spec.heading), along = left_of(o.spec.heading);
      const float half_width = 0.5f * o.spec.size.x + (kept ? kSourceKeptWidth : 0.0f);
      if (std::fabs(glm::dot(c.position - p, along)) > half_width) continue;  // passes beside it
      distance = std::fabs(glm::dot(d, n));
    } else {
      distance = glm::length(d);
    }
    // Behind: not in the facing direction.
    if (glm::dot(d, fwd) <= (kept ? std::cos(kSourceKeptAngle) * glm::length(d) : 0.0f)) continue;
    if (distance < best) {
      best = distance;
      c.has_source = true;
      c.source_object = k;
      c.prepared_for = o.spec.action;
      c.source_object_position = p;
    }
  }
  if (c.has_source) {
    const WorldObject& o = objects_[static_cast<size_t>(c.source_object)];
    c.source = launch_point(index, c.source_object_position, o.spec.heading, is_across(o.spec.type), c.prepared_for,
                            0.5f * o.spec.size.x);
  }
}

// The controller: a decision per action (its duration in the action table; none while arriving), and the
// motion stream kept one motion ahead.
void World::control(int index) {
  WorldCharacter& c = characters_[static_cast<size_t>(index)];
  Runtime& rt = *runtime_[static_cast<size_t>(index)];
  Controller& ctl = *rt.controller;
  // A goal just reached is stopped at now, not at the end of the action playing (up to a gait cycle on).
  if (c.control == Control::User && c.reached_goal && rt.stream.node() != assets_->idle_node)
    rt.next_decision = std::min(rt.next_decision, time_);
  if (time_ >= rt.next_decision && !ctl.arrived()) {
    ControlInput in;
    in.position = c.position;
    in.heading = c.heading;
    if (c.control == Control::Opponent) in.goal = c.has_source ? c.source : c.position;
    else in.goal = c.goal.empty() ? c.position : c.goal.front();
    // Unattended (auto), the user meets the opponent that is its source, as a player steering with the
    // keys would: its launch point is the goal until it is defeated (world.h).
    if (c.control == Control::User && auto_launch_ && c.source_character >= 0) in.goal = c.source;
    // No source: one far behind, beyond the last distance bin, never to be reached (world.h).
    in.source = c.has_source ? c.source : c.position - 100.0f * forward_of(c.heading);
    // A source that closes in (an opponent walking up) is shown where a still one would leave the same
    // time to prepare: nearer by the share of the closing that is its own (training's sources stand still,
    // so the policy reads distance as time at the character's own pace).
    if (c.has_source && rt.source_closing_speed > 0.0f) {
      const float own = std::max(rt.speed, kMinApproachSpeed);
      in.source = c.position + (in.source - c.position) * (own / (own + rt.source_closing_speed));
    }
    const ControlDecision d = ctl.decide(in);
    c.motion = d.motion;
    c.chosen_alpha = d.alpha;
    rt.next_decision = time_ + std::max(ctl.effect(d.action).duration, params_.runtime.fixed_dt);
    // The controller acts per action (Sec. 6's actions, one gait cycle each), but the graph's edges
    // between two core clips come where the clips match, not where an action ends: waiting for one would
    // play the old motion for up to a cycle more (and turn the character past its goal). So a new core
    // motion starts at once, entered at the frame of its loop that best matches the frame playing (the
    // graph's point-cloud distance) and cross-faded over GraphParams::blend_s. Loops and the returns from
    // target motions still follow graph edges.
    const bool stay = (c.control == Control::User && c.reached_goal) || (c.control == Control::Opponent && c.defeated);
    const int wanted = stay ? assets_->idle_node : assets_->core_nodes[static_cast<size_t>(d.motion)];
    if (wanted != rt.stream.node()) {
      rt.fade_from = c.pose;
      rt.fade_total = rt.fade_left = params_.graph.blend_s;
      rt.stream.switch_to(wanted, c.position, c.heading);
      rt.reseed = true;
    }
  }
  if (rt.stream.needs_next()) {
    const int wanted = rt.stream.node();  // keep looping what plays (a change comes with a decision, above)
    if (!rt.stream.queue(wanted)) {
      // The graph has no edge to the wanted motion from here (e.g. a set whose idle joins nothing):
      // switch anyway, placed where the character stands and cross-faded over GraphParams::blend_s.
      rt.fade_from = c.pose;
      rt.fade_total = rt.fade_left = params_.graph.blend_s;
      rt.stream.start(wanted, -1, c.position, c.heading);
      rt.reseed = true;
    }
  }
}

bool World::start_target(int index, TargetAction action, int object, int target_character, bool automatic) {
  WorldCharacter& c = characters_[static_cast<size_t>(index)];
  Runtime& rt = *runtime_[static_cast<size_t>(index)];
  const TargetMotion& t = assets_->target(action);
  if (c.in_target || t.clip < 0) return false;
  LaunchRecord r;
  r.character = index;
  r.action = action;
  r.object = object;
  r.target_character = target_character;
  r.alpha_at_launch = c.alpha;
  r.time = time_;
  r.automatic = automatic;
  const bool at_source = (object >= 0 && object == c.source_object) || (target_character >= 0 && target_character == c.source_character);
  if (at_source) {
    r.level_at_arrival = c.level_at_arrival;
    r.alpha_at_1m = c.alpha_at_1m;
    r.miss = std::isfinite(c.to_launch) ? c.to_launch : 0.0f;
  }
  launches_.push_back(r);
  if (object >= 0) objects_[static_cast<size_t>(object)].used = true;

  // Enter the target clip at T_p, where the prepared character stands and faces; then back to walking.
  // Past the launch point of an obstacle, the clip is entered where it has come as far (TargetMotion::advance).
  const bool across_obstacle = object >= 0 && is_across(objects_[static_cast<size_t>(object)].spec.type);
  const int entry = at_source && across_obstacle && c.to_launch < 0.0f ? t.entry_frame(-c.to_launch) : t.reference_frame;
  rt.fade_from = c.pose;
  // A late entry follows the previous target clip: the poses differ more, the fade is the kept one's.
  rt.fade_total = rt.fade_left = entry == t.reference_frame ? params_.graph.blend_s : kKeptFadeSeconds;
  rt.stream.start(t.clip, entry, c.position, c.heading);
  const int walk = find_cyclic_clip(*assets_->set, Role::Walk);
  bool queued = walk >= 0 && rt.stream.queue(walk);
  for (size_t k = 0; !queued && k < assets_->core_nodes.size(); ++k) queued = rt.stream.queue(assets_->core_nodes[k]);
  c.in_target = true;
  c.playing = action;
  c.clip = t.clip;
  rt.target_object = object;
  rt.target_character = target_character;
  rt.struck = false;
  return true;
}

bool World::launch(TargetAction action) {
  const WorldCharacter& u = characters_[static_cast<size_t>(user_)];
  int object = -1, target_character = -1;
  if (u.has_source && u.prepared_for == action) {
    object = u.source_object;
    target_character = u.source_character;
  }
  return start_target(user_, action, object, target_character, false);
}

void World::try_auto_launch(int index) {
  WorldCharacter& c = characters_[static_cast<size_t>(index)];
  if (c.in_target || !c.has_source || !c.source_ahead) return;
  if (c.control == Control::User && !auto_launch_) return;
  if (c.control == Control::Opponent && (c.defeated || time_ - c.last_attack < rules_.cooldown_s)) return;
  if (assets_->target(c.prepared_for).clip < 0) return;
  // On the launch point, or arrived and prepared enough to launch where it stands (world.h, arrival.h).
  const bool on_point = c.to_launch <= 0.0f;
  const bool ready = c.arrived && c.alpha >= params_.runtime.launch_alpha;
  if (!on_point && !ready) return;
  if (start_target(index, c.prepared_for, c.source_object, c.source_character, true) && c.control == Control::Opponent)
    c.last_attack = time_;
}

World::Approach World::approach(int index) const {
  const WorldCharacter& c = characters_[static_cast<size_t>(index)];
  Approach a;
  a.to_launch = std::numeric_limits<float>::infinity();
  if (!c.has_source) return a;
  const TargetMotion& t = assets_->target(c.prepared_for);
  const glm::vec2 fwd = forward_of(c.heading);
  const glm::vec2 to_object = c.source_object_position - c.position;
  const float d = glm::length(to_object);
  if (c.source_object >= 0 && is_across(objects_[static_cast<size_t>(c.source_object)].spec.type)) {
    // Along the obstacle's normal, from the character's side (as launch_point() places the point).
    glm::vec2 n = forward_of(objects_[static_cast<size_t>(c.source_object)].spec.heading);
    if (glm::dot(to_object, n) < 0.0f) n = -n;
    const float along = glm::dot(to_object, n);
    a.to_launch = along - t.reach;
    a.ahead = along > 0.0f && glm::dot(fwd, n) >= kCos45;
    a.facing = along > 0.0f && glm::dot(fwd, n) >= std::cos(kArrivalFacing);
  } else if (d > 1e-4f) {
    a.to_launch = d - t.reach;
    a.ahead = glm::dot(to_object, fwd) >= kCos45 * d;
  }
  return a;
}

// Arrival at the launch point (engine/control/arrival.h): how far the character still has to go along the
// approach, whether the source lies ahead, and the forcing of the played alpha once within the arrival
// radius. Runs after the tick's pose, so the next tick plays the forced alpha.
void World::update_arrival(int index) {
  WorldCharacter& c = characters_[static_cast<size_t>(index)];
  Runtime& rt = *runtime_[static_cast<size_t>(index)];
  Controller& ctl = *rt.controller;
  const float dt = params_.runtime.fixed_dt;
  const int key = !c.has_source ? -2 : c.source_object >= 0 ? c.source_object : -c.source_character - 3;
  if (key != rt.source_key) {  // another source (or none): its approach starts afresh
    rt.source_key = key;
    rt.source_position = c.source_object_position;
    rt.source_closing_speed = 0.0f;
    rt.approach_seen = false;
    c.level_at_arrival = c.alpha_at_1m = -1.0f;
    if (ctl.arrived()) ctl.set_arrived(false);
  }
  c.to_launch = std::numeric_limits<float>::infinity();
  c.source_ahead = false;
  rt.facing = false;
  if (c.has_source && !c.in_target) {
    const Approach a = approach(index);
    c.to_launch = a.to_launch;
    c.source_ahead = a.ahead;
    rt.facing = a.facing;
    const glm::vec2 to_object = c.source_object_position - c.position;
    const float d = glm::length(to_object);
    // How fast the source itself comes toward the character (an opponent walking in), smoothed over about
    // a gait cycle (the root sways within one).
    if (d > 1e-4f) {
      const float closing = -glm::dot(c.source_object_position - rt.source_position, to_object / d) / dt;
      const float k = dt / (dt + 0.5f);
      rt.source_closing_speed += k * (std::max(0.0f, closing) - rt.source_closing_speed);
    }
    rt.source_position = c.source_object_position;
    // The alpha 1 m before the launch point, for an approach that began farther away (one that starts
    // closer, e.g. out of the previous obstacle's clip, has no such moment: left at -1).
    if (!rt.approach_seen) {
      rt.approach_seen = true;
      rt.approach_from_far = c.to_launch > 1.0f;
    }
    if (rt.approach_from_far && c.alpha_at_1m < 0.0f && c.to_launch <= 1.0f) c.alpha_at_1m = c.alpha;
  }
  c.source_in_range = c.has_source && !c.in_target && c.to_launch <= params_.runtime.preparation_range;
  // Without preparation (the naive baseline, set_preparation) synthesis ignores alpha, so nothing would
  // stop the character: it walks on to the launch point and launches there.
  // A character whose policy has itself chosen the top level inside the source radius has stopped there
  // (w_r = 1, Eq. 3-4): it has arrived as near as it will get, and launches where it stands (the shortfall
  // is the launch's miss). Seen with slow core walks, whose stride at 0.8 does not pay for moving on
  // inside the radius (reward.h).
  const bool stopped = ctl.alpha_level() == ctl.policy().table.alpha_levels - 1;
  // An obstacle is arrived at facing it more loosely than it is launched at: the arrival squares the
  // character up to it (steer_tightly), and the launch waits for that (try_auto_launch: ahead).
  const bool within = preparation_ && (c.source_ahead || rt.facing) &&
                      (c.to_launch <= arrival_->radius(rt.source_closing_speed) ||
                       ((stopped || ctl.arrived()) && c.to_launch <= params_.reward.source_radius));
  if (within && !ctl.arrived()) {
    c.level_at_arrival = ctl.alpha_of_level(ctl.alpha_level());
    ctl.set_arrived(true);
  } else if (!within && ctl.arrived()) {
    ctl.set_arrived(false);
  }
  c.arrived = ctl.arrived();
  if (c.arrived) c.chosen_alpha = 1.0f;
}

// The level kept between close targets (RuntimeParams::kept_alpha), as the nearest level an action may choose.
int World::kept_level() const {
  const int top = action_levels(policy_->quantization) - 1;
  const float step = policy_->quantization.alpha_step;
  return std::clamp(static_cast<int>(std::lround(params_.runtime.kept_alpha / step)), 0, top);
}

bool World::next_source_in_range(int index) const {
  if (params_.runtime.kept_alpha < 0.0f || !characters_[static_cast<size_t>(index)].has_source) return false;
  return approach(index).to_launch <= params_.runtime.preparation_range;
}

// Kept preparation (world.h): once the target movement is over, with the next source in range, the
// character leaves the clip for the core walk, prepared.
bool World::release_for_next_source(int index) {
  WorldCharacter& c = characters_[static_cast<size_t>(index)];
  Runtime& rt = *runtime_[static_cast<size_t>(index)];
  const TargetMotion& t = assets_->target(c.playing);
  if (t.release_frame < 0 || rt.stream.clip_frame() < t.release_frame || !next_source_in_range(index)) return false;
  const int walk_node = find_cyclic_clip(*assets_->set, Role::Walk);
  const auto walk = std::find(assets_->core_nodes.begin(), assets_->core_nodes.end(), walk_node);
  const int motion = walk == assets_->core_nodes.end() ? rt.controller->motion() : static_cast<int>(walk - assets_->core_nodes.begin());
  c.in_target = false;
  rt.controller->reset(motion, kept_level());
  rt.next_decision = time_;
  rt.fade_from = c.pose;
  rt.fade_total = rt.fade_left = kKeptFadeSeconds;
  rt.stream.switch_to(assets_->core_nodes[static_cast<size_t>(motion)], c.position, c.heading);
  rt.reseed = true;
  return true;
}

// Tight turns toward a goal the walking turns cannot reach without circling it (steering.h): the stream
// is turned about the stance foot and its stride shortened, on top of the clip just advanced.
void World::steer_tightly(int index) {
  const WorldCharacter& c = characters_[static_cast<size_t>(index)];
  Runtime& rt = *runtime_[static_cast<size_t>(index)];
  const float dt = params_.runtime.fixed_dt;
  const float max_rate = params_.runtime.tight_turn_deg_per_s * kPi / 180.0f;
  TightTurn turn;
  // Squaring up to the obstacle arrived at comes first (steering.h).
  if (max_rate > 0.0f && c.control == Control::User && c.has_source && c.source_object >= 0 && rt.controller->arrived() &&
      is_across(objects_[static_cast<size_t>(c.source_object)].spec.type)) {
    glm::vec2 n = forward_of(objects_[static_cast<size_t>(c.source_object)].spec.heading);
    if (glm::dot(c.source_object_position - c.position, n) < 0.0f) n = -n;
    turn.rate = squaring_rate(c.heading, std::atan2(n.x, n.y), max_rate);
  }
  const bool steering = turn.rate == 0.0f && max_rate > 0.0f && c.control == Control::User && !c.goal.empty() &&
                        !c.reached_goal && !rt.controller->arrived() &&
                        !(c.source_in_range && c.source_ahead);  // a source's approach is the policy's
  if (steering) {
    const float radius = walking_turn_rate_ > 0.0f ? rt.speed / walking_turn_rate_ : 0.0f;
    turn = tight_turn(c.position, c.heading, c.goal.front(), radius, max_rate);
  }
  rt.stride_scale += dt / (dt + kStrideTime) * (turn.stride - rt.stride_scale);
  if (rt.reseed) return;  // the stream was just restarted: it has no step of its own yet
  const glm::vec3 root = rt.stream.pose().root_position;
  FloorTransform move;
  // The stride: the clip's step this tick, shortened (the root is moved back by the part not taken).
  const glm::vec2 step = floor_xz(root) - floor_xz(rt.synthesis_previous_root);
  move.offset = -(1.0f - rt.stride_scale) * step;
  if (turn.rate != 0.0f) {
    const FrameContacts contacts = rt.stream.contacts();
    const bool left = contacts[kLeft].any(), right = contacts[kRight].any();
    if (left != right) {  // single support: pivot on the stance foot
      const MotionSet& set = *assets_->set;
      forward_kinematics(*set.skeleton, rt.stream.pose(), rt.positions);
      const glm::vec3 ankle = rt.positions[static_cast<size_t>(set.body.legs[left ? kLeft : kRight].ankle)];
      const glm::vec2 pivot = floor_xz(ankle) + move.offset;
      FloorTransform pivoting;
      pivoting.angle = turn.rate * dt;
      const glm::vec3 turned = pivoting.apply(glm::vec3(pivot.x, 0.0f, pivot.y));
      pivoting.offset = pivot - floor_xz(turned);
      move = move.then(pivoting);
    }
  }
  if (move.angle != 0.0f || glm::length(move.offset) > 0.0f) rt.stream.move(move);
}

void World::update_goal(int index) {
  WorldCharacter& c = characters_[static_cast<size_t>(index)];
  if (c.control != Control::User) return;
  auto reached = [&](glm::vec2 g) {
    if (glm::length(g - c.position) <= params_.reward.goal_radius) return true;
    return c.goal.size() > 1 && passed_waypoint(c.position, c.heading, g, params_.runtime.waypoint_pass_radius);
  };
  while (!c.goal.empty() && reached(c.goal.front())) {
    c.goal.erase(c.goal.begin());
    if (c.goal.empty()) {
      c.reached_goal = true;
      c.reached_time = time_;
    }
  }
}

// The COM and the support polygon of this tick's pose (Sec. 5.3), for the panels and for evaluation.
void World::update_balance(int index) {
  WorldCharacter& c = characters_[static_cast<size_t>(index)];
  Runtime& rt = *runtime_[static_cast<size_t>(index)];
  const MotionSet& set = *assets_->set;
  forward_kinematics(*set.skeleton, c.pose, rt.positions, &rt.rotations);
  segment_centroids(*set.skeleton, set.mass, rt.positions, rt.rotations, rt.centroids);
  c.com = center_of_mass(set.mass, rt.centroids);
  c.contacts = rt.stream.contacts();
  const FootPoints feet = foot_points(*set.skeleton, set.body, rt.positions, rt.rotations);
  c.support = support_polygon(feet, c.contacts, params_.contacts);
  c.com_in_support = !c.support.empty() && c.support.contains({c.com.x, c.com.z});
}

void World::step_character(int index) {
  WorldCharacter& c = characters_[static_cast<size_t>(index)];
  Runtime& rt = *runtime_[static_cast<size_t>(index)];
  const float dt = params_.runtime.fixed_dt;
  const auto control_start = StageClock::now();

  choose_source(index);
  if (!c.in_target) control(index);
  // Relaxed when no source is in range (world.h), taken from this tick's source.
  const bool relaxed = params_.runtime.relax_without_source && !c.in_target &&
                       !(c.has_source && approach(index).to_launch <= params_.runtime.preparation_range);
  float alpha = rt.controller->tick(relaxed);  // Gaussian-smoothed (controller.h)
  if (!preparation_) alpha = 0.0f;      // the naive baseline (set_preparation)
  const auto motion_start = StageClock::now();
  stage_times_.control_ms += ms_between(control_start, motion_start);
  rt.stream.advance(dt);
  if (!c.in_target) steer_tightly(index);

  if (c.in_target) {
    const MotionClip& mc = assets_->set->clips[static_cast<size_t>(c.clip)];
    if (rt.stream.node() != c.clip) {
      // Back to locomotion through the graph edge: the controller resumes from the core motion playing, at
      // the kept level when the next source is in range, else at alpha 0 (the edge leads into the plain
      // locomotion, world.h).
      c.in_target = false;
      const auto core = std::find(assets_->core_nodes.begin(), assets_->core_nodes.end(), rt.stream.node());
      rt.controller->reset(core == assets_->core_nodes.end() ? rt.controller->motion() : static_cast<int>(core - assets_->core_nodes.begin()),
                           next_source_in_range(index) ? kept_level() : 0);
      rt.next_decision = time_;
      rt.reseed = true;
      rt.fade_from = c.pose;
      rt.fade_total = rt.fade_left = params_.graph.blend_s;
    } else if (!rt.struck && rt.stream.clip_frame() >= mc.target_frame) {
      rt.struck = true;  // the target movement begins: the ball flies, the opponent is hit
      if (c.playing == TargetAction::Kick && rt.target_object >= 0) {
        // The ball leaves at a typical pass speed (6 m/s) along the kick.
        objects_[static_cast<size_t>(rt.target_object)].velocity = 6.0f * forward_of(c.heading);
      }
      if (rt.target_character >= 0 && characters_[static_cast<size_t>(rt.target_character)].control == Control::Opponent)
        characters_[static_cast<size_t>(rt.target_character)].defeated = true;
    } else if (rt.struck && release_for_next_source(index)) {
      // Left for prepared locomotion (world.h, kept preparation).
    } else if (!rt.stream.has_ahead(0.0f)) {
      // The clip ended without an edge back (a set without one): stand where it ended.
      c.in_target = false;
      rt.stream.start(assets_->idle_node, -1, c.position, c.heading);
      rt.reseed = true;
    }
  }

  const auto synthesis_start = StageClock::now();
  stage_times_.motion_ms += ms_between(motion_start, synthesis_start);
  Pose out = synthesizer_->make_pose();
  c.alpha = alpha;
  if (c.in_target) {
    out = rt.stream.pose();
    c.report = SynthesisReport{};
  } else {
    const TargetMotion& t = assets_->target(c.prepared_for);
    SynthesisInput in;
    in.locomotion = &rt.stream.pose();
    in.contacts = rt.stream.contacts();
    in.reference = t.clip >= 0 ? &t.reference : &rt.stream.pose();
    in.alpha = t.clip >= 0 ? alpha : 0.0f;
    in.dt = dt;
    if (rt.reseed) {
      // Continue from where the character stands: the synthesizer's root restarts here, with no step.
      rt.synthesis = SynthesisState{};
      rt.synthesis.started = true;
      rt.synthesis.root_xz = c.position;
      in.has_displacement = true;
      in.displacement = rt.last_displacement;  // the stream's last step, so the gait does not hitch
      rt.reseed = false;
    }
    synthesizer_->step(in, rt.synthesis, rt.scratch, out, &c.report);
    if (!in.has_displacement) rt.last_displacement = rt.stream.pose().root_position - rt.synthesis_previous_root;
    rt.synthesis_previous_root = rt.stream.pose().root_position;
    c.clip = rt.stream.node();
  }
  if (rt.fade_left > 0.0f) {
    // Cross-fade from the pose before a switch (launch, return, restart) into the new stream.
    Pose faded;
    const float w = smoothstep(1.0f - rt.fade_left / rt.fade_total);
    interpolate(rt.fade_from, out, w, faded);
    faded.root_position.x = out.root_position.x;
    faded.root_position.z = out.root_position.z;
    out = faded;
    rt.fade_left -= dt;
  }
  c.pose = out;
  const glm::vec2 previous_position = c.position;
  c.position = floor_xz(out.root_position);
  rt.speed += dt / (dt + 0.5f) * (glm::length(c.position - previous_position) / dt - rt.speed);
  c.heading = heading_of(rt.stream.pose().rotations[0]);
  const auto balance_start = StageClock::now();
  stage_times_.synthesis_ms += ms_between(synthesis_start, balance_start);
  update_balance(index);
  update_goal(index);
  update_arrival(index);
  try_auto_launch(index);
  stage_times_.balance_ms += ms_between(balance_start, StageClock::now());
}

// ---------------------------------------------------------------------------------------------------------
// Views and summaries

WorldScene World::scene() const {
  WorldScene s;
  const WorldCharacter& u = characters_[static_cast<size_t>(user_)];
  for (int i = 0; i < static_cast<int>(characters_.size()); ++i) {
    const WorldCharacter& c = characters_[static_cast<size_t>(i)];
    WorldScene::Character v;
    v.skeleton = assets_->set->skeleton;
    v.pose = &c.pose;
    v.user = i == user_;
    v.is_source = u.source_character == i;
    v.alpha = c.alpha;
    v.com = c.com;
    v.support = &c.support;
    s.characters.push_back(v);
  }
  for (int k = 0; k < static_cast<int>(objects_.size()); ++k) {
    const WorldObject& o = objects_[static_cast<size_t>(k)];
    if (o.spec.type == ObjectType::Opponent) continue;
    WorldScene::Object v;
    v.type = o.spec.type;
    v.action = o.spec.action;
    v.position = o.position;
    v.heading = o.spec.heading;
    v.size = o.spec.size;
    v.is_source = u.source_object == k;
    v.used = o.used;
    s.objects.push_back(v);
  }
  for (const glm::vec2& g : u.goal) s.goal.push_back({g.x, 0.0f, g.y});
  s.goal_radius = params_.reward.goal_radius;
  s.source_radius = params_.reward.source_radius;
  if (u.has_source) {
    s.source = glm::vec3(u.source_object_position.x, 0.0f, u.source_object_position.y);
    s.launch_point = glm::vec3(u.source.x, 0.0f, u.source.y);
  }
  s.alpha_history = &alpha_history_;
  return s;
}

RunSummary summarize(const World& world) {
  RunSummary s;
  s.scenario = world.scenario().name;
  s.seconds = world.time();
  s.launches = world.launches();
  s.goal_reached = world.goal_reached();
  s.goal_time = world.characters()[static_cast<size_t>(world.user())].reached_time;
  for (const WorldObject& o : world.objects()) {
    if (o.used) continue;
    if (o.spec.type == ObjectType::Opponent && world.characters()[static_cast<size_t>(o.character)].defeated) continue;
    char text[96];
    std::snprintf(text, sizeof text, "%s at (%.2f, %.2f)", object_type_name(o.spec.type), o.spec.position.x, o.spec.position.y);
    s.unused_objects.push_back(text);
  }
  return s;
}

std::string summary_json(const RunSummary& summary, const World& world) {
  nlohmann::json j;
  j["scenario"] = summary.scenario;
  j["seconds"] = summary.seconds;
  j["launches"] = nlohmann::json::array();
  for (const LaunchRecord& r : summary.launches) {
    nlohmann::json l;
    l["action"] = target_action_name(r.action);
    l["alpha_at_launch"] = r.alpha_at_launch;
    l["time"] = r.time;
    l["character"] = r.character;
    l["control"] = control_name(world.characters()[static_cast<size_t>(r.character)].control);
    l["automatic"] = r.automatic;
    if (r.level_at_arrival >= 0.0f) l["level_at_arrival"] = r.level_at_arrival;
    if (r.alpha_at_1m >= 0.0f) l["alpha_at_1m"] = r.alpha_at_1m;
    l["miss"] = r.miss;
    if (r.object >= 0) l["object"] = r.object;
    if (r.target_character >= 0) l["target_character"] = r.target_character;
    j["launches"].push_back(l);
  }
  j["goal_reached"] = summary.goal_reached;
  if (summary.goal_reached) j["goal_time"] = summary.goal_time;
  j["objects_without_launch"] = summary.unused_objects;
  return j.dump(2);
}

std::string summary_text(const RunSummary& summary) {
  std::string out = "scenario " + summary.scenario + ", " + std::to_string(summary.seconds) + " s\n";
  char line[224];
  for (const LaunchRecord& r : summary.launches) {
    char at_1m[16] = "-", level[16] = "-";  // -1: the approach began within 1 m / no arrival
    if (r.alpha_at_1m >= 0.0f) std::snprintf(at_1m, sizeof at_1m, "%.2f", r.alpha_at_1m);
    if (r.level_at_arrival >= 0.0f) std::snprintf(level, sizeof level, "%.1f", r.level_at_arrival);
    std::snprintf(line, sizeof line, "  %6.2f s  character %d  %-11s alpha_at_launch %.3f  (1 m before: %s, level on arrival %s, miss %+.2f m)%s\n",
                  r.time, r.character, target_action_name(r.action), r.alpha_at_launch, at_1m, level, r.miss,
                  r.automatic ? "  (auto)" : "");
    out += line;
  }
  if (summary.goal_reached) {
    std::snprintf(line, sizeof line, "goal reached at %.2f s\n", summary.goal_time);
    out += line;
  } else {
    out += "goal not reached\n";
  }
  for (const std::string& o : summary.unused_objects) out += "no launch at " + o + "\n";
  return out;
}

}  // namespace prep
