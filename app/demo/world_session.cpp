#include "app/demo/world_session.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <thread>

#include <nlohmann/json.hpp>

#include "app/demo/world_scene.h"
#include "engine/util/error.h"
#include "engine/util/files.h"
#include "engine/world/floor.h"

namespace prep::demo {

std::vector<ScenarioEntry> list_scenarios(const std::string& folder) {
  std::vector<ScenarioEntry> out;
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(folder, ec)) {
    if (!entry.is_regular_file() || entry.path().extension() != ".json") continue;
    try {
      const Scenario s = load_scenario(entry.path().string());
      out.push_back({s.name, entry.path().string(), s.description});
    } catch (const std::exception&) {
      // Not a scenario (a Params file beside them, or a broken one: opening it by hand names the error).
    }
  }
  std::sort(out.begin(), out.end(), [](const ScenarioEntry& a, const ScenarioEntry& b) { return a.name < b.name; });
  return out;
}

std::string default_scenarios_dir() { return source_dir() + "/assets/scenarios"; }
std::string default_scenario_path() { return default_scenarios_dir() + "/obstacles.json"; }
std::string default_crowd_scenario_path() { return default_scenarios_dir() + "/stadium.json"; }

const char* phase_name(SessionPhase phase) {
  switch (phase) {
    case SessionPhase::Empty: return "empty";
    case SessionPhase::Loading: return "loading";
    case SessionPhase::Training: return "training";
    case SessionPhase::Running: return "running";
    case SessionPhase::Failed: return "failed";
  }
  return "?";
}

namespace {

using floor_plane::forward_of;

// Sections of Params the assets (motion graph, T_p, core motions) are built from: a change there needs
// new assets, not just World::set_params.
bool ready(const std::future<std::shared_ptr<WorldAssets>>& f) {
  return f.valid() && f.wait_for(std::chrono::seconds(0)) == std::future_status::ready;
}

std::shared_ptr<WorldAssets> build_assets(const Scenario& scenario, const Params& params) {
  return std::make_shared<WorldAssets>(make_world_assets(load_scenario_motions(scenario, params), params));
}

}  // namespace

// Background work that is no longer wanted, kept until it ends (a policy job is cancelled first; loading
// cannot be interrupted) so that dropping it never blocks a frame.
struct WorldSession::Retired {
  std::unique_ptr<PolicyJob> job;
  std::shared_ptr<const WorldAssets> assets;  // the set and graph the job reads
  std::future<std::shared_ptr<WorldAssets>> loading;
  bool done() const { return (!job || job->done()) && (!loading.valid() || ready(loading)); }
};

WorldSession::WorldSession(SessionOptions options) : options_(std::move(options)) {
  if (options_.cache_dir.empty()) options_.cache_dir = default_policy_cache_dir();
}

WorldSession::~WorldSession() {
  if (job_) job_->cancel();
  for (auto& r : retired_)
    if (r->job) r->job->cancel();
}

void WorldSession::open(const std::string& path, std::optional<Params> params) {
  Scenario s = load_scenario(path);                                 // InputError: keep what is open
  Params p = params ? std::move(*params) : load_scenario_params(s);  // likewise
  const bool reuse = assets_ && assets_->policy && s.motions == scenario_.motions && same_world_assets_params(p, params_);
  retire_job();
  if (loading_.valid()) {
    auto r = std::make_unique<Retired>();
    r->loading = std::move(loading_);
    retired_.push_back(std::move(r));
  }
  world_.reset();
  scenario_ = std::move(s);
  path_ = path;
  params_ = std::move(p);
  error_.clear();
  notice_.clear();
  pending_goal_.clear();
  pending_pick_ = -1;
  auto_override_.reset();
  retrain_at_ = -1.0;
  last_goal_ = scenario_.goal.back();
  if (reuse) {
    start_world();
    return;
  }
  assets_.reset();
  start_loading();
  if (!options_.background) wait_blocking();
}

void WorldSession::restart() {
  if (!assets_ || !assets_->policy) return;
  const std::optional<bool> keep_auto = auto_override_;
  pending_goal_.clear();
  pending_pick_ = -1;
  last_goal_ = scenario_.goal.back();
  auto_override_ = keep_auto;
  start_world();
}

