#include "engine/world/evaluation.h"

#include <doctest/doctest.h>

#include <cmath>
#include <memory>
#include <random>
#include <vector>

#include "engine/library/builtin.h"
#include "engine/world/policy_cache.h"
#include "tests/support/paths.h"
#include "tests/synthesis/test_rig.h"

using namespace prep;

namespace {

constexpr float kDt = 1.0f / 60.0f;

// The hand-made humanoid of the synthesis tests as a one-clip motion set: the whole body glides along +X
// at `speed` m/s with its root `lift` m above standing height, for `frames` frames at `fps`. In the rest
// pose the feet are flat: the ankle joint 5 cm above the floor, the toe tip on it.
MotionSet gliding_set(float speed, float lift, int frames, float fps) {
  MotionSet set;
  set.name = "gliding";
  set.skeleton = test::make_test_skeleton();
  MotionClip mc;
  mc.clip.name = "glide";
  mc.clip.skeleton = set.skeleton;
  mc.clip.fps = fps;
  for (int f = 0; f < frames; ++f) {
    Pose p(set.skeleton->size());
    p.root_position = {speed * static_cast<float>(f) / fps, 0.95f + lift, 0.0f};
    mc.clip.frames.push_back(p);
  }
  set.clips.push_back(mc);
  finalize_motion_set(set, Params{});
  return set;
}

// A floor path sampled every kDt: `speed` m/s along +Z until `brake_at` s, then slowing at `decel` m/s^2
// to a standstill.
std::vector<glm::vec2> braking_path(float speed, float brake_at, float decel, float seconds) {
  std::vector<glm::vec2> p;
  for (int k = 0; k * kDt <= seconds; ++k) {
    const float t = k * kDt, stop = brake_at + speed / decel;
    float z;
    if (t <= brake_at) {
      z = speed * t;
    } else {
      const float u = std::min(t, stop) - brake_at;
      z = speed * brake_at + speed * u - 0.5f * decel * u * u;
    }
    p.push_back({0.3f, z});
  }
  return p;
}

std::shared_ptr<const MotionSet> builtin_set() {
  static auto set = std::make_shared<const MotionSet>(make_builtin_motion_set(Params{}));
  return set;
}

}  // namespace

TEST_CASE("the skate weight is 1 on the floor, 2 - sqrt 2 at half of H = 2.5 cm and 0 from H up") {
  CHECK(skate_weight(0.0f) == doctest::Approx(1.0f));
  CHECK(skate_weight(-0.01f) == doctest::Approx(1.0f));  // below the planted height: clamped
  CHECK(skate_weight(0.0125f) == doctest::Approx(2.0f - std::sqrt(2.0f)));
  CHECK(skate_weight(0.025f) == doctest::Approx(0.0f));
  CHECK(skate_weight(0.10f) == doctest::Approx(0.0f));
  // A slide of 1 cm in a 60 Hz frame, 1.25 cm above the planted height of 5 cm.
  CHECK(weighted_slide({0, 0.0625f, 0}, {0.006f, 0.0625f, 0.008f}, 0.05f, kDt) == doctest::Approx(0.01f * (2.0f - std::sqrt(2.0f))));
  // The same slide over a 30 Hz step is half a centimetre per 60 Hz frame.
  CHECK(weighted_slide({0, 0.05f, 0}, {0.01f, 0.05f, 0}, 0.05f, 2 * kDt) == doctest::Approx(0.005f));
}

TEST_CASE("a foot in contact sliding 1 cm a frame at a known height gives the known weighted skate") {
  // 0.6 m/s = 1 cm per 60 Hz frame; the root 1.25 cm above standing, so heel and toe are H/2 above planted.
  for (float fps : {60.0f, 30.0f}) {
    CAPTURE(fps);
    MotionSet set = gliding_set(0.6f, 0.0125f, static_cast<int>(fps) + 1, fps);
    MotionClip& mc = set.clips[0];
    // Contact labels by hand: the left foot flat on the floor throughout, the right foot in the air (its
    // slide, just as large and as low, must not count).
    for (FrameContacts& c : mc.contacts) c = {FootContact{true, true}, FootContact{false, false}};
    EvaluationReference reference(set);
    reference.planted_height = {{{0.05f, 0.0f}, {0.05f, 0.0f}}};
    const double skate = clip_foot_skate_cm_per_frame(set, mc, reference);
    CHECK(skate == doctest::Approx(1.0 * (2.0 - std::sqrt(2.0))).epsilon(1e-3));

    // Toe-only contact: the toe tip is the point that counts; 3 cm up it counts nothing.
    MotionSet high = gliding_set(0.6f, 0.03f, static_cast<int>(fps) + 1, fps);
    for (FrameContacts& c : high.clips[0].contacts) c = {FootContact{false, true}, FootContact{false, false}};
    CHECK(clip_foot_skate_cm_per_frame(high, high.clips[0], reference) == doctest::Approx(0.0));
  }
}

