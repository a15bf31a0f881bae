#include "engine/world/evaluation.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>

#include "engine/motion/kinematics.h"

namespace prep {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

int span_ticks(float dt) { return std::max(1, static_cast<int>(std::lround(metric::kSpeedSpan / dt))); }

// The 0 = heel (ankle joint), 1 = toe tip points of both feet of a posed skeleton.
std::array<std::array<glm::vec3, 2>, 2> foot_pair(const MotionSet& set, const std::vector<glm::vec3>& positions,
                                                  const std::vector<glm::quat>& rotations) {
  const FootPoints f = foot_points(*set.skeleton, set.body, positions, rotations);
  return {{{f.heel[0], f.toe[0]}, {f.heel[1], f.toe[1]}}};
}

// The skate of one foot in contact: the height-weighted slide of its point in contact (heel or toe tip as
// the contact labels say; both down: the one nearer its planted height, which bears the weight).
float contact_slide(const EvaluationReference& r, size_t side, const FootContact& contact,
                    const std::array<glm::vec3, 2>& previous, const std::array<glm::vec3, 2>& current, float dt) {
  size_t k = contact.toe ? 1 : 0;
  if (contact.heel && contact.toe)
    k = current[1].y - r.planted_height[side][1] < current[0].y - r.planted_height[side][0] ? 1 : 0;
  return weighted_slide(previous[k], current[k], r.planted_height[side][k], dt);
}

float median(std::vector<float> v) {
  if (v.empty()) return 0.0f;
  const size_t mid = v.size() / 2;
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(mid), v.end());
  return v[mid];
}

}  // namespace

const char* method_name(EvaluationMethod method) {
  switch (method) {
    case EvaluationMethod::Ours: return "ours";
    case EvaluationMethod::Linear: return "linear";
    case EvaluationMethod::Naive: return "naive";
  }
  return "?";
}

std::optional<EvaluationMethod> parse_method(std::string_view name) {
  for (EvaluationMethod m : {EvaluationMethod::Ours, EvaluationMethod::Linear, EvaluationMethod::Naive})
    if (name == method_name(m)) return m;
  return std::nullopt;
}

Params method_params(EvaluationMethod method, Params base) {
  if (method == EvaluationMethod::Linear) base.blend.method = "linear";
  return base;
}

// ---------------------------------------------------------------------------------------------------------
// The measures

float skate_weight(float height_above_planted) {
  return std::clamp(2.0f - std::exp2(height_above_planted / metric::kSkateHeight), 0.0f, 1.0f);
}

float weighted_slide(const glm::vec3& previous, const glm::vec3& current, float planted, float dt) {
  const float slide = glm::length(glm::vec2(current.x - previous.x, current.z - previous.z));
  // A slide over a step of dt seconds is that of 1 / (60 dt) frames at 60 Hz.
  return skate_weight(current.y - planted) * slide / (metric::kSkateFrameRate * dt);
}

float speed_at(const std::vector<glm::vec2>& positions, float dt, int k) {
  const int n = span_ticks(dt);
  if (k - n < 0 || k >= static_cast<int>(positions.size())) return 0.0f;
  return glm::length(positions[static_cast<size_t>(k)] - positions[static_cast<size_t>(k - n)]) / (n * dt);
}

float peak_deceleration(const std::vector<glm::vec2>& positions, float dt, int first, int last) {
  const int n = span_ticks(dt);
  first = std::max(first, 2 * n);  // two spans of samples behind it
  last = std::min(last, static_cast<int>(positions.size()) - 1);
  float peak = 0.0f;
  for (int k = first; k <= last; ++k)
    peak = std::max(peak, (speed_at(positions, dt, k - n) - speed_at(positions, dt, k)) / (n * dt));
  return peak;
}

float preparation_lead(const std::vector<float>& alpha, int launch, int earliest, float dt) {
  if (launch < 0 || launch >= static_cast<int>(alpha.size()) || alpha[static_cast<size_t>(launch)] <= metric::kLeadAlpha)
    return 0.0f;
  int first = launch;
  while (first - 1 >= std::max(earliest, 0) && alpha[static_cast<size_t>(first - 1)] > metric::kLeadAlpha) --first;
  return static_cast<float>(launch - first) * dt;
}

