#include "engine/world/world.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <utility>

#include "engine/control/action_effects.h"
#include "engine/control/arrival.h"
#include "engine/motion/kinematics.h"
#include "engine/synthesis/preparation_run.h"
#include "engine/util/error.h"
#include "engine/world/floor.h"
#include "engine/world/motion_stream.h"
#include "engine/world/steering.h"
#include "engine/world/world_runtime.h"

namespace prep {

namespace {

using floor_plane::floor_xz;
using floor_plane::crossing_direction;
using floor_plane::forward_of;
using floor_plane::is_across;
using floor_plane::kPi;

using StageClock = std::chrono::steady_clock;
double ms_between(StageClock::time_point a, StageClock::time_point b) {
  return std::chrono::duration<double, std::milli>(b - a).count();
}

float smoothstep(float x) {
  x = std::clamp(x, 0.0f, 1.0f);
  return x * x * (3.0f - 2.0f * x);
}

// rad/s: the fastest turn among the policy's unprepared actions (steering.h's turning radius).
float fastest_level0_turn(const ActionTable& table) {
  float rate = 0.0f;
  for (int m = 0; m < table.motions; ++m) {
    const ActionEffect& e = table.at(m * table.alpha_levels);
    if (e.duration > 0.0f) rate = std::max(rate, std::fabs(e.turn) / e.duration);
  }
  return rate;
}

constexpr float kMinApproachSpeed = 0.5f;  // m/s: the character's pace assumed when slower (control)
constexpr float kKeptFadeSeconds = 1.0f;   // s: kept preparation's cross-fade from a target clip into walking
constexpr float kLateFadeSeconds = 0.4f;   // s: the cross-fade into an obstacle clip entered past T_t
constexpr float kStandingSpeed = 0.1f;     // m/s: slower than this the character has stopped (try_auto_launch)
constexpr float kTurningAction = 0.1f;     // rad: an action turning more than this in its cycle is a turn (control)

// The turn actions (more than kTurningAction in their cycle) that would leave a point at `bearing`
// (bearing_to) further off the facing than it is: those away from it, and those toward it that swing past
// it by more than it is off now (its bearing less than half the turn). A point dead ahead is left further
// off by every turn.
std::uint64_t turns_off(const ActionTable& table, float bearing) {
  std::uint64_t ruled_out = 0;
  for (size_t a = 0; a < table.effects.size() && a < 64; ++a) {
    const float turn = table.effects[a].turn;  // the heading's change: the bearing after it is bearing - turn
    if (std::fabs(turn) > kTurningAction && !(std::fabs(bearing - turn) < std::fabs(bearing))) ruled_out |= std::uint64_t{1} << a;
  }
  return ruled_out;
}

}  // namespace

World::World(const Scenario& scenario, std::shared_ptr<const WorldAssets> assets)
    : scenario_(scenario), assets_(std::move(assets)), params_(assets_->params), synthesizer_(assets_->synthesizer),
      policy_(assets_->policy), auto_launch_(scenario.auto_launch) {
  if (!policy_) throw std::invalid_argument("world: the assets hold no policy (train or load one first)");
  if (scenario_.user() < 0) throw std::invalid_argument("world: the scenario has no user character");
  arrival_ = std::make_unique<ArrivalModel>(policy_->table, policy_->quantization.alpha_step, params_.runtime);
  walking_turn_rate_ = fastest_level0_turn(policy_->table);
  volumes_ = assets_->volumes;

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
    // A set without an idle clip stands in a posture held from its walk (held_stand.h), and starts on the
    // walk itself: the cross-fade out of the stand slides the feet from side by side into a stride.
    const bool held = !assets_->set->clips[static_cast<size_t>(assets_->idle_node)].derived_from.empty();
    rt->stream.start(held ? find_cyclic_clip(*assets_->set, Role::Walk) : assets_->idle_node, -1, position, heading);
    // The stream's step on the first tick is taken from where it starts, not from the origin: a restart on
    // the second tick (the first decision, held a tick) would carry the character by that step.
    rt->synthesis_previous_root = rt->stream.pose().root_position;
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
    solids_.push_back(object_solids(o.type, o.size));
    // An obstacle no clip of the set can pass (obstacle_fit.h) is refused here, named.
    const TargetMotion& t = assets_->target(o.action);
    if (is_across(o.type) && t.clip >= 0) {
      const ObstacleFit fit = fit_obstacle(assets_->sweeps[static_cast<size_t>(o.action)], t, o.type, o.size);
      if (!fit.possible) {
        const bool over = o.type == ObjectType::Hurdle;
        char what[320];
        std::snprintf(what, sizeof what,
                      "objects[%zu]: the %s at (%.2f, %.2f) has its %s at %.2f m; the %s clip '%s' %s %.2f m (%s by up to "
                      "%.2f m), so it cannot be passed without going through it",
                      i, object_type_name(o.type), o.position.x, o.position.y, over ? "top" : "underside", o.size.y,
                      target_action_name(o.action), assets_->set->clips[static_cast<size_t>(t.clip)].clip.name.c_str(),
                      over ? "clears boards up to" : "passes under rails down to",
                      over ? fit.clip_height - kFitMargin + max_fit(o.action) : fit.clip_height + kFitMargin - max_fit(o.action),
                      over ? "raised" : "lowered", max_fit(o.action));
        throw InputError(scenario_.file.empty() ? scenario_.name : scenario_.file, what);
      }
    }
  }
  for (size_t i = 0; i < characters_.size(); ++i) {
    characters_[i].pose = runtime_[i]->stream.pose();
    update_balance(static_cast<int>(i), false);
  }
  // A character placed into an obstacle starts set out of it, as every tick leaves it: the first frame
  // shows no body in a rail, and the first tick does not jump it out. (Bodies placed into each other are
  // shoved apart tick by tick, at a walking pace, as when they meet.)
  for (int i = 0; i < static_cast<int>(characters_.size()); ++i) keep_clear_of_obstacles(i);
}