TEST_CASE("planted heights come from the frames the contact detection has down") {
  // Standing still on the floor: detected in contact; the ankle rests 5 cm up, the toe tip at 0.
  const MotionSet set = gliding_set(0.0f, 0.0f, 61, 60.0f);
  REQUIRE(set.clips[0].contacts[30][kLeft].heel);
  const EvaluationReference reference(set);
  for (int s : {kLeft, kRight}) {
    CHECK(reference.planted_height[static_cast<size_t>(s)][0] == doctest::Approx(0.05f).epsilon(1e-3));
    CHECK(reference.planted_height[static_cast<size_t>(s)][1] == doctest::Approx(0.0f));
  }
  // And a standing clip does not skate.
  CHECK(clip_foot_skate_cm_per_frame(set, set.clips[0], reference) == doctest::Approx(0.0));
}

TEST_CASE("a known deceleration profile gives its peak, a turn at constant speed is no deceleration") {
  const std::vector<glm::vec2> path = braking_path(1.5f, 1.0f, 3.0f, 2.0f);
  const int last = static_cast<int>(path.size()) - 1;
  CHECK(peak_deceleration(path, kDt, 0, last) == doctest::Approx(3.0f).epsilon(1e-3));
  // Before the brakes only constant speed: nothing.
  CHECK(peak_deceleration(path, kDt, 0, 55) == doctest::Approx(0.0f).scale(1.0f).epsilon(1e-4));
  CHECK(speed_at(path, kDt, 50) == doctest::Approx(1.5f).epsilon(1e-4));
  CHECK(speed_at(path, kDt, last) == doctest::Approx(0.0f).scale(1.0f).epsilon(1e-4));
  // A harder stop is a larger peak.
  CHECK(peak_deceleration(braking_path(1.5f, 1.0f, 7.5f, 2.0f), kDt, 0, last) == doctest::Approx(7.5f).epsilon(1e-3));

  std::vector<glm::vec2> circle;
  for (int k = 0; k < 120; ++k) {
    const float a = 1.2f * k * kDt;  // 1.2 m/s on a 1 m circle
    circle.push_back({std::cos(a), std::sin(a)});
  }
  CHECK(peak_deceleration(circle, kDt, 0, 119) < 0.01f);
}

TEST_CASE("the preparation lead counts from alpha first exceeding 0.1 to the launch") {
  std::vector<float> alpha(200, 0.0f);
  for (int k = 40; k < 200; ++k) alpha[static_cast<size_t>(k)] = std::min(1.0f, 0.02f * static_cast<float>(k - 40));
  // alpha = 0.02 (k - 40) > 0.1 from k = 46: a launch at k = 106 has a lead of 60 ticks = 1 s.
  CHECK(preparation_lead(alpha, 106, 0, kDt) == doctest::Approx(1.0f));
  // Bounded by the end of a previous target motion (the character kept its preparation through it).
  CHECK(preparation_lead(alpha, 106, 76, kDt) == doctest::Approx(0.5f));
  // Unprepared at the launch: no lead, whatever came before.
  alpha[150] = 0.05f;
  CHECK(preparation_lead(alpha, 150, 0, kDt) == doctest::Approx(0.0f));
  CHECK(preparation_lead(alpha, 160, 0, kDt) == doctest::Approx(9 * kDt));
  CHECK(preparation_lead(std::vector<float>(50, 0.0f), 30, 0, kDt) == 0.0f);
}

TEST_CASE("pose plausibility: a database pose is at distance 0, the k-d tree finds what a full scan finds") {
  const auto set = builtin_set();
  const UpperBodyPoseIndex index(*set);
  size_t frames = 0;
  for (const MotionClip& mc : set->clips) frames += mc.clip.frames.size();
  CHECK(index.size() == frames);
  // Spine, neck, head and four joints per arm, at least.
  CHECK(index.joints() >= 10);
  for (const MotionClip& mc : set->clips)
    for (size_t f = 0; f < mc.clip.frames.size(); f += 37) CHECK(index.distance_to_database(mc.clip.frames[f]) == 0.0f);

  // Poses away from the database: random rotations of the upper-body joints on walking frames.
  std::mt19937 rng(7);
  std::normal_distribution<float> noise(0.0f, 0.25f);
  const Clip& walk = set->clips[static_cast<size_t>(set->find("walk"))].clip;
  std::vector<glm::vec3> positions;
  std::vector<float> feature(static_cast<size_t>(index.dimension()));
  int positive = 0;
  for (int trial = 0; trial < 40; ++trial) {
    Pose p = walk.frames[static_cast<size_t>(trial * 3) % walk.frames.size()];
    for (size_t j = 1; j < p.rotations.size(); ++j)
      if (set->body.upper_body[j])
        p.rotations[j] = glm::normalize(p.rotations[j] * glm::quat(1.0f, noise(rng), noise(rng), noise(rng)));
    index.feature(p, positions, feature.data());
    const float tree = index.nearest_distance(feature.data()), scan = index.nearest_distance_brute_force(feature.data());
    CHECK(tree == doctest::Approx(scan).epsilon(1e-6));
    positive += tree > 0.01f;
  }
  CHECK(positive == 40);

  // Where the root stands and which way it faces do not matter.
  Pose moved = walk.frames[10];
  moved.root_position += glm::vec3(3.0f, 0.0f, -2.0f);
  moved.rotations[0] = glm::angleAxis(1.3f, glm::vec3(0, 1, 0)) * moved.rotations[0];
  CHECK(index.distance_to_database(moved) == doctest::Approx(0.0f).scale(1.0f).epsilon(1e-5));
}