// ---------------------------------------------------------------------------------------------------------
// Upper-body pose index

UpperBodyPoseIndex::UpperBodyPoseIndex(const MotionSet& set) : skeleton_(set.skeleton) {
  const BodyMap& b = set.body;
  std::vector<int> j(b.spine.begin(), b.spine.end());
  j.push_back(b.neck);
  j.push_back(b.head);
  for (const ArmChain& arm : b.arms) j.insert(j.end(), {arm.collar, arm.shoulder, arm.elbow, arm.wrist});
  j.erase(std::remove_if(j.begin(), j.end(), [&](int x) { return x < 0 || x == b.root; }), j.end());
  std::sort(j.begin(), j.end());
  j.erase(std::unique(j.begin(), j.end()), j.end());
  joints_ = j;

  const int d = dimension();
  std::vector<float> raw;
  std::vector<glm::vec3> positions;
  for (const MotionClip& mc : set.clips) count_ += mc.clip.frames.size();
  raw.resize(count_ * static_cast<size_t>(d));
  size_t item = 0;
  for (const MotionClip& mc : set.clips)
    for (const Pose& p : mc.clip.frames) feature(p, positions, &raw[item++ * static_cast<size_t>(d)]);
  std::vector<int> order(count_);
  std::iota(order.begin(), order.end(), 0);
  nodes_.reserve(2 * count_ / 16 + 2);
  if (count_ > 0) build(0, static_cast<int>(count_), order, raw);
  features_.resize(raw.size());
  for (size_t i = 0; i < count_; ++i)
    std::copy_n(&raw[static_cast<size_t>(order[i]) * static_cast<size_t>(d)], d, &features_[i * static_cast<size_t>(d)]);
}

void UpperBodyPoseIndex::feature(const Pose& pose, std::vector<glm::vec3>& positions, float* out) const {
  forward_kinematics(*skeleton_, pose, positions);
  const glm::vec3 root = positions[0];
  const glm::quat unturn = glm::angleAxis(-heading_of(pose.rotations[0]), glm::vec3(0, 1, 0));
  for (size_t k = 0; k < joints_.size(); ++k) {
    const glm::vec3 p = unturn * (positions[static_cast<size_t>(joints_[k])] - root);
    out[3 * k] = p.x;
    out[3 * k + 1] = p.y;
    out[3 * k + 2] = p.z;
  }
}

int UpperBodyPoseIndex::build(int begin, int end, std::vector<int>& order, const std::vector<float>& raw) {
  const int index = static_cast<int>(nodes_.size());
  nodes_.push_back({begin, end, -1, 0.0f, -1, -1});
  if (end - begin <= 16) return index;
  const int d = dimension();
  int best_dim = 0;
  float best_spread = -1.0f;
  for (int k = 0; k < d; ++k) {
    float lo = std::numeric_limits<float>::infinity(), hi = -lo;
    for (int i = begin; i < end; ++i) {
      const float v = raw[static_cast<size_t>(order[static_cast<size_t>(i)]) * static_cast<size_t>(d) + static_cast<size_t>(k)];
      lo = std::min(lo, v);
      hi = std::max(hi, v);
    }
    if (hi - lo > best_spread) best_spread = hi - lo, best_dim = k;
  }
  if (best_spread <= 0.0f) return index;  // identical features: a leaf however many
  const int mid = (begin + end) / 2;
  auto value = [&](int item) { return raw[static_cast<size_t>(item) * static_cast<size_t>(d) + static_cast<size_t>(best_dim)]; };
  std::nth_element(order.begin() + begin, order.begin() + mid, order.begin() + end,
                   [&](int a, int b) { return value(a) < value(b); });
  const float split = value(order[static_cast<size_t>(mid)]);
  const int left = build(begin, mid, order, raw);
  const int right = build(mid, end, order, raw);
  Node& n = nodes_[static_cast<size_t>(index)];
  n.dim = best_dim;
  n.split = split;  // left holds values <= split, right values >= split
  n.left = left;
  n.right = right;
  return index;
}

