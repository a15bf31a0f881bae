#include "engine/synthesis/balance.h"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>

#include "engine/motion/kinematics.h"
#include "engine/motion/support_polygon.h"
#include "test_rig.h"

namespace prep {
namespace {

Pose random_pose(int n, std::mt19937& rng, float spread) {
  std::uniform_real_distribution<float> u(-spread, spread);
  Pose p(n);
  for (auto& q : p.rotations) q = glm::angleAxis(glm::length(glm::vec3(u(rng), u(rng), u(rng))) + 0.01f, glm::normalize(glm::vec3(u(rng), u(rng), u(rng)) + glm::vec3(0.01f, 0.0f, 0.0f)));
  p.rotations[0] = glm::angleAxis(0.1f, glm::vec3(0, 1, 0));
  p.root_position = {0.1f, 0.9f, -0.2f};
  return p;
}

struct Fixture {
  std::shared_ptr<const Skeleton> skeleton = test::make_test_skeleton();
  BodyMap body = BodyMap::detect(*skeleton);
  MassModel mass = MassModel::build(*skeleton, body);
  BalanceModel model = BalanceModel::build(*skeleton, body, mass);
  int n = skeleton->size();
  int parts = static_cast<int>(model.parts.size());
};

std::vector<glm::vec3> centroids_of(const Fixture& f, const Pose& pose) {
  std::vector<glm::vec3> p;
  std::vector<glm::quat> r;
  forward_kinematics(*f.skeleton, pose, p, &r);
  std::vector<glm::vec3> c(static_cast<size_t>(f.parts));
  part_centroids(*f.skeleton, f.model, p, r, c.data());
  return c;
}

}  // namespace

TEST_CASE("body-part centroids and COM match the mass model's") {
  Fixture f;
  std::mt19937 rng(3);
  const Pose pose = random_pose(f.n, rng, 0.6f);
  std::vector<glm::vec3> p, expected;
  std::vector<glm::quat> r;
  forward_kinematics(*f.skeleton, pose, p, &r);
  segment_centroids(*f.skeleton, f.mass, p, r, expected);
  const std::vector<glm::vec3> ours = centroids_of(f, pose);
  REQUIRE(ours.size() == expected.size());
  for (size_t i = 0; i < ours.size(); ++i) CHECK(glm::length(ours[i] - expected[i]) < 1e-6f);
  CHECK(glm::length(model_center_of_mass(f.model, ours.data()) - center_of_mass(f.mass, expected)) < 1e-6f);
  // Only upper-body joints are optimized.
  for (int j : f.model.optimized) CHECK(f.body.upper_body[static_cast<size_t>(j)]);
  CHECK(f.model.optimized.size() >= 10);
}

TEST_CASE("the analytic gradient equals finite differences") {
  Fixture f;
  std::mt19937 rng(11);
  BalanceParams params;
  params.norm_smoothing = 1e-2f;  // keeps the cost smooth at the scale of the finite-difference step
  const Pose pose = random_pose(f.n, rng, 0.5f);
  const std::vector<glm::vec3> style = centroids_of(f, random_pose(f.n, rng, 0.5f));
  const std::vector<glm::vec3> prev = centroids_of(f, random_pose(f.n, rng, 0.5f));
  const std::vector<glm::vec3> prev2 = centroids_of(f, random_pose(f.n, rng, 0.5f));
  BalanceTargets targets;
  targets.support_centre = {0.25f, -0.1f};
  targets.style = style.data();
  targets.previous = prev.data();
  targets.before_previous = prev2.data();

  BalanceScratch s;
  s.resize(f.n, f.parts);
  forward_kinematics(*f.skeleton, pose, s.positions, &s.rotations);
  part_centroids(*f.skeleton, f.model, s.positions, s.rotations, s.centroids.data());
  balance_gradient(*f.skeleton, f.model, params, targets, s);

  const float h = 1e-3f;
  float largest = 0.0f;
  for (int j = 0; j < f.n; ++j) {
    const int parent = f.skeleton->joints[static_cast<size_t>(j)].parent;
    const glm::quat parent_world = parent >= 0 ? s.rotations[static_cast<size_t>(parent)] : glm::quat(1, 0, 0, 0);
    for (int axis = 0; axis < 3; ++axis) {
      glm::vec3 e(0.0f);
      e[axis] = 1.0f;
      double cost[2];
      for (int sign = 0; sign < 2; ++sign) {
        Pose q = pose;
        const glm::quat world_turn = glm::angleAxis(sign == 0 ? h : -h, e);
        q.rotations[static_cast<size_t>(j)] = glm::inverse(parent_world) * world_turn * parent_world * pose.rotations[static_cast<size_t>(j)];
        cost[sign] = balance_cost(f.model, params, targets, centroids_of(f, q).data()).total;
      }
      const double fd = (cost[0] - cost[1]) / (2.0 * h);
      const double analytic = s.joint_gradient[static_cast<size_t>(j)][axis];
      largest = std::max(largest, static_cast<float>(std::abs(analytic)));
      CHECK(analytic == doctest::Approx(fd).epsilon(0.02).scale(1.0));
    }
  }
  CHECK(largest > 0.05f);  // the check above compared real, non-zero derivatives
}

// A posture whose COM is well ahead of the feet: the trunk leaned forward, both arms out in front.
Pose leaning_pose(const Fixture& f) {
  Pose pose(f.n);
  pose.root_position = {0.0f, 0.95f, 0.0f};
  pose.rotations[static_cast<size_t>(f.skeleton->find("abdomen"))] = glm::angleAxis(0.35f, glm::vec3(1, 0, 0));
  for (const char* s : {"lShldr", "rShldr"}) pose.rotations[static_cast<size_t>(f.skeleton->find(s))] = glm::angleAxis(s[0] == 'l' ? -1.4f : 1.4f, glm::vec3(0, 1, 0));
  return pose;
}

float largest_shift(const std::vector<glm::vec3>& a, const std::vector<glm::vec3>& b) {
  float largest = 0.0f;
  for (size_t i = 0; i < a.size(); ++i) largest = std::max(largest, glm::length(a[i] - b[i]));
  return largest;
}

TEST_CASE("the cost at the style targets themselves is the cost of the same centroids held elsewhere, to the bit") {
  // balance_cost takes Eq. 7's terms at the targets (all distances zero) as one number; it must be the
  // number the terms would each give, whatever the other terms and the history.
  Fixture f;
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> smoothing(1e-4f, 0.1f);
  for (int round = 0; round < 50; ++round) {
    BalanceParams params;
    params.norm_smoothing = smoothing(rng);
    const std::vector<glm::vec3> style = centroids_of(f, random_pose(f.n, rng, 0.6f));
    const std::vector<glm::vec3> copy = style;
    const std::vector<glm::vec3> previous = centroids_of(f, random_pose(f.n, rng, 0.6f));
    const std::vector<glm::vec3> before_previous = centroids_of(f, random_pose(f.n, rng, 0.6f));
    BalanceTargets targets;
    targets.support_centre = {0.02f * static_cast<float>(round % 5), -0.03f};
    targets.style = style.data();
    if (round % 2) {
      targets.previous = previous.data();
      targets.before_previous = before_previous.data();
    }
    const BalanceCost at_targets = balance_cost(f.model, params, targets, style.data());
    const BalanceCost held_elsewhere = balance_cost(f.model, params, targets, copy.data());
    CHECK(std::memcmp(&at_targets.style, &held_elsewhere.style, sizeof(float)) == 0);
    CHECK(std::memcmp(&at_targets.total, &held_elsewhere.total, sizeof(float)) == 0);
  }
}

TEST_CASE("the optimizer lowers the cost, brings the COM toward the support centre and moves only the upper body") {
  Fixture f;
  BalanceParams params;
  params.max_part_shift = 0.0f;  // no trust region: the descent alone (the bounds have their own test)
  params.max_shift_speed = 0.0f;
  Pose pose = leaning_pose(f);
  const std::vector<glm::vec3> style = centroids_of(f, pose);
  BalanceTargets targets;
  targets.support_centre = {0.0f, 0.05f};  // between the feet
  targets.style = style.data();
  BalanceScratch s;
  s.resize(f.n, f.parts);
  const Pose before = pose;
  const BalanceResult result = optimize_balance(*f.skeleton, f.model, params, targets, pose, s);
  CHECK(result.optimized);
  CHECK(result.steps >= 1);
  CHECK(result.steps <= params.max_steps);
  CHECK(result.after.total < result.before.total);
  CHECK(result.after.com_distance < 0.7f * result.before.com_distance);
  // The reported cost is the cost of the posture returned, each taken at its posture's COM: the start's
  // exactly as model_center_of_mass gives it (the synthesizer reports it as the blended posture's COM).
  const BalanceCost returned = balance_cost(f.model, params, targets, centroids_of(f, pose).data());
  CHECK(returned.total == doctest::Approx(result.after.total).epsilon(1e-4));
  CHECK(glm::length(returned.com - result.after.com) < 1e-6f);
  const glm::vec3 start_com = model_center_of_mass(f.model, style.data());
  CHECK((result.before.com.x == start_com.x && result.before.com.y == start_com.y && result.before.com.z == start_com.z));
  CHECK(glm::length(result.after.com - start_com) > 0.01f);
  for (int j = 0; j < f.n; ++j) {
    if (!f.body.upper_body[static_cast<size_t>(j)]) CHECK(pose.rotations[static_cast<size_t>(j)] == before.rotations[static_cast<size_t>(j)]);
  }
  // Fewer steps allowed: stops earlier, never worse than the start.
  params.max_steps = 1;
  Pose one = before;
  const BalanceResult short_run = optimize_balance(*f.skeleton, f.model, params, targets, one, s);
  CHECK(short_run.steps <= 1);
  CHECK(short_run.after.com_distance <= short_run.before.com_distance);
}

TEST_CASE("with a history, the reported cost is the cost of the posture returned, Eq. 8-9 included") {
  // The optimizer keeps the terms of the parts it never moves aside (style and smoothness) and adds those
  // of the parts it moves: its reported cost must be what balance_cost gives for the posture it returns.
  Fixture f;
  BalanceParams params;
  params.max_part_shift = 0.0f;
  params.max_shift_speed = 0.0f;
  Pose pose = leaning_pose(f);
  const std::vector<glm::vec3> style = centroids_of(f, pose);
  // Two earlier frames: the body drifting 2 cm and then 3 cm forward, with some parts further, so that
  // every part's acceleration (and smoothness term) is its own.
  std::vector<glm::vec3> previous = style, before_previous = style;
  for (size_t i = 0; i < style.size(); ++i) {
    const float k = static_cast<float>(i);
    previous[i] -= glm::vec3(0.001f * k, 0.0f, 0.03f);
    before_previous[i] -= glm::vec3(0.0f, 0.002f * k, 0.05f);
  }
  BalanceTargets targets;
  targets.support_centre = {0.0f, 0.05f};
  targets.style = style.data();
  targets.previous = previous.data();
  targets.before_previous = before_previous.data();
  BalanceScratch s;
  s.resize(f.n, f.parts);
  const BalanceResult result = optimize_balance(*f.skeleton, f.model, params, targets, pose, s);
  REQUIRE(result.steps >= 1);
  const BalanceCost before = balance_cost(f.model, params, targets, style.data());
  CHECK(result.before.smooth == before.smooth);
  CHECK(before.smooth > 0.01f);
  const BalanceCost returned = balance_cost(f.model, params, targets, centroids_of(f, pose).data());
  CHECK(returned.smooth == doctest::Approx(result.after.smooth).epsilon(1e-4));
  CHECK(returned.style == doctest::Approx(result.after.style).epsilon(1e-4));
  CHECK(returned.total == doctest::Approx(result.after.total).epsilon(1e-4));
}

TEST_CASE("the trust region bounds how far and how fast the optimizer moves the body parts") {
  Fixture f;
  BalanceParams params;  // defaults: max_part_shift 6 cm, max_shift_speed 0.3 m/s
  Pose pose = leaning_pose(f);
  const std::vector<glm::vec3> style = centroids_of(f, pose);
  BalanceTargets targets;
  targets.support_centre = {0.0f, 0.05f};
  targets.style = style.data();
  // The support centre 12 cm behind the COM: further than any slight correction can bring it.
  const glm::vec3 com = model_center_of_mass(f.model, style.data());
  targets.support_centre = {com.x, com.z - 0.12f};
  BalanceScratch s;
  s.resize(f.n, f.parts);
  // Without a frame rate bound the size bound holds and is reached: the optimizer goes as far as it may.
  params.max_shift_speed = 0.0f;
  Pose a = pose;
  const BalanceResult bounded = optimize_balance(*f.skeleton, f.model, params, targets, a, s);
  CHECK(bounded.before.com_distance == doctest::Approx(0.12f).epsilon(1e-3));
  CHECK(bounded.after.com_distance < bounded.before.com_distance - 0.01f);
  const float shift = largest_shift(centroids_of(f, a), style);
  CHECK(shift <= params.max_part_shift + 1e-5f);
  CHECK(shift > 0.8f * params.max_part_shift);
  CHECK(bounded.largest_shift == doctest::Approx(shift).epsilon(1e-3));
  CHECK(bounded.after.total < bounded.before.total);
  // The rate bound: in one frame of 1/30 s no centroid moves more than max_shift_speed / 30.
  params.max_shift_speed = 0.3f;
  Pose b = pose;
  optimize_balance(*f.skeleton, f.model, params, targets, b, s, nullptr, 1.0f / 30.0f);
  const float step = largest_shift(centroids_of(f, b), style);
  CHECK(step <= 0.3f / 30.0f + 1e-5f);
  CHECK(step > 0.5f * 0.3f / 30.0f);
}

TEST_CASE("warm start: each frame continues from the previous correction, and drops it when it would hurt") {
  Fixture f;
  BalanceParams params;
  Pose pose = leaning_pose(f);
  const std::vector<glm::vec3> style = centroids_of(f, pose);
  BalanceTargets targets;
  targets.support_centre = {0.0f, 0.05f};
  targets.style = style.data();
  BalanceScratch s;
  s.resize(f.n, f.parts);
  BalanceCorrection memory;
  const float dt = 1.0f / 30.0f;
  // The same blended posture frame after frame: the correction changes by at most max_shift_speed * dt a
  // frame, and since each frame starts where the last one ended, the cost never rises.
  std::vector<glm::vec3> last = style;
  float last_cost = 1e9f;
  for (int frame = 0; frame < 12; ++frame) {
    Pose p = pose;
    const BalanceResult r = optimize_balance(*f.skeleton, f.model, params, targets, p, s, &memory, dt);
    CHECK(r.warm_started == (frame > 0));
    const std::vector<glm::vec3> now = centroids_of(f, p);
    CHECK(largest_shift(now, last) <= params.max_shift_speed * dt + 1e-4f);
    CHECK(largest_shift(now, style) <= params.max_part_shift + 1e-5f);
    CHECK(r.after.total <= last_cost + 1e-6f);
    CHECK(r.after.com_distance <= r.before.com_distance);
    last = now;
    last_cost = r.after.total;
  }
  // Twelve frames went further than one frame may.
  CHECK(largest_shift(last, style) > 2.0f * params.max_shift_speed * dt);
  CHECK(memory.valid);
  // The support moves far ahead of the body: keeping the correction (which pulled the COM back toward the
  // old centre) would take the COM further from the new centre than the blended posture has it, so the
  // descent starts afresh.
  targets.support_centre = {0.0f, 0.6f};
  Pose p = pose;
  const BalanceResult r = optimize_balance(*f.skeleton, f.model, params, targets, p, s, &memory, dt);
  CHECK_FALSE(r.warm_started);
  CHECK(r.after.com_distance <= r.before.com_distance);
  CHECK(largest_shift(centroids_of(f, p), style) <= params.max_shift_speed * dt + 1e-5f);
}

TEST_CASE("the optimizer gradient equals the full gradient at the optimized joints, and joints that move no mass are left out") {
  // The rig with fingers below each hand: the hand segment ends at the middle finger's first joint, so
  // turning a finger joint moves no point of the mass table.
  const auto skeleton = test::make_test_skeleton(true);
  const BodyMap body = BodyMap::detect(*skeleton);
  const MassModel mass = MassModel::build(*skeleton, body);
  const BalanceModel model = BalanceModel::build(*skeleton, body, mass);
  for (const char* finger : {"lMid1", "lMid2", "rMid1", "rMid2"}) {
    const int j = skeleton->find(finger);
    REQUIRE(j >= 0);
    CHECK(body.upper_body[static_cast<size_t>(j)]);
    CHECK(std::find(model.optimized.begin(), model.optimized.end(), j) == model.optimized.end());
  }
  CHECK(std::find(model.optimized.begin(), model.optimized.end(), skeleton->find("lHand")) != model.optimized.end());

  std::mt19937 rng(17);
  const int n = skeleton->size(), parts = static_cast<int>(model.parts.size());
  const auto centroids = [&](const Pose& p) {
    std::vector<glm::vec3> wp, c(static_cast<size_t>(parts));
    std::vector<glm::quat> wr;
    forward_kinematics(*skeleton, p, wp, &wr);
    part_centroids(*skeleton, model, wp, wr, c.data());
    return c;
  };
  const Pose pose = random_pose(n, rng, 0.5f);
  const std::vector<glm::vec3> style = centroids(random_pose(n, rng, 0.5f));
  const std::vector<glm::vec3> prev = centroids(random_pose(n, rng, 0.5f)), prev2 = centroids(random_pose(n, rng, 0.5f));
  BalanceParams params;
  BalanceTargets targets;
  targets.support_centre = {0.2f, -0.1f};
  targets.style = style.data();
  targets.previous = prev.data();
  targets.before_previous = prev2.data();
  BalanceScratch full, fast;
  for (BalanceScratch* s : {&full, &fast}) {
    s->resize(n, parts);
    forward_kinematics(*skeleton, pose, s->positions, &s->rotations);
    part_centroids(*skeleton, model, s->positions, s->rotations, s->centroids.data());
  }
  balance_gradient(*skeleton, model, params, targets, full);
  optimized_balance_gradient(*skeleton, model, params, targets, fast);
  for (int j = 0; j < n; ++j) {
    const glm::vec3 g = full.joint_gradient[static_cast<size_t>(j)];
    const bool optimized = std::find(model.optimized.begin(), model.optimized.end(), j) != model.optimized.end();
    if (optimized) {
      CHECK(glm::length(fast.joint_gradient[static_cast<size_t>(j)] - g) < 1e-5f * std::max(1.0f, glm::length(g)));
    } else if (body.upper_body[static_cast<size_t>(j)]) {
      CHECK(glm::length(g) < 1e-6f);  // a left-out upper-body joint: its gradient is zero
    }
  }
  CHECK(glm::length(com_response(model, fast) - com_response(model, full)) < 1e-5f);
}

TEST_CASE("support polygon into an existing polygon: the same hull, storage reused") {
  FootPoints feet;
  feet.heel = {glm::vec3(0.1f, 0.08f, 0.0f), glm::vec3(-0.1f, 0.08f, 0.3f)};
  feet.toe = {glm::vec3(0.12f, 0.0f, 0.2f), glm::vec3(-0.08f, 0.0f, 0.5f)};
  const ContactParams params;
  SupportPolygon reused;
  reused.hull.reserve(16);
  const glm::vec2* storage = reused.hull.data();
  for (const FrameContacts contacts : {FrameContacts{FootContact{true, true}, FootContact{true, false}},
                                       FrameContacts{FootContact{false, true}, FootContact{false, false}},
                                       FrameContacts{FootContact{false, false}, FootContact{false, false}},
                                       FrameContacts{FootContact{true, true}, FootContact{true, true}}}) {
    const SupportPolygon made = support_polygon(feet, contacts, params);
    support_polygon(feet, contacts, params, reused);
    CHECK(reused.hull == made.hull);
    CHECK(reused.hull.data() == storage);
  }
  CHECK(reused.hull.size() >= 6);  // the last: both whole soles
}

}  // namespace prep
