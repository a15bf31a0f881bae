#include "engine/synthesis/balance.h"

#include <doctest/doctest.h>

#include <cmath>
#include <random>

#include "engine/motion/kinematics.h"
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

TEST_CASE("the optimizer lowers the cost, brings the COM toward the support centre and moves only the upper body") {
  Fixture f;
  std::mt19937 rng(5);
  BalanceParams params;
  Pose pose(f.n);
  pose.root_position = {0.0f, 0.95f, 0.0f};
  // Lean the trunk forward and put both arms out in front: the COM moves ahead of the feet.
  pose.rotations[static_cast<size_t>(f.skeleton->find("abdomen"))] = glm::angleAxis(0.35f, glm::vec3(1, 0, 0));
  for (const char* s : {"lShldr", "rShldr"}) pose.rotations[static_cast<size_t>(f.skeleton->find(s))] = glm::angleAxis(s[0] == 'l' ? -1.4f : 1.4f, glm::vec3(0, 1, 0));
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

}  // namespace prep