float UpperBodyPoseIndex::squared_distance(const float* q, size_t item, float bound) const {
  const size_t d = static_cast<size_t>(dimension());
  const float* f = &features_[item * d];
  float s = 0.0f;
  for (size_t k = 0; k < d; k += 3) {  // one joint at a time, stopping once past the bound
    const float a = q[k] - f[k], b = q[k + 1] - f[k + 1], c = q[k + 2] - f[k + 2];
    s += a * a + b * b + c * c;
    if (s >= bound) return s;
  }
  return s;
}

void UpperBodyPoseIndex::search(int node, const float* q, float& best) const {
  const Node& n = nodes_[static_cast<size_t>(node)];
  if (n.dim < 0) {
    for (int i = n.begin; i < n.end; ++i) best = std::min(best, squared_distance(q, static_cast<size_t>(i), best));
    return;
  }
  const float gap = q[n.dim] - n.split;
  const int near = gap <= 0.0f ? n.left : n.right, far = gap <= 0.0f ? n.right : n.left;
  search(near, q, best);
  if (gap * gap < best) search(far, q, best);
}

float UpperBodyPoseIndex::nearest_distance(const float* feature) const {
  if (count_ == 0 || joints_.empty()) return 0.0f;
  float best = std::numeric_limits<float>::infinity();
  search(0, feature, best);
  return std::sqrt(best / static_cast<float>(joints()));
}

float UpperBodyPoseIndex::nearest_distance_brute_force(const float* feature) const {
  if (count_ == 0 || joints_.empty()) return 0.0f;
  float best = std::numeric_limits<float>::infinity();
  for (size_t i = 0; i < count_; ++i) best = std::min(best, squared_distance(feature, i, best));
  return std::sqrt(best / static_cast<float>(joints()));
}

float UpperBodyPoseIndex::distance_to_database(const Pose& pose) const {
  std::vector<glm::vec3> positions;
  std::vector<float> f(static_cast<size_t>(dimension()));
  feature(pose, positions, f.data());
  return nearest_distance(f.data());
}

EvaluationReference::EvaluationReference(const MotionSet& set) : poses(set) {
  // Where each foot point rests when planted: the median of its height over the frames the set's contact
  // detection has it down (the ankle joint sits above the sole; captured floors are not exactly at 0).
  std::array<std::array<std::vector<float>, 2>, 2> heights;
  std::vector<glm::vec3> positions;
  std::vector<glm::quat> rotations;
  for (const MotionClip& mc : set.clips)
    for (size_t f = 0; f < mc.clip.frames.size() && f < mc.contacts.size(); ++f) {
      forward_kinematics(*set.skeleton, mc.clip.frames[f], positions, &rotations);
      const auto feet = foot_pair(set, positions, rotations);
      for (size_t s = 0; s < 2; ++s) {
        if (mc.contacts[f][s].heel) heights[s][0].push_back(feet[s][0].y);
        if (mc.contacts[f][s].toe) heights[s][1].push_back(feet[s][1].y);
      }
    }
  for (size_t s = 0; s < 2; ++s)
    for (size_t k = 0; k < 2; ++k) planted_height[s][k] = median(heights[s][k]);
}

double clip_foot_skate_cm_per_frame(const MotionSet& set, const MotionClip& mc, const EvaluationReference& reference) {
  const Clip& clip = mc.clip;
  if (clip.frames.empty() || mc.contacts.size() != clip.frames.size()) return kNaN;
  const float dt = 1.0f / metric::kSkateFrameRate;
  const int samples = static_cast<int>(std::floor(clip.duration() / dt));
  std::vector<glm::vec3> positions;
  std::vector<glm::quat> rotations;
  Pose pose;
  std::array<std::array<glm::vec3, 2>, 2> previous{};
  double sum = 0.0;
  long count = 0;
  for (int i = 0; i <= samples; ++i) {
    clip.sample(static_cast<float>(i) * dt, pose);
    forward_kinematics(*set.skeleton, pose, positions, &rotations);
    const auto feet = foot_pair(set, positions, rotations);
    const int f = std::min(clip.frame_count() - 1, static_cast<int>(std::lround(static_cast<float>(i) * dt * clip.fps)));
    for (size_t s = 0; i > 0 && s < 2; ++s) {
      const FootContact& contact = mc.contacts[static_cast<size_t>(f)][s];
      if (!contact.any()) continue;
      sum += contact_slide(reference, s, contact, previous[s], feet[s], dt);
      ++count;
    }
    previous = feet;
  }
  return count > 0 ? 100.0 * sum / static_cast<double>(count) : kNaN;
}