TEST_CASE("evaluate_scenario: naive never prepares, ours does, and the measures add up") {
  const Scenario s = load_scenario(test::repo() + "/assets/scenarios/kick.json");
  const Params params = load_scenario_params(s);
  const auto set = builtin_set();
  const EvaluationReference reference(*set);
  auto assets = std::make_shared<WorldAssets>(make_world_assets(set, params));
  assets->policy = load_or_train_policy(*set, *assets->graph, params, test::tmp_dir() + "/policy-cache");

  const Evaluation naive = evaluate_scenario(s, assets, reference, EvaluationMethod::Naive, 30.0f);
  const Evaluation ours = evaluate_scenario(s, assets, reference, EvaluationMethod::Ours, 30.0f);
  for (const Evaluation* e : {&naive, &ours}) {
    CAPTURE(std::string(method_name(e->method)));
    REQUIRE(e->characters.size() == 1);
    const CharacterEvaluation& u = e->characters[0];
    CHECK(e->times.size() == static_cast<size_t>(e->ticks) + 1);  // the first frame, then one per tick
    CHECK(u.alpha.size() == e->times.size());
    CHECK(u.totals.frames == e->ticks + 1);
    CHECK(u.totals.synthesized_frames <= u.totals.frames);
    CHECK(u.totals.synthesized_frames > u.totals.frames / 2);
    CHECK(u.totals.balance_inside <= u.totals.balance_frames);
    // The run ends a second after the goal was reached and the kick has finished, before the 30 s cap.
    REQUIRE(u.reached_goal);
    CHECK(e->seconds >= u.time_to_goal_s + metric::kSettle - 0.01f);
    CHECK(e->seconds < 30.0f - 0.5f);
    REQUIRE(u.launches.size() == 1);
    CHECK(u.launches[0].action == TargetAction::Kick);
    CHECK(std::isfinite(u.totals.foot_skate_cm_per_frame()));
    CHECK(u.totals.foot_skate_cm_per_frame() >= 0.0);
    CHECK(e->synthesis_calls > 0);
  }
  // Naive: alpha 0 throughout, so no preparation lead and no frame with alpha >= 0.3; its locomotion is
  // database poses (interpolated between frames and cross-faded), within a few millimetres of one.
  for (float a : naive.characters[0].alpha) CHECK(a == 0.0f);
  CHECK(naive.characters[0].launches[0].alpha_at_launch == 0.0f);
  CHECK(naive.characters[0].launches[0].prep_lead_s == 0.0f);
  CHECK(naive.totals().balance_frames == 0);
  CHECK(std::isnan(naive.totals().com_in_support()));
  CHECK(naive.totals().pose_plausibility_cm() < 1.0);
  // Ours prepares before the kick: the launch's alpha is the alpha recorded at that frame, and it rose
  // above 0.1 some time before.
  const CharacterEvaluation& u = ours.characters[0];
  const LaunchEvaluation& l = u.launches[0];
  CHECK(l.alpha_at_launch > 0.3f);
  CHECK(l.prep_lead_s > 0.0f);
  const size_t at = static_cast<size_t>(std::lround(l.time / kDt));
  CHECK(u.alpha[at] == doctest::Approx(l.alpha_at_launch));
  CHECK(u.alpha[at - static_cast<size_t>(std::lround(l.prep_lead_s / kDt))] > metric::kLeadAlpha);
  CHECK(ours.totals().balance_frames > 0);
  CHECK(ours.totals().pose_plausibility_cm() > naive.totals().pose_plausibility_cm());

  // The JSON carries every metric, null where undefined.
  const nlohmann::json j = evaluation_json(naive);
  CHECK(j["method"] == "naive");
  CHECK(j["total"]["com_in_support"].is_null());
  CHECK(j["total"]["launches"][0]["action"] == "kick");
  CHECK(j["characters"][0]["control"] == "user");
}

TEST_CASE("method names parse and linear runs with one blend weight") {
  CHECK(parse_method("ours") == EvaluationMethod::Ours);
  CHECK(parse_method("linear") == EvaluationMethod::Linear);
  CHECK(parse_method("naive") == EvaluationMethod::Naive);
  CHECK_FALSE(parse_method("Ours").has_value());
  CHECK(method_params(EvaluationMethod::Linear, Params{}).blend.method == "linear");
  CHECK(method_params(EvaluationMethod::Naive, Params{}).blend.method == "ours");
}
