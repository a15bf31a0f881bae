#include "engine/world/course_evaluation.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <exception>
#include <limits>
#include <mutex>
#include <numeric>
#include <thread>

#include <glm/geometric.hpp>

#include "engine/world/courses.h"
#include "engine/world/floor.h"
#include "engine/world/steering.h"

namespace prep {

namespace {

using floor_plane::floor_xz;
using floor_plane::kPi;
using floor_plane::wrap_angle;
// Named for its type: evaluation.cpp, which can share this file's unity translation unit, has a double kNaN.
constexpr float kFloatNaN = std::numeric_limits<float>::quiet_NaN();

std::string percent(int part, int whole) {
  char b[32];
  std::snprintf(b, sizeof b, "%.1f%%", whole > 0 ? 100.0 * part / whole : 0.0);
  return b;
}

std::string number(float v, int decimals) {
  if (!std::isfinite(v)) return "-";
  char b[32];
  std::snprintf(b, sizeof b, "%.*f", decimals, static_cast<double>(v));
  return b;
}

nlohmann::json number_or_null(float v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }

}  // namespace

float CourseEvaluation::no_source_mean() const {
  if (no_source_alpha.empty()) return kFloatNaN;
  return static_cast<float>(std::accumulate(no_source_alpha.begin(), no_source_alpha.end(), 0.0) /
                            static_cast<double>(no_source_alpha.size()));
}

float CourseEvaluation::no_source_median() const { return percentile(no_source_alpha, 50.0f); }

// ---------------------------------------------------------------------------------------------------------
// Alpha with no source in range

NoSourceMeter::NoSourceMeter(bool out, float alpha) : was_out_(out) {
  if (out) alpha_.push_back(alpha);
}

void NoSourceMeter::add(float time, bool out, float alpha) {
  if (out) {
    alpha_.push_back(alpha);
    if (!was_out_) {  // out of range, or out of a target motion, now: an episode begins
      in_episode_ = true;
      episode_start_ = time;
    }
    if (in_episode_ && alpha < course_metric::kRelaxedAlpha) {
      relax_.push_back(time - episode_start_);
      in_episode_ = false;
    }
  } else {
    finish();
  }
  was_out_ = out;
}

void NoSourceMeter::finish() {
  if (in_episode_) ++unrelaxed_;
  in_episode_ = false;
}

// ---------------------------------------------------------------------------------------------------------
// Weaving

void WeavingMeter::add(float time, int turning, bool in_target) {
  if (in_target) {
    last_turning_ = 0;
    return;
  }
  if (turning == 0) return;
  if (last_turning_ != 0 && turning != last_turning_) {
    reversal_times_.push_back(time);
    while (time - reversal_times_[window_start_] > course_metric::kWeaveWindow) ++window_start_;
    most_in_window_ = std::max(most_in_window_, static_cast<int>(reversal_times_.size() - window_start_));
  }
  last_turning_ = turning;
}

void SwerveMeter::add(int source, glm::vec2 launch_point, float to_launch, glm::vec2 position, float heading) {
  if (source != source_) {
    finish();
    source_ = source;
  }
  if (source < 0) return;
  const float off = std::fabs(bearing_to(position, heading, launch_point)) * 180.0f / kPi;
  if (!ahead_) {
    ahead_ = off <= course_metric::kSwerveAheadDeg;
    return;
  }
  if (!(to_launch > course_metric::kSwerveNear)) return;
  widest_deg_ = std::max(widest_deg_, off);
  swerved_ = swerved_ || off > course_metric::kSwerveDeg;
}

void SwerveMeter::finish() {
  approaches_ += ahead_;
  swerves_ += swerved_;
  source_ = -1;
  ahead_ = swerved_ = false;
}

// ---------------------------------------------------------------------------------------------------------
// Circling

CirclingMeter::CirclingMeter(float dt, float heading)
    : dt_(dt), last_heading_(heading), heading_(heading),
      window_(static_cast<size_t>(std::max(1L, std::lround(course_metric::kHeadingWindow / dt))), heading),
      sum_(static_cast<double>(heading) * static_cast<double>(window_.size())), smoothed_(heading) {}

void CirclingMeter::add(glm::vec2 position, float heading, int goal_index, glm::vec2 goal_point) {
  // The heading averaged over the window, unwrapped so that the mean of headings either side of 180
  // degrees is not 0.
  heading_ += wrap_angle(heading - last_heading_);
  last_heading_ = heading;
  sum_ += static_cast<double>(heading_) - static_cast<double>(window_[next_]);
  window_[next_] = heading_;
  next_ = (next_ + 1) % window_.size();
  const float previous = smoothed_;
  smoothed_ = static_cast<float>(sum_ / static_cast<double>(window_.size()));

  const float distance = glm::length(position - goal_point);
  if (visit_goal_ >= 0 && (distance > course_metric::kCirclingLeave || goal_index != visit_goal_)) finish();
  if (visit_goal_ < 0 && distance <= course_metric::kCirclingRadius) {
    visit_goal_ = goal_index;
    visit_turn_ = 0.0f;
    visit_ticks_ = 0;
  }
  if (visit_goal_ >= 0) {
    visit_turn_ += std::fabs(smoothed_ - previous);
    ++visit_ticks_;
  }
}

void CirclingMeter::finish() {
  if (visit_goal_ < 0) return;
  const float degrees = visit_turn_ * 180.0f / kPi;
  max_turn_deg_ = std::max(max_turn_deg_, degrees);
  if (degrees > course_metric::kCirclingTurnDeg) {
    seconds_ += static_cast<float>(visit_ticks_) * dt_;
    ++visits_;
  }
  visit_goal_ = -1;
}

// ---------------------------------------------------------------------------------------------------------
// Recorder

CourseRecorder::CourseRecorder(const World& world)
    : no_source_(!world.characters()[static_cast<size_t>(world.user())].source_in_range &&
                     !world.characters()[static_cast<size_t>(world.user())].in_target,
                 world.characters()[static_cast<size_t>(world.user())].alpha),
      circling_(world.params().runtime.fixed_dt, world.characters()[static_cast<size_t>(world.user())].heading),
      clearance_(world) {
  const Scenario& s = world.scenario();
  const WorldCharacter& u = world.characters()[static_cast<size_t>(world.user())];
  e_.name = s.name;
  e_.description = s.description;
  e_.route_length = polyline_length(course_route(s));
  e_.objects = static_cast<int>(s.objects.size());
  launches_seen_ = world.launches().size();
  last_position_ = u.position;
  e_.times.push_back(world.time());
  e_.alpha.push_back(u.alpha);
}

void CourseRecorder::observe(const World& world) {
  const int tick = static_cast<int>(e_.times.size());
  const float t = world.time();
  const int user = world.user();
  const WorldCharacter& u = world.characters()[static_cast<size_t>(user)];
  const Scenario& s = world.scenario();
  e_.times.push_back(t);
  e_.alpha.push_back(u.alpha);

  // The user's launches of this tick, and where what they were launched at stood.
  for (; launches_seen_ < world.launches().size(); ++launches_seen_) {
    const LaunchRecord& r = world.launches()[launches_seen_];
    if (r.character != user) continue;
    CourseLaunch l;
    l.action = r.action;
    l.time = r.time;
    l.tick = tick;
    l.object = r.object;
    l.target_character = r.target_character;
    l.alpha_at_launch = r.alpha_at_launch;
    l.alpha_at_1m = r.alpha_at_1m;
    l.slide_forward = r.slide_forward;
    l.slide_side = r.slide_side;
    l.turn = r.turn;
    l.at = r.object >= 0 ? floor_xz(world.objects()[static_cast<size_t>(r.object)].position)
           : r.target_character >= 0 ? world.characters()[static_cast<size_t>(r.target_character)].position
                                     : u.position;
    e_.launches.push_back(l);
  }

  clearance_.observe(world);

  // The path up to the goal.
  if (!e_.reached_goal) {
    e_.path_length += glm::length(u.position - last_position_);
    if (u.reached_goal) {
      e_.reached_goal = true;
      e_.goal_time = u.reached_time;
    }
  }

  // Alpha with no source in range, and its relaxation per episode.
  no_source_.add(t, !u.source_in_range && !u.in_target, u.alpha);

  // Circling near the current waypoint or goal (the last one once the goal is reached).
  const int passed = static_cast<int>(s.goal.size()) - static_cast<int>(u.goal.size());
  const int target = std::clamp(passed, 0, static_cast<int>(s.goal.size()) - 1);
  circling_.add(u.position, u.heading, target, s.goal[static_cast<size_t>(target)]);

  // Weaving: the turning clip playing.
  const Role role = u.clip >= 0 ? world.assets().set->clips[static_cast<size_t>(u.clip)].role : Role::Walk;
  weaving_.add(t, role == Role::TurnLeft ? 1 : role == Role::TurnRight ? -1 : 0, u.in_target);

  // Swerving: the source and how far off the facing its launch point is.
  const int source = !u.has_source || u.in_target ? -1
                     : u.source_object >= 0      ? u.source_object
                     : u.source_character >= 0   ? static_cast<int>(world.objects().size()) + u.source_character
                                                 : -1;
  swerve_.add(source, u.source, u.to_launch, u.position, u.heading);

  last_position_ = u.position;
}

CourseEvaluation CourseRecorder::finish(const World& world) const {
  CourseEvaluation e = e_;
  e.seconds = world.time();
  NoSourceMeter no_source = no_source_;
  no_source.finish();
  e.clearance = clearance_.summary;
  // The user's launches are those of ClearanceLog's with the user's index, in the same order.
  size_t next = 0;
  for (const LaunchClearance& l : clearance_.launches) {
    if (l.character != world.user() || next >= e.launches.size()) continue;
    e.launches[next].strike_gap = l.strike_gap;
    e.launches[next++].min_clearance = l.min_clearance;
  }
  e.no_source_alpha = no_source.alpha();
  e.relax_times = no_source.relax_times();
  e.unrelaxed_episodes = no_source.unrelaxed();
  CirclingMeter circling = circling_;
  circling.finish();
  e.circling_seconds = circling.seconds();
  e.circling_visits = circling.visits();
  e.max_visit_turn_deg = circling.max_turn_deg();
  e.turn_reversals = weaving_.reversals();
  e.most_reversals_in_window = weaving_.most_in_window();
  SwerveMeter swerve = swerve_;
  swerve.finish();
  e.approaches = swerve.approaches();
  e.swerving_approaches = swerve.swerves();
  e.widest_approach_deg = swerve.widest_deg();

  const float straight = e.route_length - world.params().reward.goal_radius;
  e.path_ratio = e.reached_goal ? e.path_length / std::max(straight, 1e-3f) : kFloatNaN;

  e.objects_unused = 0;
  for (const WorldObject& o : world.objects()) {
    const bool acted_on = o.spec.type == ObjectType::Opponent && o.character >= 0
                              ? world.characters()[static_cast<size_t>(o.character)].defeated
                              : o.used;
    e.objects_unused += !acted_on;
  }

  for (size_t k = 0; k + 1 < e.launches.size(); ++k) {
    const CourseLaunch &a = e.launches[k], &b = e.launches[k + 1];
    const float d = glm::length(b.at - a.at);
    if (d >= course_metric::kKeptDistance || b.tick - a.tick < 2) continue;
    KeptPreparation kp;
    kp.first = static_cast<int>(k);
    kp.second = static_cast<int>(k + 1);
    kp.distance = d;
    kp.min_alpha = *std::min_element(e.alpha.begin() + a.tick + 1, e.alpha.begin() + b.tick);
    e.kept.push_back(kp);
  }
  return e;
}

// ---------------------------------------------------------------------------------------------------------
// Runs

float course_time_limit(const Scenario& scenario) {
  return course_metric::kBaseSeconds + course_metric::kSecondsPerMetre * polyline_length(course_route(scenario));
}

CourseEvaluation evaluate_course(const Scenario& scenario, std::shared_ptr<const WorldAssets> assets) {
  World world(scenario, std::move(assets));
  world.set_auto(true);
  CourseRecorder recorder(world);
  world.run_until_done(course_time_limit(scenario), course_metric::kRelaxSeconds,
                       [&](const World& w) { recorder.observe(w); });
  return recorder.finish(world);
}

std::vector<CourseEvaluation> evaluate_courses(const std::vector<Scenario>& courses, std::shared_ptr<const WorldAssets> assets,
                                               int threads) {
  std::vector<CourseEvaluation> results(courses.size());
  std::atomic<size_t> next{0};
  std::exception_ptr error;
  std::mutex error_mutex;
  auto work = [&] {
    for (size_t k = next++; k < courses.size(); k = next++) {
      try {
        results[k] = evaluate_course(courses[k], assets);
      } catch (...) {
        std::lock_guard<std::mutex> lock(error_mutex);
        if (!error) error = std::current_exception();
      }
    }
  };
  const int n = std::max(1, std::min(threads, static_cast<int>(courses.size())));
  std::vector<std::thread> pool;
  for (int k = 1; k < n; ++k) pool.emplace_back(work);
  work();
  for (std::thread& th : pool) th.join();
  if (error) std::rethrow_exception(error);
  return results;
}

// ---------------------------------------------------------------------------------------------------------
// Totals

float percentile(std::vector<float> values, float p) {
  if (values.empty()) return kFloatNaN;
  std::sort(values.begin(), values.end());
  const float rank = std::clamp(p, 0.0f, 100.0f) / 100.0f * static_cast<float>(values.size() - 1);
  const size_t lo = static_cast<size_t>(std::floor(rank));
  const size_t hi = std::min(lo + 1, values.size() - 1);
  return values[lo] + (rank - static_cast<float>(lo)) * (values[hi] - values[lo]);
}

bool CourseTotals::pass() const {
  return !checks.empty() && std::all_of(checks.begin(), checks.end(), [](const CourseCheck& c) { return c.pass; });
}

CourseTotals course_totals(const std::vector<CourseEvaluation>& courses) {
  using namespace course_metric;
  CourseTotals t;
  std::vector<float> ratios, no_source, relax, kept;
  double reversals = 0.0, seconds = 0.0;
  for (const CourseEvaluation& e : courses) {
    ++t.courses;
    t.goals += e.reached_goal;
    if (e.reached_goal) ratios.push_back(e.path_ratio);
    t.objects += e.objects;
    t.objects_unused += e.objects_unused;
    for (const CourseLaunch& l : e.launches) {
      ++t.launches;
      t.launches_prepared += l.alpha_at_launch >= kLaunchAlpha;
      if (l.alpha_at_1m >= 0.0f) {
        ++t.measured_1m;
        t.prepared_1m += l.alpha_at_1m >= kAlpha1m;
      }
    }
    no_source.insert(no_source.end(), e.no_source_alpha.begin(), e.no_source_alpha.end());
    relax.insert(relax.end(), e.relax_times.begin(), e.relax_times.end());
    t.unrelaxed_episodes += e.unrelaxed_episodes;
    if (e.circling_visits > 0) ++t.circling_courses;
    t.circling_seconds += e.circling_seconds;
    t.weaving_courses += e.most_reversals_in_window >= kWeaveReversals;
    t.approaches += e.approaches;
    t.swerving_approaches += e.swerving_approaches;
    reversals += e.turn_reversals;
    seconds += e.seconds;
    for (const KeptPreparation& k : e.kept) kept.push_back(k.min_alpha);
    t.penetrating_courses += e.clearance.object_frames > 0;
    t.overlapping_courses += e.clearance.character_frames > 0;
    if (t.courses == 1 || e.clearance.min_object < t.min_object_clearance) {
      t.min_object_clearance = e.clearance.min_object;
      t.min_object_what = e.name + ": " + e.clearance.min_object_what;
    }
    if (t.courses == 1 || e.clearance.min_character < t.min_character_clearance) {
      t.min_character_clearance = e.clearance.min_character;
      t.min_character_what = e.name + ": " + e.clearance.min_character_what;
    }
  }
  t.path_median = percentile(ratios, 50.0f);
  t.path_p95 = percentile(ratios, 95.0f);
  t.no_source_median = percentile(no_source, 50.0f);
  t.no_source_mean = no_source.empty() ? kFloatNaN
                                       : static_cast<float>(std::accumulate(no_source.begin(), no_source.end(), 0.0) /
                                                            static_cast<double>(no_source.size()));
  t.relax_median = percentile(relax, 50.0f);
  t.relax_max = relax.empty() ? kFloatNaN : *std::max_element(relax.begin(), relax.end());
  t.kept_pairs = static_cast<int>(kept.size());
  t.reversals_per_minute = seconds > 0.0 ? static_cast<float>(60.0 * reversals / seconds) : 0.0f;
  t.kept_min = kept.empty() ? kFloatNaN : *std::min_element(kept.begin(), kept.end());
  t.kept_median = percentile(kept, 50.0f);

  // The acceptance, one line each; a measure with nothing to measure fails.
  auto fraction = [](int part, int whole) { return whole > 0 ? static_cast<float>(part) / static_cast<float>(whole) : 0.0f; };
  t.checks.push_back({"goal_reached",
                      std::to_string(t.goals) + "/" + std::to_string(t.courses) + " courses (" + percent(t.goals, t.courses) +
                          ") reach the goal; needed >= " + number(100.0f * kGoalFraction, 0) + "%",
                      t.courses > 0 && fraction(t.goals, t.courses) >= kGoalFraction});
  t.checks.push_back({"alpha_at_launch",
                      std::to_string(t.launches_prepared) + "/" + std::to_string(t.launches) + " launches (" +
                          percent(t.launches_prepared, t.launches) + ") with alpha >= " + number(kLaunchAlpha, 2) +
                          "; needed >= " + number(100.0f * kLaunchFraction, 0) + "%",
                      t.launches > 0 && fraction(t.launches_prepared, t.launches) >= kLaunchFraction});
  t.checks.push_back({"alpha_at_1m",
                      std::to_string(t.prepared_1m) + "/" + std::to_string(t.measured_1m) + " measured launches (" +
                          percent(t.prepared_1m, t.measured_1m) + ") with alpha >= " + number(kAlpha1m, 2) +
                          " 1 m before the launch point; needed >= " + number(100.0f * kAlpha1mFraction, 0) + "%",
                      t.measured_1m > 0 && fraction(t.prepared_1m, t.measured_1m) >= kAlpha1mFraction});
  t.checks.push_back({"path_ratio",
                      "median " + number(t.path_median, 3) + ", 95th percentile " + number(t.path_p95, 3) + " over " +
                          std::to_string(ratios.size()) + " courses; needed median <= " + number(kPathMedian, 2) +
                          " and p95 <= " + number(kPathP95, 2),
                      !ratios.empty() && t.path_median <= kPathMedian && t.path_p95 <= kPathP95});
  t.checks.push_back({"no_source_alpha",
                      "median " + number(t.no_source_median, 3) + " (mean " + number(t.no_source_mean, 3) + ") over " +
                          std::to_string(no_source.size()) + " ticks; needed median <= " + number(kNoSourceMedian, 2),
                      !no_source.empty() && t.no_source_median <= kNoSourceMedian});
  t.checks.push_back({"circling",
                      std::to_string(t.circling_courses) + " courses circling (" + number(t.circling_seconds, 1) +
                          " s); needed none",
                      t.circling_courses == 0});
  t.checks.push_back({"weaving",
                      std::to_string(t.weaving_courses) + " courses weaving (" + number(t.reversals_per_minute, 1) +
                          " turn reversals a minute); needed <= " + std::to_string(kWeavePercent) + "% of " +
                          std::to_string(t.courses),
                      t.courses > 0 && 100 * t.weaving_courses <= kWeavePercent * t.courses});
  return t;
}

// ---------------------------------------------------------------------------------------------------------
// JSON

nlohmann::json course_json(const CourseEvaluation& e) {
  nlohmann::json j;
  j["name"] = e.name;
  j["description"] = e.description;
  j["seconds"] = e.seconds;
  j["reached_goal"] = e.reached_goal;
  j["goal_time_s"] = e.reached_goal ? nlohmann::json(e.goal_time) : nlohmann::json(nullptr);
  j["route_length_m"] = e.route_length;
  j["path_length_m"] = e.path_length;
  j["path_ratio"] = number_or_null(e.path_ratio);
  j["objects"] = e.objects;
  j["objects_unused"] = e.objects_unused;
  j["launches"] = nlohmann::json::array();
  for (const CourseLaunch& l : e.launches) {
    nlohmann::json lj;
    lj["action"] = target_action_name(l.action);
    lj["time_s"] = l.time;
    lj["alpha_at_launch"] = l.alpha_at_launch;
    lj["alpha_at_1m"] = l.alpha_at_1m >= 0.0f ? nlohmann::json(l.alpha_at_1m) : nlohmann::json(nullptr);
    if (l.object >= 0) lj["object"] = l.object;
    if (l.target_character >= 0) lj["target_character"] = l.target_character;
    lj["min_clearance_m"] = number_or_null(l.min_clearance);
    lj["slide_m"] = {l.slide_forward, l.slide_side};
    lj["turn_deg"] = l.turn * 57.2957795f;
    if (l.action == TargetAction::Kick) lj["strike_gap_m"] = number_or_null(l.strike_gap);
    j["launches"].push_back(lj);
  }
  j["kept_preparation"] = nlohmann::json::array();
  for (const KeptPreparation& k : e.kept)
    j["kept_preparation"].push_back({{"launches", {k.first, k.second}}, {"distance_m", k.distance}, {"min_alpha", k.min_alpha}});
  j["no_source"] = {{"ticks", e.no_source_alpha.size()},
                    {"alpha_mean", number_or_null(e.no_source_mean())},
                    {"alpha_median", number_or_null(e.no_source_median())},
                    {"relax_times_s", e.relax_times},
                    {"unrelaxed_episodes", e.unrelaxed_episodes}};
  j["circling"] = {{"seconds", e.circling_seconds}, {"visits", e.circling_visits}, {"max_visit_turn_deg", e.max_visit_turn_deg}};
  j["weaving"] = {{"turn_reversals", e.turn_reversals}, {"most_reversals_in_window", e.most_reversals_in_window}};
  j["swerving"] = {{"approaches", e.approaches}, {"swerving", e.swerving_approaches}, {"widest_deg", e.widest_approach_deg}};
  j["clearance"] = clearance_json(e.clearance);
  return j;
}

nlohmann::json course_totals_json(const CourseTotals& t) {
  auto fraction = [](int part, int whole) {
    return whole > 0 ? nlohmann::json(static_cast<double>(part) / whole) : nlohmann::json(nullptr);
  };
  nlohmann::json j;
  j["courses"] = t.courses;
  j["goal_reached"] = fraction(t.goals, t.courses);
  j["launches"] = t.launches;
  j["alpha_at_launch_prepared"] = fraction(t.launches_prepared, t.launches);
  j["alpha_at_1m_measured"] = t.measured_1m;
  j["alpha_at_1m_prepared"] = fraction(t.prepared_1m, t.measured_1m);
  j["objects"] = t.objects;
  j["objects_unused"] = t.objects_unused;
  j["path_ratio_median"] = number_or_null(t.path_median);
  j["path_ratio_p95"] = number_or_null(t.path_p95);
  j["no_source_alpha_median"] = number_or_null(t.no_source_median);
  j["no_source_alpha_mean"] = number_or_null(t.no_source_mean);
  j["relax_time_median_s"] = number_or_null(t.relax_median);
  j["relax_time_max_s"] = number_or_null(t.relax_max);
  j["unrelaxed_episodes"] = t.unrelaxed_episodes;
  j["circling_courses"] = t.circling_courses;
  j["circling_seconds"] = t.circling_seconds;
  j["weaving_courses"] = t.weaving_courses;
  j["turn_reversals_per_minute"] = t.reversals_per_minute;
  j["approaches"] = t.approaches;
  j["swerving_approaches"] = t.swerving_approaches;
  j["kept_pairs"] = t.kept_pairs;
  j["kept_min_alpha"] = number_or_null(t.kept_min);
  j["kept_median_alpha"] = number_or_null(t.kept_median);
  j["penetrating_courses"] = t.penetrating_courses;
  j["overlapping_courses"] = t.overlapping_courses;
  j["min_object_clearance_m"] = number_or_null(t.min_object_clearance);
  j["min_object_clearance"] = t.min_object_what;
  j["min_character_clearance_m"] = number_or_null(t.min_character_clearance);
  j["min_character_clearance"] = t.min_character_what;
  nlohmann::json checks = nlohmann::json::object();
  for (const CourseCheck& c : t.checks) checks[c.name] = {{"pass", c.pass}, {"measure", c.measure}};
  j["checks"] = checks;
  j["pass"] = t.pass();
  return j;
}

}  // namespace prep