// ---------------------------------------------------------------------------------------------------------
// Results

double FrameTotals::foot_skate_cm_per_frame() const {
  return contact_foot_frames > 0 ? 100.0 * skate_m / static_cast<double>(contact_foot_frames) : kNaN;
}
double FrameTotals::com_in_support() const {
  return balance_frames > 0 ? static_cast<double>(balance_inside) / static_cast<double>(balance_frames) : kNaN;
}
double FrameTotals::pose_plausibility_cm() const {
  return synthesized_frames > 0 ? 100.0 * plausibility_m / static_cast<double>(synthesized_frames) : kNaN;
}
FrameTotals& FrameTotals::operator+=(const FrameTotals& o) {
  frames += o.frames;
  synthesized_frames += o.synthesized_frames;
  contact_foot_frames += o.contact_foot_frames;
  skate_m += o.skate_m;
  plausibility_m += o.plausibility_m;
  balance_frames += o.balance_frames;
  balance_inside += o.balance_inside;
  return *this;
}

FrameTotals Evaluation::totals() const {
  FrameTotals t;
  for (const CharacterEvaluation& c : characters) t += c.totals;
  return t;
}

std::vector<LaunchEvaluation> Evaluation::launches() const {
  std::vector<LaunchEvaluation> all;
  for (const CharacterEvaluation& c : characters) all.insert(all.end(), c.launches.begin(), c.launches.end());
  std::stable_sort(all.begin(), all.end(), [](const auto& a, const auto& b) { return a.time < b.time; });
  return all;
}

// ---------------------------------------------------------------------------------------------------------
// Recorder

EvaluationRecorder::EvaluationRecorder(const World& world, const EvaluationReference& reference)
    : reference_(&reference), clearance_(world), tracks_(world.characters().size()) {
  feature_.resize(static_cast<size_t>(reference.poses.dimension()));
  launches_seen_ = world.launches().size();
  first_launch_record_ = launches_seen_;
  times_.push_back(world.time());
  for (size_t i = 0; i < tracks_.size(); ++i) {
    tracks_[i].in_target = world.characters()[i].in_target;
    measure_frame(world, static_cast<int>(i), tracks_[i], 0);
  }
}

void EvaluationRecorder::measure_frame(const World& world, int index, Track& t, int tick) {
  const WorldCharacter& c = world.characters()[static_cast<size_t>(index)];
  const MotionSet& set = *world.assets().set;
  const float dt = world.params().runtime.fixed_dt;
  t.positions.push_back(c.position);
  t.alpha.push_back(c.alpha);
  ++t.totals.frames;

  forward_kinematics(*set.skeleton, c.pose, positions_, &rotations_);
  const auto feet = foot_pair(set, positions_, rotations_);
  const bool synthesized = !c.in_target || tick <= t.fade_until;
  if (synthesized) {
    ++t.totals.synthesized_frames;
    if (t.has_feet) {
      for (size_t s = 0; s < 2; ++s) {
        const FootContact& contact = c.contacts[s];
        if (!contact.any()) continue;
        ++t.totals.contact_foot_frames;
        t.totals.skate_m += contact_slide(*reference_, s, contact, t.feet[s], feet[s], dt);
      }
    }
    if (c.alpha >= metric::kBalanceAlpha) {
      ++t.totals.balance_frames;
      if (c.com_in_support) ++t.totals.balance_inside;
    }
    reference_->poses.feature(c.pose, positions_, feature_.data());
    t.totals.plausibility_m += reference_->poses.nearest_distance(feature_.data());
  }
  t.feet = feet;
  t.has_feet = true;
}