void WorldSession::start_loading() {
  phase_ = SessionPhase::Loading;
  if (options_.background) {
    loading_ = std::async(std::launch::async, [s = scenario_, p = params_] { return build_assets(s, p); });
    return;
  }
  try {
    assets_ = build_assets(scenario_, params_);
  } catch (const std::exception& e) {
    phase_ = SessionPhase::Failed;
    error_ = e.what();
    throw;
  }
  phase_ = SessionPhase::Training;
  start_policy_job();
}

void WorldSession::retire_job() {
  if (!job_) return;
  job_->cancel();
  auto r = std::make_unique<Retired>();
  r->job = std::move(job_);
  r->assets = assets_;
  retired_.push_back(std::move(r));
}

void WorldSession::start_policy_job() {
  if (!assets_) return;
  const std::uint64_t want = wanted_hash();
  if (job_ && job_hash_ == want) return;  // already on its way
  retire_job();
  if (assets_->policy && assets_->policy->params_hash == want) return;  // the one playing will do
  job_ = std::make_unique<PolicyJob>(*assets_->set, *assets_->graph, params_, options_.cache_dir);
  job_hash_ = want;
}

void WorldSession::on_policy(std::shared_ptr<const Policy> policy) {
  auto with_policy = std::make_shared<WorldAssets>(*assets_);
  with_policy->policy = std::move(policy);
  assets_ = std::move(with_policy);
  if (world_) {
    world_->set_policy(assets_->policy);
    notice_.clear();
  } else {
    start_world();
  }
}

void WorldSession::start_world() {
  world_ = std::make_unique<World>(scenario_, assets_);
  if (params_to_json(params_) != params_to_json(world_->params())) world_->set_params(params_);
  if (!pending_goal_.empty()) world_->set_goal(pending_goal_.front());
  if (pending_pick_ >= 0) world_->set_source(pending_pick_);
  if (auto_override_) world_->set_auto(*auto_override_);
  pending_goal_.clear();
  pending_pick_ = -1;
  accumulator_ = 0.0;
  previous_ = current_ = capture();
  samples_.clear();
  phase_ = SessionPhase::Running;
  if (policy_stale()) retrain_at_ = clock_;  // e.g. reopened with Params edited for another policy
}

void WorldSession::poll() {
  retired_.erase(std::remove_if(retired_.begin(), retired_.end(), [](const auto& r) { return r->done(); }), retired_.end());
  if (phase_ == SessionPhase::Loading && ready(loading_)) {
    try {
      assets_ = loading_.get();
      phase_ = SessionPhase::Training;
      start_policy_job();
    } catch (const std::exception& e) {
      phase_ = SessionPhase::Failed;
      error_ = e.what();
    }
  }
  if (retrain_at_ >= 0.0 && clock_ >= retrain_at_ && assets_) {
    retrain_at_ = -1.0;
    start_policy_job();
  }
  if (job_ && job_->done()) {
    std::shared_ptr<const Policy> policy;
    std::string failure;
    try {
      policy = job_->result();
    } catch (const std::exception& e) {
      failure = e.what();
    }
    const std::uint64_t hash = job_hash_;
    job_.reset();  // its thread has ended: no wait
    if (!failure.empty()) {
      if (world_) {
        notice_ = "retraining failed: " + failure;
      } else {
        phase_ = SessionPhase::Failed;
        error_ = failure;
      }
    } else if (policy && hash == wanted_hash()) {
      on_policy(std::move(policy));
    }
  }
}

