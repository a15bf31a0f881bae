#include "engine/world/soak.h"

#include <malloc.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>

#include <glm/geometric.hpp>

#include "engine/control/random.h"
#include "engine/library/builtin.h"
#include "engine/util/error.h"
#include "engine/motion/kinematics.h"
#include "engine/world/course_evaluation.h"
#include "engine/world/courses.h"
#include "engine/world/policy_cache.h"

namespace prep {
namespace {

using nlohmann::json;

constexpr float kFootTolerance = 0.01f;       // m below the floor
constexpr float kRootSlack = 0.3f;            // m beyond the clips' root heights
constexpr float kStuckSeconds = 30.0f;
constexpr float kProgress = 0.25f;            // m closer than the best since, to count as progress
constexpr float kArrivedSlack = 0.5f;         // m beyond the goal radius: close enough not to be stuck
constexpr float kGoalMoveMin = 2.0f, kGoalMoveMax = 6.0f;  // s between a wandering user's goals
constexpr float kGoalReach = 6.0f;            // m: how far away a moved goal may be
constexpr float kWanderSeconds = 90.0f;       // a wandering world's course is regenerated after this
constexpr float kLiveChangeEvery = 10.0f;     // s between live Params changes
constexpr float kRetrainEvery = 600.0f;       // s between changes that retrain the policy
constexpr double kMemoryToleranceMb = 1.0;
constexpr double kQuietEnd = 180.0;           // s at the end without changes that make new assets, so that every
                                              // world is back on the defaults' when the memory is read
constexpr size_t kViolationsKept = 5;

// A tunable: a number or a switch of one section of the Params, by its JSON names.
struct Tunable {
  std::string section, field;
};

std::vector<Tunable> tunables_of(const json& params) {
  std::vector<Tunable> out;
  for (const auto& [section, fields] : params.items())
    if (fields.is_object())
      for (const auto& [field, value] : fields.items())
        if (value.is_number() || value.is_boolean()) out.push_back({section, field});
  return out;
}

// A new value near the default: a switch flipped, a count one up or down (never below 1 from 1 or more),
// a number scaled by 0.7-1.3 (0 becomes up to 0.1).
json changed(const json& value, Rng& rng) {
  if (value.is_boolean()) return !value.get<bool>();
  if (value.is_number_integer()) {
    const std::int64_t v = value.get<std::int64_t>();
    const std::int64_t next = v + (rng.below(2) == 0 ? -1 : 1);
    return v >= 1 ? std::max<std::int64_t>(1, next) : next;
  }
  const double v = value.get<double>();
  return v == 0.0 ? static_cast<double>(rng.uniform(0.0f, 0.1f)) : v * static_cast<double>(rng.uniform(0.7f, 1.3f));
}

struct Slot {
  std::unique_ptr<World> world;
  bool wander = false;
  float next_goal_at = 0.0f;
  float ends_at = 0.0f;
  // The user's progress toward its goal.
  glm::vec2 goal_seen{std::numeric_limits<float>::quiet_NaN()};
  float best = std::numeric_limits<float>::max();
  float best_at = 0.0f;
};

bool finite(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

class Soak {
 public:
  Soak(const SoakOptions& options, const std::function<void(const SoakPeriod&)>& on_period)
      : options_(options), on_period_(on_period), rng_(options.seed) {
    cache_ = options.cache_dir.empty() ? default_policy_cache_dir() : options.cache_dir;
    base_json_ = json::parse(params_to_json(base_));
    tunables_ = tunables_of(base_json_);
    assets_ = build_assets(base_);
    root_range_ = root_height_range(*assets_->set);
    course_options_.seed = options.seed;
    course_options_.actions = actions_of(*assets_);
    course_options_.reach = reaches_of(*assets_);
    SoakPeriod none;
    while (characters_ < options.characters) add_world(none);
  }

  SoakReport run() {
    const auto wall_start = std::chrono::steady_clock::now();
    const double total = options_.hours * 3600.0;
    const double dt = base_.runtime.fixed_dt;
    SoakPeriod period;
    period.hour = 1;
    const double next_minute = 60.0;
    float next_live = kLiveChangeEvery, next_retrain = kRetrainEvery;
    while (time_ < total) {
      for (size_t k = 0; k < slots_.size(); ++k) tick(slots_[k], period);
      while (characters_ < options_.characters) add_world(period);
      time_ += dt;
      period.simulated_s += dt;
      if (time_ >= next_live) {
        next_live += kLiveChangeEvery;
        change_params(false, period);
      }
      if (time_ >= next_retrain && time_ + kQuietEnd < total) {
        next_retrain += kRetrainEvery;
        change_params(true, period);
      }
      if (time_ >= next_minute && report_.heap_first_minute_mb == 0.0) {
        report_.heap_first_minute_mb = heap_in_use_mb();
        report_.rss_first_minute_mb = resident_mb();
      }
      if (period.simulated_s >= 3600.0 - 0.5 * dt || time_ >= total) close(period);
    }
    // Memory: what the heap holds at the end against the first minute (the resident size is reported too,
    // but the allocator keeps freed pages, so it is no measure of a leak).
    report_.heap_end_mb = heap_in_use_mb();
    report_.rss_end_mb = resident_mb();
    if (report_.heap_end_mb > report_.heap_first_minute_mb + kMemoryToleranceMb && !report_.hours.empty()) {
      SoakPeriod& last = report_.hours.back();
      ++last.violations.memory;
      note(last, "the heap holds " + std::to_string(report_.heap_end_mb) + " MB at the end, the first minute's " +
                     std::to_string(report_.heap_first_minute_mb) + " MB");
    }
    report_.characters = characters_;
    report_.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
    return report_;
  }

 private:
  // The assets for these Params: the defaults' are made once and kept (every change starts from the
  // defaults, so the soak keeps coming back to them); a change's are made for it and dropped once no
  // world plays them.
  std::shared_ptr<const WorldAssets> build_assets(const Params& params) {
    const bool defaults = same_world_assets_params(params, base_) && policy_params_hash(params) == policy_params_hash(base_);
    if (defaults && base_assets_) return base_assets_;
    const Scenario any = make_course(CourseOptions{}, 0);  // the built-in set, as every course here
    auto made = prepare_world_assets(any, params, cache_);
    if (defaults) base_assets_ = made;
    return made;
  }

  // A course regenerated with fewer characters leaves the crowd short: another world makes it up.
  void add_world(SoakPeriod& period) {
    slots_.emplace_back();
    start_course(slots_.back(), 0.0f);
    characters_ += static_cast<int>(slots_.back().world->characters().size());
    ++period.courses;
  }

  void start_course(Slot& slot, float now) {
    Scenario course = make_course(course_options_, next_course_++);
    slot.world = std::make_unique<World>(course, assets_);
    slot.world->set_params(params_);
    slot.wander = rng_.below(2) == 0;
    slot.next_goal_at = rng_.uniform(kGoalMoveMin, kGoalMoveMax);
    slot.ends_at = slot.wander ? kWanderSeconds : course_time_limit(course);
    slot.goal_seen = glm::vec2(std::numeric_limits<float>::quiet_NaN());
    (void)now;
  }

  void tick(Slot& slot, SoakPeriod& period) {
    World& w = *slot.world;
    if (slot.wander && w.time() >= slot.next_goal_at) {
      slot.next_goal_at = w.time() + rng_.uniform(kGoalMoveMin, kGoalMoveMax);
      const glm::vec2 at = w.characters()[static_cast<size_t>(w.user())].position;
      const float angle = rng_.uniform(-3.14159265f, 3.14159265f), reach = rng_.uniform(1.0f, kGoalReach);
      w.set_goal(at + reach * glm::vec2(std::sin(angle), std::cos(angle)));
      ++period.goals_moved;
    }
    w.step();
    ++period.ticks;
    for (int i = 0; i < static_cast<int>(w.characters().size()); ++i) {
      ++period.character_ticks;
      const std::string problem = check_character(w.characters()[static_cast<size_t>(i)], *w.assets().set, root_range_, period.violations);
      if (!problem.empty()) {
        char where[160];
        std::snprintf(where, sizeof where, "%s: character %d at t = %.2f s ", w.scenario().name.c_str(), i, w.time());
        note(period, where + problem);
      }
    }
    check_progress(slot, period);
    if ((!slot.wander && w.done()) || w.time() >= slot.ends_at) {
      characters_ -= static_cast<int>(w.characters().size());
      start_course(slot, w.time());
      characters_ += static_cast<int>(slot.world->characters().size());
      ++period.courses;
    }
  }

  void check_progress(Slot& slot, SoakPeriod& period) {
    const World& w = *slot.world;
    const WorldCharacter& u = w.characters()[static_cast<size_t>(w.user())];
    if (u.goal.empty() || u.in_target) {
      slot.goal_seen = glm::vec2(std::numeric_limits<float>::quiet_NaN());
      return;
    }
    const glm::vec2 goal = u.goal.front();
    const float distance = glm::length(goal - u.position);
    const bool new_goal = !(goal == slot.goal_seen);
    if (new_goal || distance <= w.params().reward.goal_radius + kArrivedSlack || distance < slot.best - kProgress) {
      slot.goal_seen = goal;
      slot.best = distance;
      slot.best_at = w.time();
      return;
    }
    if (w.time() - slot.best_at > kStuckSeconds) {
      ++period.violations.stuck;
      char text[200];
      std::snprintf(text, sizeof text, "%s: the user at (%.2f, %.2f) no closer than %.2f m to its goal (%.2f, %.2f) for %.0f s",
                    w.scenario().name.c_str(), u.position.x, u.position.y, slot.best, goal.x, goal.y, kStuckSeconds);
      note(period, text);
      slot.best_at = w.time();  // counted once per 30 s
    }
  }

  // One tunable set to a new value: one that leaves the policy and the motion graph alone (applied live to
  // every world), or one that changes either (a new policy is trained, then given to the worlds it fits).
  void change_params(bool retraining, SoakPeriod& period) {
    for (int attempt = 0; attempt < 50; ++attempt) {
      const Tunable& t = tunables_[static_cast<size_t>(rng_.below(static_cast<int>(tunables_.size())))];
      json j = base_json_;
      j[t.section][t.field] = changed(j[t.section][t.field], rng_);
      Params p;
      try {
        p = params_from_json(j.dump(), "soak: " + t.section + "." + t.field);
      } catch (const InputError&) {
        ++period.params_refused;
        continue;
      }
      const bool same_assets = same_world_assets_params(p, base_);
      const bool same_policy = policy_params_hash(p) == policy_params_hash(base_);
      if (retraining == (same_assets && same_policy)) continue;  // not the kind of change wanted now
      if (!apply(p, same_assets, period)) continue;
      change_ = t.section + "." + t.field + " = " + j[t.section][t.field].dump();
      ++period.params_changes;
      return;
    }
  }

  bool apply(const Params& p, bool same_assets, SoakPeriod& period) {
    const bool retrain = policy_params_hash(p) != policy_params_hash(params_) || !same_world_assets_params(p, params_);
    if (retrain) {
      try {
        assets_ = build_assets(p);  // trains (or finds cached) the policy for these Params
      } catch (const std::exception&) {
        // Params the file format takes but training cannot (a state space without its top level): left
        // out, as the demo keeps the policy playing when a retraining fails.
        ++period.params_refused;
        return false;
      }
      ++period.retrains;
    }
    params_ = p;
    for (Slot& slot : slots_) {
      if (!same_assets) continue;  // a new motion graph: its worlds take it when their courses are regenerated
      slot.world->set_params(p);
      if (retrain) slot.world->set_policy(assets_->policy);
    }
    return true;
  }

  void note(SoakPeriod& period, const std::string& text) {
    if (period.first_violations.size() < kViolationsKept)
      period.first_violations.push_back(text + (change_.empty() ? "" : " (Params: " + change_ + ")"));
  }

  void close(SoakPeriod& period) {
    period.rss_mb = resident_mb();
    period.heap_mb = heap_in_use_mb();
    if (on_period_) on_period_(period);
    report_.hours.push_back(period);
    const int next = period.hour + 1;
    period = SoakPeriod{};
    period.hour = next;
  }

  SoakOptions options_;
  std::function<void(const SoakPeriod&)> on_period_;
  Rng rng_;
  std::string cache_;
  const Params base_{};
  Params params_{};
  json base_json_;
  std::vector<Tunable> tunables_;
  std::shared_ptr<const WorldAssets> assets_;
  std::shared_ptr<const WorldAssets> base_assets_;
  glm::vec2 root_range_{0.0f};
  CourseOptions course_options_;
  int next_course_ = 0;
  std::vector<Slot> slots_;
  int characters_ = 0;
  double time_ = 0.0;
  SoakReport report_;
  std::string change_;  // the Params change in force, as "section.field = value"
};

}  // namespace

bool SoakReport::ok() const {
  for (const SoakPeriod& p : hours)
    if (p.violations.total() > 0) return false;
  return true;
}

glm::vec2 root_height_range(const MotionSet& set) {
  glm::vec2 range(std::numeric_limits<float>::max(), std::numeric_limits<float>::lowest());
  for (const MotionClip& c : set.clips)
    for (const Pose& p : c.clip.frames) {
      range.x = std::min(range.x, p.root_position.y);
      range.y = std::max(range.y, p.root_position.y);
    }
  return range;
}

std::string check_character(const WorldCharacter& c, const MotionSet& set, glm::vec2 root_range, SoakViolations& v) {
  char text[200];
  auto described = [&](const char* what, double value) {
    const std::string& clip = set.clips[static_cast<size_t>(std::max(0, c.clip))].clip.name;
    std::snprintf(text, sizeof text, "(%s%s, alpha %.2f): %s %.4f", clip.c_str(), c.in_target ? ", a target motion" : "", c.alpha, what, value);
    return std::string(text);
  };
  bool finite_pose = finite(c.pose.root_position) && std::isfinite(c.position.x) && std::isfinite(c.position.y);
  for (const glm::quat& q : c.pose.rotations) finite_pose = finite_pose && std::isfinite(q.w) && std::isfinite(q.x) && std::isfinite(q.y) && std::isfinite(q.z);
  if (!finite_pose) {
    ++v.bad_pose;
    return described("a NaN or infinity in the pose; root height", c.pose.root_position.y);
  }
  std::string problem;
  if (!(c.alpha >= 0.0f && c.alpha <= 1.0f)) {
    ++v.alpha_range;
    problem = described("alpha", c.alpha);
  }
  const float root = c.pose.root_position.y;
  if (root < root_range.x - kRootSlack || root > root_range.y + kRootSlack) {
    ++v.root_height;
    if (problem.empty()) problem = described("root height (m)", root);
  }
  thread_local std::vector<glm::vec3> positions;
  thread_local std::vector<glm::quat> rotations;
  forward_kinematics(*set.skeleton, c.pose, positions, &rotations);
  const FootPoints feet = foot_points(*set.skeleton, set.body, positions, rotations);
  const float lowest = std::min({feet.heel[0].y, feet.heel[1].y, feet.toe[0].y, feet.toe[1].y});
  if (lowest < -kFootTolerance) {
    ++v.foot_below;
    if (problem.empty()) problem = described("a foot below the floor (m)", lowest);
  }
  return problem;
}

double heap_in_use_mb() {
  const struct mallinfo2 m = mallinfo2();
  return static_cast<double>(m.uordblks + m.hblkhd) / (1024.0 * 1024.0);
}

double resident_mb() {
  std::ifstream statm("/proc/self/statm");
  long pages = 0, resident = 0;
  if (!(statm >> pages >> resident)) return 0.0;
  return static_cast<double>(resident) * static_cast<double>(sysconf(_SC_PAGESIZE)) / (1024.0 * 1024.0);
}

SoakReport run_soak(const SoakOptions& options, const std::function<void(const SoakPeriod&)>& on_period) {
  if (!(options.hours > 0.0)) throw std::invalid_argument("the soak's hours must be positive");
  if (options.characters < 1) throw std::invalid_argument("the soak needs at least one character");
  Soak soak(options, on_period);
  return soak.run();
}

json soak_json(const SoakReport& report) {
  json j;
  j["characters"] = report.characters;
  j["wall_s"] = report.wall_s;
  j["heap_first_minute_mb"] = report.heap_first_minute_mb;
  j["heap_end_mb"] = report.heap_end_mb;
  j["rss_first_minute_mb"] = report.rss_first_minute_mb;
  j["rss_end_mb"] = report.rss_end_mb;
  j["ok"] = report.ok();
  json hours = json::array();
  for (const SoakPeriod& p : report.hours) {
    const SoakViolations& v = p.violations;
    hours.push_back({{"hour", p.hour},
                     {"simulated_s", p.simulated_s},
                     {"ticks", p.ticks},
                     {"character_ticks", p.character_ticks},
                     {"courses", p.courses},
                     {"goals_moved", p.goals_moved},
                     {"params_changes", p.params_changes},
                     {"params_refused", p.params_refused},
                     {"retrains", p.retrains},
                     {"rss_mb", p.rss_mb},
                     {"heap_mb", p.heap_mb},
                     {"violations",
                      {{"bad_pose", v.bad_pose},
                       {"foot_below", v.foot_below},
                       {"root_height", v.root_height},
                       {"alpha_range", v.alpha_range},
                       {"stuck", v.stuck},
                       {"memory", v.memory},
                       {"total", v.total()}}},
                     {"first_violations", p.first_violations}});
  }
  j["hours"] = hours;
  return j;
}

}  // namespace prep