void EvaluationRecorder::observe(const World& world) {
  clearance_.observe(world);
  const int tick = static_cast<int>(times_.size());
  times_.push_back(world.time());
  const float dt = world.params().runtime.fixed_dt;
  const int fade_ticks = static_cast<int>(std::lround(world.params().graph.blend_s / dt));
  // Launches of this tick: the character's pose observed now is still the one before the launch (the
  // world launches at the end of the character's step); the cross-fade into the target follows.
  std::vector<bool> launched(tracks_.size(), false);
  for (; launches_seen_ < world.launches().size(); ++launches_seen_) {
    const LaunchRecord& r = world.launches()[launches_seen_];
    if (r.character < 0 || r.character >= static_cast<int>(tracks_.size())) continue;
    Track& t = tracks_[static_cast<size_t>(r.character)];
    t.launch_ticks.push_back(tick);
    t.launch_records.push_back(static_cast<int>(launches_seen_));
    t.fade_until = tick + fade_ticks;
    launched[static_cast<size_t>(r.character)] = true;
  }
  for (size_t i = 0; i < tracks_.size(); ++i) {
    Track& t = tracks_[i];
    const WorldCharacter& c = world.characters()[i];
    if (t.in_target && !c.in_target) t.return_ticks.push_back(tick);
    // Synthesizer::step ran this tick unless the character played a target motion all through it.
    if (!c.in_target || launched[i]) ++synthesis_calls_;
    t.in_target = c.in_target;
    measure_frame(world, static_cast<int>(i), t, tick);
  }
  synthesis_ms_ += world.stage_times().synthesis_ms;
}

Evaluation EvaluationRecorder::finish(const World& world, EvaluationMethod method) const {
  Evaluation e;
  e.scenario = world.scenario().name;
  e.motions = world.assets().set->name;  // "builtin", "daz43", ... (the scenario names a manifest path)
  e.method = method;
  e.seconds = world.time();
  e.ticks = world.ticks();
  e.times = times_;
  e.user = world.user();
  e.synthesis_calls = synthesis_calls_;
  e.clearance = clearance_.summary;
  e.synthesis_us_per_frame = synthesis_calls_ > 0 ? 1000.0 * synthesis_ms_ / static_cast<double>(synthesis_calls_) : kNaN;
  const float dt = world.params().runtime.fixed_dt;
  const int window_ticks = static_cast<int>(std::lround(metric::kDecelWindow / dt));
  for (size_t i = 0; i < tracks_.size(); ++i) {
    const Track& t = tracks_[i];
    const WorldCharacter& c = world.characters()[i];
    CharacterEvaluation ce;
    ce.index = static_cast<int>(i);
    ce.control = c.control;
    ce.reached_goal = c.control == Control::User && c.reached_goal;
    ce.time_to_goal_s = ce.reached_goal ? c.reached_time : -1.0f;
    ce.totals = t.totals;
    ce.alpha = t.alpha;
    for (size_t k = 0; k < t.launch_ticks.size(); ++k) {
      const LaunchRecord& r = world.launches()[static_cast<size_t>(t.launch_records[k])];
      const int L = t.launch_ticks[k];
      // The preparation run may not reach back past the end of the previous target motion.
      int earliest = 0;
      for (int back : t.return_ticks)
        if (back <= L) earliest = std::max(earliest, back);
      LaunchEvaluation l;
      l.action = r.action;
      l.time = r.time;
      l.automatic = r.automatic;
      l.object = r.object;
      l.target_character = r.target_character;
      l.alpha_at_launch = r.alpha_at_launch;
      l.prep_lead_s = preparation_lead(t.alpha, L, earliest, dt);
      // Up to the hand-over: the last span before the launch against the first of the clip (the clip plays
      // from the tick after L). Later falls are the recorded clip's own, the same for every method.
      l.peak_decel_mps2 = peak_deceleration(t.positions, dt, L - window_ticks, L + span_ticks(dt));
      l.speed_at_launch_mps = speed_at(t.positions, dt, L);
      const size_t record = static_cast<size_t>(t.launch_records[k]) - first_launch_record_;
      l.min_clearance = record < clearance_.launches.size() ? clearance_.launches[record].min_clearance : kNaN;
      l.strike_gap = record < clearance_.launches.size() ? clearance_.launches[record].strike_gap : kNaN;
      ce.launches.push_back(l);
    }
    e.characters.push_back(std::move(ce));
  }
  return e;
}