void WorldSession::wait_blocking() {
  while (phase_ == SessionPhase::Loading || phase_ == SessionPhase::Training) {
    poll();
    if (phase_ == SessionPhase::Loading || phase_ == SessionPhase::Training) {
      if (options_.on_progress) options_.on_progress(status(), progress());
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
  }
  if (phase_ == SessionPhase::Failed) throw std::runtime_error(path_ + ": " + error_);
}

WorldSession::Snapshot WorldSession::capture() const {
  Snapshot s;
  for (const WorldCharacter& c : world_->characters()) s.poses.push_back(c.pose);
  for (const WorldObject& o : world_->objects()) s.objects.push_back(o.position);
  return s;
}

void WorldSession::tick() {
  previous_ = std::move(current_);
  if (steer_ != glm::vec2(0.0f)) {
    const WorldCharacter& u = world_->characters()[static_cast<size_t>(world_->user())];
    set_goal(u.position + kSteerLead * steer_);
  }
  world_->step();
  current_ = capture();
  const World::StageTimes& t = world_->stage_times();
  stage_times_.control_ms += t.control_ms;
  stage_times_.motion_ms += t.motion_ms;
  stage_times_.synthesis_ms += t.synthesis_ms;
  stage_times_.balance_ms += t.balance_ms;
  stage_times_.total_ms += t.total_ms;
  const WorldCharacter& u = world_->characters()[static_cast<size_t>(world_->user())];
  TickSample sample;
  sample.time = world_->time();
  sample.alpha = u.alpha;
  sample.com_height = u.com.y;
  sample.com_inside = u.com_in_support;
  sample.com_offset = u.support.empty() ? 0.0f : glm::length(glm::vec2(u.com.x, u.com.z) - u.support.center());
  samples_.push_back(sample);
  if (samples_.size() > kSampleHistory) samples_.pop_front();
  if (!u.goal.empty()) last_goal_ = u.goal.back();
}

int WorldSession::advance(double dt) {
  clock_ += std::max(dt, 0.0);
  stage_times_ = World::StageTimes{};
  ticks_last_advance_ = 0;
  poll();
  if (!world_ || paused) return 0;
  const double fixed = world_->params().runtime.fixed_dt;
  accumulator_ += std::max(dt, 0.0) * std::max(time_scale, 0.0f);
  // A tolerance of a nanosecond: frames of exactly k ticks (headless 1/30 s = 2 ticks) never lose one to rounding.
  while (accumulator_ + 1e-9 >= fixed && ticks_last_advance_ < kMaxTicksPerFrame) {
    tick();
    accumulator_ -= fixed;
    ++ticks_last_advance_;
  }
  // A frame slower than kMaxTicksPerFrame ticks: the rest of its time is dropped (the simulation slows
  // down instead of falling further behind), and the drawing shows the last two ticks from the start.
  if (accumulator_ + 1e-9 >= fixed) accumulator_ = 0.0;
  accumulator_ = std::max(accumulator_, 0.0);
  return ticks_last_advance_;
}

void WorldSession::step_once() {
  stage_times_ = World::StageTimes{};
  if (!world_) return;
  tick();
  accumulator_ = 0.0;
  ticks_last_advance_ = 1;
}

float WorldSession::blend() const {
  if (!world_) return 0.0f;
  return static_cast<float>(std::clamp(accumulator_ / world_->params().runtime.fixed_dt, 0.0, 1.0));
}

render::Scene WorldSession::scene(bool balance_overlay) const {
  if (!world_) {
    std::vector<glm::vec2> goal = pending_goal_.empty() ? scenario_.goal : pending_goal_;
    return preview_scene(scenario_, assets_.get(), goal);
  }
  WorldScene ws = world_->scene();
  const float b = blend();
  blended_.resize(ws.characters.size());
  for (size_t i = 0; i < ws.characters.size() && i < current_.poses.size(); ++i) {
    interpolate(previous_.poses[i], current_.poses[i], b, blended_[i]);
    ws.characters[i].pose = &blended_[i];
  }
  // World::scene() lists the objects that are not opponents, in order.
  size_t k = 0;
  const auto& objects = world_->objects();
  for (size_t i = 0; i < objects.size() && k < ws.objects.size(); ++i) {
    if (objects[i].spec.type == ObjectType::Opponent) continue;
    ws.objects[k++].position = glm::mix(previous_.objects[i], current_.objects[i], b);
  }
  return to_render_scene(ws, balance_overlay);
}

void WorldSession::set_params(const Params& params) {
  if (!same_world_assets_params(params, params_)) {
    // The motion graph, T_p or the core motions change: new assets (the scenario reopens with these Params).
    const std::string path = path_;
    open(path, params);
    return;
  }
  params_ = params;
  if (world_) world_->set_params(params_);
  const std::uint64_t want = wanted_hash();
  const bool playing_fits = assets_ && assets_->policy && assets_->policy->params_hash == want;
  if (playing_fits) {
    retire_job();  // back to the Params of the policy playing: nothing to train
    retrain_at_ = -1.0;
  } else if (!(job_ && job_hash_ == want)) {
    retrain_at_ = clock_ + kRetrainDelay;
  }
}

bool WorldSession::policy_stale() const {
  return world_ && assets_ && assets_->policy && assets_->policy->params_hash != wanted_hash();
}

std::string WorldSession::status() const {
  char text[256];
  switch (phase_) {
    case SessionPhase::Empty: return "no scenario open";
    case SessionPhase::Loading: return "loading the motions (" + scenario_.motions + "), motion graph and T_p";
    case SessionPhase::Training:
      return job_ ? "controller policy: " + job_->status() : "controller policy: waiting";
    case SessionPhase::Failed: return "failed: " + error_;
    case SessionPhase::Running:
      if (job_) {
        std::snprintf(text, sizeof text, "retraining the controller for the new Params (%s)", job_->status().c_str());
        return text;
      }
      if (policy_stale()) return "Params changed: retraining the controller shortly";
      std::snprintf(text, sizeof text, "running, t = %.1f s", world_->time());
      return text;
  }
  return "";
}

float WorldSession::progress() const {
  if (phase_ == SessionPhase::Loading) return 0.0f;
  return job_ ? job_->progress() : 1.0f;
}

bool WorldSession::launch(TargetAction action) { return world_ && world_->launch(action); }

std::optional<TargetAction> WorldSession::prepared_action() const {
  if (!world_) return std::nullopt;
  const WorldCharacter& u = world_->characters()[static_cast<size_t>(world_->user())];
  if (!u.has_source) return std::nullopt;
  return u.prepared_for;
}

bool WorldSession::launch_prepared() {
  const auto a = prepared_action();
  return a && launch(*a);
}

glm::vec2 WorldSession::goal() const {
  if (world_) {
    const WorldCharacter& u = world_->characters()[static_cast<size_t>(world_->user())];
    if (!u.goal.empty()) return u.goal.front();
    return last_goal_;
  }
  return pending_goal_.empty() ? scenario_.goal.front() : pending_goal_.front();
}

void WorldSession::set_goal(glm::vec2 goal) {
  last_goal_ = goal;
  if (world_) world_->set_goal(goal);
  else pending_goal_.assign(1, goal);
}

void WorldSession::steer(glm::vec2 direction) {
  const float len = glm::length(direction);
  steer_ = len > 1e-6f ? direction / len : glm::vec2(0.0f);
}

void WorldSession::pick_object(int object) {
  if (object < 0 || object >= static_cast<int>(scenario_.objects.size())) return;
  const ScenarioObject& spec = scenario_.objects[static_cast<size_t>(object)];
  glm::vec2 where = spec.position, from = scenario_.characters[static_cast<size_t>(scenario_.user())].position;
  if (world_) {
    const WorldObject& o = world_->objects()[static_cast<size_t>(object)];
    where = {o.position.x, o.position.z};
    if (o.character >= 0) where = world_->characters()[static_cast<size_t>(o.character)].position;
    from = world_->characters()[static_cast<size_t>(world_->user())].position;
    world_->set_source(object);
  } else {
    pending_pick_ = object;
  }
  if (spec.type == ObjectType::Bar || spec.type == ObjectType::Beam || spec.type == ObjectType::Hurdle) {
    glm::vec2 n = forward_of(spec.heading);
    if (glm::dot(where - from, n) < 0.0f) n = -n;  // crossed from the character's side
    set_goal(where + 2.0f * n);
  } else {
    set_goal(where);
  }
}

void WorldSession::set_auto(bool on) {
  auto_override_ = on;
  if (world_) world_->set_auto(on);
}

bool WorldSession::auto_launch() const {
  if (world_) return world_->auto_launch();
  return auto_override_ ? *auto_override_ : scenario_.auto_launch;
}

}  // namespace prep::demo