World::~World() = default;

void World::set_params(const Params& params) {
  // The controllers hold their own alpha filter (built from the Params they started with).
  const bool smoothing_changed = params.runtime.alpha_sigma_s != params_.runtime.alpha_sigma_s ||
                                 params.runtime.fixed_dt != params_.runtime.fixed_dt;
  params_ = params;
  if (smoothing_changed)
    for (auto& rt : runtime_) rt->controller->set_smoothing(params_.runtime.alpha_sigma_s, params_.runtime.fixed_dt);
  synthesizer_ = std::make_shared<const Synthesizer>(*assets_->set, params_);
  for (auto& rt : runtime_) rt->scratch = synthesizer_->make_scratch();
  arrival_ = std::make_unique<ArrivalModel>(policy_->table, policy_->quantization.alpha_step, params_.runtime);
}

void World::set_policy(std::shared_ptr<const Policy> policy) {
  if (!policy) throw std::invalid_argument("world: no policy given");
  policy_ = std::move(policy);
  arrival_ = std::make_unique<ArrivalModel>(policy_->table, policy_->quantization.alpha_step, params_.runtime);
  walking_turn_rate_ = fastest_level0_turn(policy_->table);
  volumes_ = assets_->volumes;
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

bool World::done() const {
  if (!goal_reached()) return false;
  for (const WorldCharacter& c : characters_)
    if (c.in_target) return false;
  return true;
}

void World::run(float seconds) {
  const int n = static_cast<int>(std::lround(seconds / params_.runtime.fixed_dt));
  for (int k = 0; k < n; ++k) step();
}

void World::step() {
  const auto step_start = stage_now();
  stage_times_ = StageTimes{};
  const float dt = params_.runtime.fixed_dt;
  time_ += dt;
  ++ticks_;
  roll_balls();  // before the characters: a ball struck this tick leaves on the next (rolling_balls.cpp)
  for (int i = 0; i < static_cast<int>(characters_.size()); ++i) step_character(i);
  if (decisions_held_ > 0) --decisions_held_;
  keep_apart();
  keep_bodies_apart();
  for (int i = 0; i < static_cast<int>(characters_.size()); ++i) keep_clear_of_obstacles(i);
  if (keep_alpha_history_) {
    alpha_history_.push_back({time_, characters_[static_cast<size_t>(user_)].alpha});
    // Trimmed in blocks, so that a tick does not move the whole history.
    if (static_cast<int>(alpha_history_.size()) >= 2 * kAlphaHistory) {
      alpha_history_.erase(alpha_history_.begin(), alpha_history_.end() - kAlphaHistory);
    }
  }
  stage_times_.total_ms = ms_between(step_start, stage_now());
}

// The source as the controller sees it. No source: one far behind, beyond the last distance bin, never to
// be reached (world.h). A source that closes in (an opponent walking up) is shown where a still one would
// leave the same time to prepare: nearer by the share of the closing that is its own (training's sources
// stand still, so the policy reads distance as time at the character's own pace).
glm::vec2 World::control_source(int index) const {
  const WorldCharacter& c = characters_[static_cast<size_t>(index)];
  const Runtime& rt = *runtime_[static_cast<size_t>(index)];
  if (!c.has_source) return c.position - 100.0f * forward_of(c.heading);
  if (!params_.runtime.anticipate_closing || !(rt.source_closing_speed > 0.0f)) return c.source;
  const float own = std::max(rt.speed, kMinApproachSpeed);
  return c.position + (c.source - c.position) * (own / (own + rt.source_closing_speed));
}

// What the controller sees: the character, its goal and its source (control_source), and the turns the
// run-time rules rule out (keep_source_ahead).
ControlInput World::control_input(int index) const {
  const WorldCharacter& c = characters_[static_cast<size_t>(index)];
  const Runtime& rt = *runtime_[static_cast<size_t>(index)];
  ControlInput in;
  in.position = c.position;
  in.heading = c.heading;
  in.goal = steering_goal(c).value_or(c.position);
  in.source = control_source(index);
  // A source ahead is not turned away from (RuntimeParams::keep_source_ahead): a turn is ruled out when it
  // would leave both the source and the goal further off the facing (a goal steered elsewhere is turned to).
  if (params_.runtime.keep_source_ahead && c.has_source && c.source_ahead)
    in.ruled_out = turns_off(rt.controller->policy().table, bearing_to(c.position, c.heading, in.source)) &
                   turns_off(rt.controller->policy().table, bearing_to(c.position, c.heading, in.goal));
  return in;
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
  // So does an opponent that is to wait for the user (waits_its_turn), or takes no part (stands_aside).
  if (c.control == Control::Opponent && rt.stream.node() != assets_->idle_node && (waits_its_turn(c) || stands_aside(c)))
    rt.next_decision = std::min(rt.next_decision, time_);
  // A turn toward the goal ends once the goal's bearing has crossed to the other side: played to the end of
  // its gait cycle it would swing the heading past the goal, and the next action would turn back (weaving;
  // RuntimeParams::end_turn_at_goal_bearing).
  if (rt.turning_toward_goal != 0 && !c.reached_goal && params_.runtime.end_turn_at_goal_bearing) {
    const std::optional<glm::vec2> goal = steering_goal(c);
    if (goal && bearing_to(c.position, c.heading, *goal) * static_cast<float>(rt.turning_toward_goal) <= 0.0f) {
      rt.next_decision = std::min(rt.next_decision, time_);
      rt.turning_toward_goal = 0;
    }
  }
  const bool due = decisions_held_ == 0 && time_ >= rt.next_decision && !ctl.arrived();
  if (!due && decisions_held_ == 0 && !ctl.arrived() && c.has_source && params_.runtime.level_per_source_bin &&
      c.source_object == rt.decided_source_object && c.source_character == rt.decided_source_character) {
    // The source has come a distance bin nearer since the level was chosen: choose it again for the
    // motion playing (RuntimeParams::level_per_source_bin).
    if (ctl.source_came_nearer(glm::length(control_source(index) - c.position)))
      c.chosen_alpha = ctl.decide_level(control_input(index)).alpha;
  }
  if (due) {
    const ControlInput in = control_input(index);
    rt.decided_source_object = c.source_object;
    rt.decided_source_character = c.source_character;
    const ControlDecision d = ctl.decide(in);
    c.motion = d.motion;
    c.chosen_alpha = d.alpha;
    rt.next_decision = time_ + std::max(ctl.effect(d.action).duration, params_.runtime.fixed_dt);
    const float turn = ctl.effect(d.action).turn;
    const bool toward_goal = std::fabs(turn) > kTurningAction && turn * bearing_to(c.position, c.heading, in.goal) > 0.0f;
    rt.turning_toward_goal = toward_goal ? (turn > 0.0f ? 1 : -1) : 0;
    // The controller acts per action (Sec. 6's actions, one gait cycle each), but the graph's edges
    // between two core clips come where the clips match, not where an action ends: waiting for one would
    // play the old motion for up to a cycle more (and turn the character past its goal). So a new core
    // motion starts at once, entered at the frame of its loop that best matches the frame playing (the
    // graph's point-cloud distance) and cross-faded over GraphParams::blend_s. Loops and the returns from
    // target motions still follow graph edges.
    const bool stay = (c.control == Control::User && c.reached_goal) ||
                      (c.control == Control::Opponent && c.defeated && (c.goal.empty() || turning_to_step_aside(c))) ||
                      waits_its_turn(c) || stands_aside(c);
    const int wanted = stay ? assets_->idle_node : assets_->core_nodes[static_cast<size_t>(d.motion)];
    if (wanted != rt.stream.node()) {
      rt.begin_fade(c.pose, params_.graph.blend_s);
      rt.stream.switch_to(wanted, c.position, c.heading);
      rt.reseed = true;
    }
  }
  if (rt.stream.needs_next()) {
    const int wanted = rt.stream.node();  // keep looping what plays (a change comes with a decision, above)
    if (!rt.stream.queue(wanted)) {
      // The graph has no edge to the wanted motion from here (e.g. a set whose idle joins nothing):
      // switch anyway, placed where the character stands and cross-faded over GraphParams::blend_s.
      rt.begin_fade(c.pose, params_.graph.blend_s);
      rt.stream.start(wanted, -1, c.position, c.heading);
      rt.reseed = true;
    }
  }
}

float World::heading_to_launch_at(int index, int object, float otherwise) const {
  const WorldCharacter& c = characters_[static_cast<size_t>(index)];
  const WorldObject& o = objects_[static_cast<size_t>(object)];
  glm::vec2 facing = floor_xz(o.position) - c.position;
  if (is_across(o.spec.type)) {
    facing = forward_of(o.spec.heading);
    if (glm::dot(floor_xz(o.position) - c.position, facing) < 0.0f) facing = -facing;
  }
  return glm::length(facing) > 1e-4f ? std::atan2(facing.x, facing.y) : otherwise;
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
  if (object >= 0) {
    WorldObject& o = objects_[static_cast<size_t>(object)];
    o.used = true;
    o.launched_from = glm::dot(c.position - floor_xz(o.position), forward_of(o.spec.heading)) >= 0.0f ? 1.0f : -1.0f;
    o.carried_across = false;
  }

  // Enter the target clip at T_p, where the prepared character stands and faces; then back to walking.
  // Past the launch point of an obstacle, the clip is entered where it has come as far (TargetMotion::advance).
  const bool across_obstacle = object >= 0 && is_across(objects_[static_cast<size_t>(object)].spec.type);
  const int entry = at_source && across_obstacle && c.to_launch < 0.0f ? t.entry_frame(-c.to_launch) : t.reference_frame;
  // A late entry follows the previous target clip: the poses differ more, the fade is the kept one's.
  // Entered past T_t (into the crouch or the run-up), the fade is shorter: the body must be in the clip's
  // posture by the time it reaches the obstacle.
  const int t_t = assets_->set->clips[static_cast<size_t>(t.clip)].target_frame;
  rt.begin_fade(c.pose, entry == t.reference_frame ? params_.graph.blend_s : entry > t_t ? kLateFadeSeconds : kKeptFadeSeconds);
  // A strike is in the clip's own pose when it lands: a longer fade still under way (kept preparation's,
  // out of the previous clip) would leave the kicking leg short of the ball.
  if (t.strike_frame > entry) {
    const float to_strike = static_cast<float>(t.strike_frame - entry) / assets_->set->clips[static_cast<size_t>(t.clip)].clip.fps;
    rt.fade_total = rt.fade_left = std::min(rt.fade_left, to_strike);
  }
  // An obstacle is crossed square and a ball kicked straight: the arrival turns the character toward it
  // (steer_tightly), and the clip starts facing the obstacle's crossing or the ball, the rest of the turn
  // taken in the launch's cross-fade. Without preparation (the naive baseline) it launches as it comes.
  float heading = c.heading;
  if (at_source && target_character >= 0 && preparation_) {  // a punch is thrown at the one it is meant for
    const glm::vec2 facing = characters_[static_cast<size_t>(target_character)].position - c.position;
    if (glm::length(facing) > 1e-4f) heading = std::atan2(facing.x, facing.y);
  }
  if (at_source && object >= 0 && preparation_) heading = heading_to_launch_at(index, object, heading);
  rt.stream.start(t.clip, entry, c.position, heading);
  rt.launch_heading = heading;
  const int walk = find_cyclic_clip(*assets_->set, Role::Walk);
  bool queued = walk >= 0 && rt.stream.queue(walk);
  for (size_t k = 0; !queued && k < assets_->core_nodes.size(); ++k) queued = rt.stream.queue(assets_->core_nodes[k]);
  c.in_target = true;
  c.playing = action;
  c.arm_out_at = action == TargetAction::PunchLeft || action == TargetAction::PunchRight ? target_character : -1;
  c.clip = t.clip;
  rt.target_object = object;
  rt.target_character = target_character;
  rt.struck = false;
  rt.aim = glm::vec2(0.0f);
  rt.aim_seconds = rt.aim_elapsed = 0.0f;
  rt.fit = ObstacleFit{};
  if (across_obstacle) {
    const WorldObject& o = objects_[static_cast<size_t>(object)];
    rt.fit = fit_obstacle(assets_->sweeps[static_cast<size_t>(action)], t, o.spec.type, o.spec.size);
    // The body is in the clip's own pose, square to the crossing, by the time it is over or under the
    // obstacle: a fade still under way there (out of the previous clip, entered late) would carry the
    // previous pose's legs and heading into the board or rail.
    if (rt.fit.last >= rt.fit.first && rt.fit.first > entry) {
      const float to_obstacle = static_cast<float>(rt.fit.first - entry) / assets_->set->clips[static_cast<size_t>(t.clip)].clip.fps;
      rt.fade_total = rt.fade_left = std::min(rt.fade_left, to_obstacle);
    }
    if (at_source) {
      // The clip entered here meets the obstacle where it was made to only if the character stands on the
      // launch point: launched short of it (arrived and prepared), past it by more than the entry frame
      // covers, or beside the part of the span a launch starts from, the difference is slid in before the
      // body reaches the obstacle (a longer or shorter stride, a drift to the side).
      const glm::vec2 p = floor_xz(o.position);
      const glm::vec2 n = crossing_direction(o.spec.heading, p, c.position);
      const glm::vec2 side = floor_plane::left_of(o.spec.heading);
      const size_t k = static_cast<size_t>(entry - t.reference_frame);
      const float clip_distance = t.reach - (k < t.advance.size() ? t.advance[k] : 0.0f);
      const float lateral = glm::dot(c.position - p, side);
      rt.aim = (glm::dot(p - c.position, n) - clip_distance) * n + (launch_lateral(index, object) - lateral) * side;
      const float fps = assets_->set->clips[static_cast<size_t>(t.clip)].clip.fps;
      const int reach_frame = rt.fit.last >= rt.fit.first ? rt.fit.first : assets_->set->clips[static_cast<size_t>(t.clip)].target_frame;
      rt.aim_seconds = std::max(0.3f, static_cast<float>(reach_frame - entry) / fps);
    }
  }
  if (action == TargetAction::Kick && object >= 0 && t.strike_frame > entry) {
    // Aim the kick: the clip entered here would meet a ball at its reach and lateral; the ball lies where
    // it lies (the launch is rarely exactly on the point, and the ball may be off the facing). The
    // difference is slid in over the wind-up, so the foot meets the ball's surface at the strike frame.
    const WorldObject& ball = objects_[static_cast<size_t>(object)];
    const glm::vec2 fwd = forward_of(heading), left = floor_plane::left_of(heading);
    const glm::vec2 met = c.position + t.reach * fwd + t.lateral * left;
    const glm::vec2 centre = floor_xz(ball.position);
    rt.aim = centre - met - (0.5f * ball.spec.size.x - 0.5f * kBallDiameter) * fwd;  // a bigger ball is met sooner
    rt.aim_seconds = static_cast<float>(t.strike_frame - entry) / assets_->set->clips[static_cast<size_t>(t.clip)].clip.fps;
  }
  launches_.back().slide_forward = glm::dot(rt.aim, forward_of(heading));
  launches_.back().slide_side = glm::dot(rt.aim, floor_plane::left_of(heading));
  launches_.back().turn = std::remainder(heading - c.heading, 2.0f * kPi);
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
  // A punch is not thrown into one coming at the character: it waits until that strike is over, then
  // counters. Thrown together, the two would strike through each other's arms.
  if (c.source_character >= 0 && striking_at(c.source_character, index)) return;
  // On the launch point, or arrived and prepared enough to launch where it stands (world.h, arrival.h). One
  // that has arrived on or past its point unprepared (started a step from a beam, whose duck begins 2.5 m
  // before it) stands and prepares first, as an arrival short of it does: launched at once, the duck was
  // entered late at alpha 0.04, the body never lowered before it.
  const bool on_point = c.to_launch <= 0.0f && (!c.arrived || c.alpha >= params_.runtime.launch_alpha);
  // An opponent holding short of its point (update_arrival) waits there for the user to come within its
  // reach: a punch launched from farther would strike the air.
  const bool ready = c.arrived && c.alpha >= params_.runtime.launch_alpha &&
                     (c.control != Control::Opponent || c.to_launch <= kOpponentStrikeSlack);
  if (!on_point && !ready) return;
  // Square to the obstacle or the ball first while the arrival turns the character (steer_tightly); one
  // that stands still not square launches anyway, the rest of the turn taken in the launch (start_target).
  Runtime& rt = *runtime_[static_cast<size_t>(index)];
  if (preparation_ && !rt.square && rt.speed > kStandingSpeed) return;
  // Someone standing between the character and the obstacle: launched, the clip would run into them. The
  // character waits on its launch point, as a person would, and a beaten opponent standing there steps aside.
  if (c.source_object >= 0 && is_across(objects_[static_cast<size_t>(c.source_object)].spec.type)) {
    const int standing = body_on_crossing(index, c.source_object);
    if (standing >= 0) {
      make_way(standing, index, c.source_object);
      return;
    }
  }
  if (start_target(index, c.prepared_for, c.source_object, c.source_character, true) && c.control == Control::Opponent)
    c.last_attack = time_;
}

// Two characters walking to strike each other make for each other's launch point, until that is near:
// steered to a point at its feet a character would swing from side to side, so from there it makes for
// the other character itself (the arrival stops it at the launch point).
glm::vec2 World::character_goal(const WorldCharacter& c) {
  return glm::length(c.source - c.position) > kLaunchPointNear ? c.source : c.source_object_position;
}

bool World::striking_at(int striker, int target) const {
  const WorldCharacter& s = characters_[static_cast<size_t>(striker)];
  const Runtime& rt = *runtime_[static_cast<size_t>(striker)];
  if (!s.in_target || rt.target_character != target) return false;
  return !rt.struck || time_ - rt.struck_time < kStrikeRecovery;
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
// character leaves the clip for the core walk, prepared. Before that, the clip is left only for the next
// obstacle's clip, when going on would carry the body into that obstacle.
bool World::release_for_next_source(int index) {
  WorldCharacter& c = characters_[static_cast<size_t>(index)];
  Runtime& rt = *runtime_[static_cast<size_t>(index)];
  const TargetMotion& t = assets_->target(c.playing);
  if (!next_source_in_range(index)) return false;
  if (t.release_frame < 0 || rt.stream.clip_frame() < t.release_frame) return leave_early_for_next_crossing(index);
  const int walk_node = find_cyclic_clip(*assets_->set, Role::Walk);
  const auto walk = std::find(assets_->core_nodes.begin(), assets_->core_nodes.end(), walk_node);
  const int motion = walk == assets_->core_nodes.end() ? rt.controller->motion() : static_cast<int>(walk - assets_->core_nodes.begin());
  // The next obstacle so near that its launch point is already behind (two bars close together): its clip
  // is entered now, at the frame that has come as far, rather than rising into the walk in between.
  if (may_chain_into_next_crossing(index, 0.0f) && chain_into_next_crossing(index)) return true;
  c.in_target = false;
  rt.controller->reset(motion, kept_level());
  rt.next_decision = time_;
  rt.begin_fade(c.pose, kKeptFadeSeconds);
  rt.stream.switch_to(assets_->core_nodes[static_cast<size_t>(motion)], c.position, c.heading);
  rt.reseed = true;
  return true;
}

bool World::may_chain_into_next_crossing(int index, float short_of_launch_point) const {
  const WorldCharacter& c = characters_[static_cast<size_t>(index)];
  if (c.source_object < 0 || !is_across(objects_[static_cast<size_t>(c.source_object)].spec.type)) return false;
  if (c.control == Control::User && !auto_launch_) return false;
  const Approach next = approach(index);
  return next.to_launch <= short_of_launch_point && next.ahead && body_on_crossing(index, c.source_object) < 0;
}

bool World::chain_into_next_crossing(int index) {
  WorldCharacter& c = characters_[static_cast<size_t>(index)];
  c.in_target = false;
  c.to_launch = approach(index).to_launch;
  if (start_target(index, c.prepared_for, c.source_object, -1, true)) return true;
  c.in_target = true;
  return false;
}

// Early, out of an obstacle clip past its T_t: the clip played on to its release frame would rise into the
// next obstacle (a crawl's get-up under a bar 1.5 m beyond), and the next clip, entered now, stands clear of
// this one. The next launch point may still lie up to kEarlyChainSlack ahead (a crawl's root barely moves
// as it kneels up): the launch slides the clip on by the rest.
bool World::leave_early_for_next_crossing(int index) {
  const WorldCharacter& c = characters_[static_cast<size_t>(index)];
  const Runtime& rt = *runtime_[static_cast<size_t>(index)];
  if (rt.target_object < 0 || c.source_object == rt.target_object || !is_across(objects_[static_cast<size_t>(rt.target_object)].spec.type))
    return false;
  if (rt.stream.clip_frame() <= assets_->set->clips[static_cast<size_t>(c.clip)].target_frame) return false;
  if (!may_chain_into_next_crossing(index, kEarlyChainSlack) || !clip_runs_into(index, c.source_object) ||
      !entry_clear_of(index, c.source_object, rt.target_object))
    return false;
  return chain_into_next_crossing(index);
}

void World::update_goal(int index) {
  WorldCharacter& c = characters_[static_cast<size_t>(index)];
  if (c.control == Control::Opponent) {  // a defeated one stepping aside (defeat)
    if (!c.goal.empty() && glm::length(c.goal.front() - c.position) <= params_.reward.goal_radius) c.goal.clear();
    return;
  }
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
void World::update_balance(int index, bool kinematics_in_scratch) {
  WorldCharacter& c = characters_[static_cast<size_t>(index)];
  Runtime& rt = *runtime_[static_cast<size_t>(index)];
  const MotionSet& set = *assets_->set;
  if (!kinematics_in_scratch) {  // (a new world: step_character takes the contacts with the pose)
    forward_kinematics(*set.skeleton, c.pose, rt.scratch.positions, &rt.scratch.rotations);
    c.contacts = rt.stream.contacts();
  }
  rt.kinematics_of_pose = true;
  if (!balance_view_) return;
  const std::vector<glm::vec3>& positions = rt.scratch.positions;
  const std::vector<glm::quat>& rotations = rt.scratch.rotations;
  std::vector<glm::vec3>& centroids = call_scratch().centroids;
  const bool feet_pitched = kinematics_in_scratch && rt.scratch.centroids_but_feet_of_output;
  if ((kinematics_in_scratch && rt.scratch.centroids_of_output) || feet_pitched) {
    // The pose is the synthesizer's output as it left it: its body-part centroids (one per mass segment,
    // in the same order, by the same arithmetic) are those it keeps for the next frame's smoothness term.
    // Feet the floor stage pitched up since move their own segments only.
    centroids.assign(rt.synthesis.previous.begin(), rt.synthesis.previous.begin() + static_cast<long>(set.mass.segments.size()));
    if (feet_pitched) segment_centroids(*set.skeleton, set.mass, positions, rotations, assets_->foot_segments, centroids);
  } else {
    segment_centroids(*set.skeleton, set.mass, positions, rotations, centroids);
  }
  c.com = center_of_mass(set.mass, centroids);
  if (kinematics_in_scratch && rt.scratch.support_of_output) {
    c.support = rt.scratch.support;  // the synthesizer's: the same feet, the same contacts
  } else {
    support_polygon(foot_points(*set.skeleton, set.body, positions, rotations), c.contacts, params_.contacts, c.support);
  }
  c.com_in_support = !c.support.empty() && c.support.contains({c.com.x, c.com.z});
}

void World::step_character(int index) {
  WorldCharacter& c = characters_[static_cast<size_t>(index)];
  Runtime& rt = *runtime_[static_cast<size_t>(index)];
  const float dt = params_.runtime.fixed_dt;
  const auto control_start = stage_now();

  choose_source(index);
  if (!c.in_target) control(index);
  // Relaxed when no source is in range (world.h), taken from this tick's source.
  const bool relaxed = params_.runtime.relax_without_source && !c.in_target &&
                       !(c.has_source && approach(index).to_launch <= params_.runtime.preparation_range);
  float alpha = rt.controller->tick(relaxed);  // Gaussian-smoothed (controller.h)
  if (!preparation_) alpha = 0.0f;      // the naive baseline (set_preparation)
  const auto motion_start = stage_now();
  stage_times_.control_ms += ms_between(control_start, motion_start);
  rt.stream.advance(dt);
  if (!c.in_target) steer_tightly(index);

  if (c.in_target && rt.aim_elapsed < rt.aim_seconds) {
    // The strike's aim (start_target), slid in with a smoothstep's share of this tick.
    const float before = smoothstep(rt.aim_elapsed / rt.aim_seconds);
    rt.aim_elapsed = std::min(rt.aim_seconds, rt.aim_elapsed + dt);
    FloorTransform slide;
    slide.offset = (smoothstep(rt.aim_elapsed / rt.aim_seconds) - before) * rt.aim;
    rt.stream.move(slide);
  }

  if (c.in_target) {
    const MotionClip& mc = assets_->set->clips[static_cast<size_t>(c.clip)];
    const TargetMotion& target = assets_->target(c.playing);
    const int strike_frame = target.strike_frame >= 0 ? target.strike_frame : mc.target_frame;
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
      rt.begin_fade(c.pose, params_.graph.blend_s);
    } else if (!rt.struck && rt.stream.clip_frame() >= strike_frame) {
      rt.struck = true;  // the strike lands: the ball flies, the opponent is hit
      rt.struck_time = time_;
      if (c.playing == TargetAction::Kick && rt.target_object >= 0) {
        // The ball leaves along the kick at 1.3 times the foot's speed: a light ball struck by a much heavier
        // leg with a restitution of about 0.5 (at least a pass's 6 m/s).
        objects_[static_cast<size_t>(rt.target_object)].velocity = std::max(6.0f, 1.3f * target.strike_speed) * forward_of(c.heading);
      }
      if (rt.target_character >= 0 && characters_[static_cast<size_t>(rt.target_character)].control == Control::Opponent)
        defeat(rt.target_character, index);
    } else if (rt.struck && release_for_next_source(index)) {
      // Left for prepared locomotion (world.h, kept preparation).
    } else if (!rt.stream.has_ahead(0.0f)) {
      // The clip ended without an edge back (a set without one): stand where it ended.
      c.in_target = false;
      rt.stream.start(assets_->idle_node, -1, c.position, c.heading);
      rt.reseed = true;
    }
  }

  const auto synthesis_start = stage_now();
  stage_times_.motion_ms += ms_between(motion_start, synthesis_start);
  Pose& out = rt.out;  // kept between ticks: no allocation per tick
  out.rotations.resize(static_cast<size_t>(assets_->set->skeleton->size()));
  c.alpha = alpha;
  c.contacts = rt.stream.contacts();  // of the frame the stream stands at, whatever makes the pose
  if (c.in_target) {
    out = rt.stream.pose();
    if (rt.fit.lift != 0.0f) fit_pose(index, out);
    c.balanced = false;
  } else {
    const TargetMotion& t = assets_->target(c.prepared_for);
    SynthesisInput in;
    in.locomotion = &rt.stream.pose();
    in.contacts = c.contacts;
    in.reference = t.clip >= 0 ? &t.reference : &rt.stream.pose();
    in.alpha = t.clip >= 0 ? alpha : 0.0f;
    in.dt = dt;
    in.keep_toes_above_floor = false;  // stage_floor follows, after the cross-fade
    if (rt.reseed) {
      // Continue from where the character stands: the synthesizer's root restarts here, with no step.
      rt.synthesis = SynthesisState{};
      rt.synthesis.started = true;
      rt.synthesis.root_xz = c.position;
      in.has_displacement = true;
      in.displacement = rt.last_displacement;  // the stream's last step, so the gait does not hitch
      rt.reseed = false;
    }
    c.balanced = synthesizer_->step(in, rt.synthesis, rt.scratch, out);
    if (!in.has_displacement) rt.last_displacement = rt.stream.pose().root_position - rt.synthesis_previous_root;
    rt.synthesis_previous_root = rt.stream.pose().root_position;
    c.clip = rt.stream.node();
  }
  bool kinematics_given = !c.in_target;  // the synthesizer's scratch holds the kinematics of `out`
  if (rt.fade_left > 0.0f) {
    // Cross-fade from the pose before a switch (launch, return, restart) into the new stream.
    kinematics_given = false;
    const float w = smoothstep(1.0f - rt.fade_left / rt.fade_total);
    const glm::vec3 root = out.root_position;
    interpolate(rt.fade_from, out, w, out);
    out.root_position.x = root.x;
    out.root_position.z = root.z;
    rt.fade_left -= dt;
  }
  // Whatever made the pose (synthesis, a recorded clip fitted to its obstacle, a cross-fade between two
  // poses whose feet differ), no toe goes into the floor.
  synthesizer_->stage_floor(rt.scratch, out, kinematics_given);
  if (!c.in_target && rt.fade_left <= 0.0f) c.arm_out_at = -1;
  // `out` is made afresh each tick before anything reads it: the two poses trade buffers, nothing is copied.
  std::swap(c.pose, out);
  const glm::vec2 previous_position = c.position;
  c.position = floor_xz(c.pose.root_position);
  rt.speed += dt / (dt + 0.5f) * (glm::length(c.position - previous_position) / dt - rt.speed);
  rt.velocity = (c.position - previous_position) / dt;
  c.heading = heading_of(rt.stream.pose().rotations[0]);
  const auto balance_start = stage_now();
  stage_times_.synthesis_ms += ms_between(synthesis_start, balance_start);
  update_balance(index, true);
  update_goal(index);
  update_arrival(index);
  try_auto_launch(index);
  stage_times_.balance_ms += ms_between(balance_start, stage_now());
}

// ---------------------------------------------------------------------------------------------------------
// Views

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

}  // namespace prep