Evaluation evaluate_scenario(const Scenario& scenario, std::shared_ptr<const WorldAssets> assets,
                             const EvaluationReference& reference, EvaluationMethod method, float max_seconds) {
  World world(scenario, std::move(assets));
  world.set_auto(true);
  world.set_preparation(method != EvaluationMethod::Naive);
  EvaluationRecorder recorder(world, reference);
  world.run_until_done(max_seconds, metric::kSettle, [&](const World& w) { recorder.observe(w); });
  return recorder.finish(world, method);
}

// ---------------------------------------------------------------------------------------------------------
// JSON

namespace {

nlohmann::json number_or_null(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }

void put_frame_metrics(nlohmann::json& j, const FrameTotals& t) {
  j["frames"] = t.frames;
  j["synthesized_frames"] = t.synthesized_frames;
  j["foot_skate_cm_per_frame"] = number_or_null(t.foot_skate_cm_per_frame());
  j["com_in_support"] = number_or_null(t.com_in_support());
  j["com_frames"] = t.balance_frames;
  j["pose_plausibility"] = number_or_null(t.pose_plausibility_cm());
}

nlohmann::json launch_json(const LaunchEvaluation& l, int character) {
  nlohmann::json j;
  j["action"] = target_action_name(l.action);
  j["character"] = character;
  j["time_s"] = l.time;
  j["automatic"] = l.automatic;
  j["alpha_at_launch"] = l.alpha_at_launch;
  j["prep_lead_s"] = l.prep_lead_s;
  j["peak_decel_mps2"] = l.peak_decel_mps2;
  j["speed_at_launch_mps"] = l.speed_at_launch_mps;
  if (l.object >= 0) j["object"] = l.object;
  if (l.target_character >= 0) j["target_character"] = l.target_character;
  j["min_clearance_m"] = number_or_null(l.min_clearance);
  if (l.action == TargetAction::Kick) j["strike_gap_m"] = number_or_null(l.strike_gap);
  return j;
}

}  // namespace

nlohmann::json evaluation_json(const Evaluation& e) {
  nlohmann::json j;
  j["scenario"] = e.scenario;
  j["motions"] = e.motions;
  j["method"] = method_name(e.method);
  j["seconds"] = e.seconds;
  j["ticks"] = e.ticks;
  const CharacterEvaluation& u = e.characters[static_cast<size_t>(e.user)];
  nlohmann::json total;
  total["reached_goal"] = u.reached_goal;
  total["time_to_goal_s"] = u.reached_goal ? nlohmann::json(u.time_to_goal_s) : nlohmann::json(nullptr);
  total["launches"] = nlohmann::json::array();
  for (const CharacterEvaluation& c : e.characters)
    for (const LaunchEvaluation& l : c.launches) total["launches"].push_back(launch_json(l, c.index));
  std::stable_sort(total["launches"].begin(), total["launches"].end(),
                   [](const nlohmann::json& a, const nlohmann::json& b) { return a["time_s"].get<double>() < b["time_s"].get<double>(); });
  put_frame_metrics(total, e.totals());
  total["synthesis_us_per_frame"] = number_or_null(e.synthesis_us_per_frame);
  total["synthesis_calls"] = e.synthesis_calls;
  total["clearance"] = clearance_json(e.clearance);
  j["total"] = total;
  j["characters"] = nlohmann::json::array();
  for (const CharacterEvaluation& c : e.characters) {
    nlohmann::json cj;
    cj["index"] = c.index;
    cj["control"] = control_name(c.control);
    if (c.control == Control::User) {
      cj["reached_goal"] = c.reached_goal;
      cj["time_to_goal_s"] = c.reached_goal ? nlohmann::json(c.time_to_goal_s) : nlohmann::json(nullptr);
    }
    cj["launches"] = nlohmann::json::array();
    for (const LaunchEvaluation& l : c.launches) cj["launches"].push_back(launch_json(l, c.index));
    put_frame_metrics(cj, c.totals);
    j["characters"].push_back(cj);
  }
  return j;
}

}  // namespace prep
