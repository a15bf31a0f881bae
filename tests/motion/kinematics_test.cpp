#include <doctest/doctest.h>

#include <glm/gtc/constants.hpp>
#include <glm/gtc/quaternion.hpp>
#include <algorithm>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "engine/motion/kinematics.h"

using namespace prep;

namespace {
// root -> spine -> arm, arm with an End Site.
Skeleton three_joint_chain() {
  Skeleton s;
  s.joints.push_back({"root", -1, {0, 0, 0}, false, {}});
  s.joints.push_back({"spine", 0, {0, 1, 0}, false, {}});
  s.joints.push_back({"arm", 1, {0, 0, 2}, true, {0, 1, 0}});
  return s;
}
// root -> pelvis -> {left hip -> knee -> ankle, right hip -> knee -> ankle}, spine -> head.
Skeleton legs_and_spine() {
  Skeleton s;
  s.joints.push_back({"root", -1, {0, 0, 0}, false, {}});
  s.joints.push_back({"pelvis", 0, {0, 0.1f, 0}, false, {}});
  s.joints.push_back({"l_hip", 1, {0.1f, -0.05f, 0}, false, {}});
  s.joints.push_back({"l_knee", 2, {0, -0.42f, 0}, false, {}});
  s.joints.push_back({"l_ankle", 3, {0, -0.43f, 0}, false, {}});
  s.joints.push_back({"r_hip", 1, {-0.1f, -0.05f, 0}, false, {}});
  s.joints.push_back({"r_knee", 5, {0, -0.42f, 0}, false, {}});
  s.joints.push_back({"r_ankle", 6, {0, -0.43f, 0}, false, {}});
  s.joints.push_back({"spine", 1, {0, 0.2f, 0}, false, {}});
  s.joints.push_back({"head", 8, {0, 0.5f, 0}, false, {}});
  return s;
}
void check_near(glm::vec3 a, glm::vec3 b) {
  CHECK(a.x == doctest::Approx(b.x).epsilon(1e-6));
  CHECK(a.y == doctest::Approx(b.y).epsilon(1e-6));
  CHECK(a.z == doctest::Approx(b.z).epsilon(1e-6));
}
}  // namespace

TEST_CASE("forward kinematics of a hand-made pose gives the hand-computed joint positions") {
  const Skeleton s = three_joint_chain();
  Pose pose(3);
  pose.root_position = {1, 2, 3};
  const float quarter = glm::half_pi<float>();
  pose.rotations[0] = glm::angleAxis(quarter, glm::vec3(0, 1, 0));  // root: 90 deg about +Y
  pose.rotations[1] = glm::angleAxis(quarter, glm::vec3(0, 0, 1));  // spine: 90 deg about +Z
  std::vector<glm::vec3> p;
  std::vector<glm::quat> r;
  forward_kinematics(s, pose, p, &r);
  REQUIRE(p.size() == 3);
  // By hand: Ry(90) maps (x, y, z) -> (z, y, -x); Rz(90) maps (x, y, z) -> (-y, x, z).
  // spine = root + Ry(90)·(0,1,0) = (1,2,3) + (0,1,0)
  check_near(p[0], {1, 2, 3});
  check_near(p[1], {1, 3, 3});
  // arm = spine + Ry(90)·Rz(90)·(0,0,2) = spine + Ry(90)·(0,0,2) = spine + (2,0,0)
  check_near(p[2], {3, 3, 3});
  // arm's End Site = arm + Ry(90)·Rz(90)·(0,1,0) = arm + Ry(90)·(-1,0,0) = arm + (0,0,1)
  check_near(end_site_position(s, 2, p, r), {3, 3, 4});
  // World rotations compose parent-first.
  const glm::quat expected = pose.rotations[0] * pose.rotations[1];
  CHECK(std::abs(glm::dot(r[2], expected)) == doctest::Approx(1.0).epsilon(1e-6));
}

TEST_CASE("forward kinematics at the rest pose sums the offsets") {
  const Skeleton s = three_joint_chain();
  Pose pose(3);
  std::vector<glm::vec3> p;
  forward_kinematics(s, pose, p);
  check_near(p[2], {0, 1, 2});
}

TEST_CASE("forward kinematics: the SSE2 joint composition agrees with glm's scalar one on random chains") {
  // A chain of 43 joints, random offsets (up to 0.5 m) and rotations, composed by place_joint (what every
  // forward kinematics pass uses) and by glm's quaternion arithmetic: the same pose to a micrometre.
  std::mt19937 rng(23);
  std::normal_distribution<float> n(0.0f, 1.0f);
  std::uniform_real_distribution<float> length(0.0f, 0.5f);
  double worst_position = 0.0, worst_rotation = 0.0;
  for (int trial = 0; trial < 200; ++trial) {
    glm::vec3 position(n(rng), n(rng), n(rng)), reference_position = position;
    glm::quat rotation = glm::normalize(glm::quat(n(rng), n(rng), n(rng), n(rng))), reference_rotation = rotation;
    for (int joint = 0; joint < 43; ++joint) {
      const glm::vec3 offset = length(rng) * glm::normalize(glm::vec3(n(rng), n(rng), n(rng)));
      const glm::quat local = glm::normalize(glm::quat(n(rng), n(rng), n(rng), n(rng)));
      glm::vec3 next_position;
      glm::quat next_rotation;
      place_joint(position, rotation, offset, local, next_position, next_rotation);
      const glm::vec3 scalar_position = reference_position + reference_rotation * offset;
      const glm::quat scalar_rotation = reference_rotation * local;
      // Both chains continue from the scalar path's joint, so that the error measured is one joint's.
      worst_position = std::max(worst_position, static_cast<double>(glm::length(next_position - scalar_position)));
      worst_rotation = std::max(worst_rotation, static_cast<double>(glm::length(glm::vec4(next_rotation.x - scalar_rotation.x,
          next_rotation.y - scalar_rotation.y, next_rotation.z - scalar_rotation.z, next_rotation.w - scalar_rotation.w))));
      position = reference_position = scalar_position;
      rotation = reference_rotation = scalar_rotation;
    }
  }
  CHECK(worst_position < 1e-6);   // one joint: float rounding of a 0.5 m offset
  CHECK(worst_rotation < 1e-6);
}

TEST_CASE("forward kinematics: a whole 43-joint body through place_joint stays within 1e-5 m of glm's scalar pass") {
  std::mt19937 rng(29);
  std::normal_distribution<float> n(0.0f, 1.0f);
  std::uniform_real_distribution<float> length(0.02f, 0.45f);
  Skeleton s;
  for (int j = 0; j < 43; ++j) {
    Joint joint;
    joint.name = "j" + std::to_string(j);
    joint.parent = j == 0 ? -1 : static_cast<int>(rng() % static_cast<unsigned>(j));  // a random tree
    joint.offset = length(rng) * glm::normalize(glm::vec3(n(rng), n(rng), n(rng)));
    s.joints.push_back(joint);
  }
  Pose pose(43);
  pose.root_position = {0.3f, 0.95f, -1.2f};
  for (glm::quat& q : pose.rotations) q = glm::normalize(glm::quat(n(rng), n(rng), n(rng), n(rng)));
  std::vector<glm::vec3> positions;
  std::vector<glm::quat> rotations;
  forward_kinematics(s, pose, positions, &rotations);
  std::vector<glm::vec3> scalar(43);
  std::vector<glm::quat> scalar_rotations(43);
  scalar[0] = pose.root_position;
  scalar_rotations[0] = pose.rotations[0];
  for (size_t j = 1; j < 43; ++j) {
    const size_t p = static_cast<size_t>(s.joints[j].parent);
    scalar[j] = scalar[p] + scalar_rotations[p] * s.joints[j].offset;
    scalar_rotations[j] = scalar_rotations[p] * pose.rotations[j];
  }
  for (size_t j = 0; j < 43; ++j) CHECK(glm::length(positions[j] - scalar[j]) < 1e-5f);
}

TEST_CASE("breadth_first: level by level, parents first, and a pass in that order gives forward kinematics to the bit") {
  const Skeleton s = legs_and_spine();
  const std::vector<int> all = breadth_first(s, {0, 1, 2, 3, 4, 5, 6, 7, 8, 9});
  CHECK(all == std::vector<int>{0, 1, 2, 5, 8, 3, 6, 9, 4, 7});
  CHECK(breadth_first(s, {7, 3, 6, 4}) == std::vector<int>{3, 6, 4, 7});  // a subset keeps to its levels

  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  Pose pose(s.size());
  pose.root_position = {0.3f, 0.9f, -0.2f};
  std::vector<glm::vec3> expected, positions(static_cast<size_t>(s.size()));
  std::vector<glm::quat> expected_rotations, rotations(static_cast<size_t>(s.size()));
  for (int k = 0; k < 100; ++k) {
    for (glm::quat& q : pose.rotations) q = glm::normalize(glm::quat(u(rng), u(rng), u(rng), u(rng)));
    forward_kinematics(s, pose, expected, &expected_rotations);
    for (int j : all) {
      const size_t i = static_cast<size_t>(j);
      const int parent = s.joints[i].parent;
      if (parent < 0) {
        positions[i] = pose.root_position;
        rotations[i] = pose.rotations[i];
      } else {
        const size_t p = static_cast<size_t>(parent);
        place_joint(positions[p], rotations[p], s.joints[i].offset, pose.rotations[i], positions[i], rotations[i]);
      }
    }
    REQUIRE(std::memcmp(positions.data(), expected.data(), sizeof(glm::vec3) * positions.size()) == 0);
    REQUIRE(std::memcmp(rotations.data(), expected_rotations.data(), sizeof(glm::quat) * rotations.size()) == 0);
  }
}

TEST_CASE("a joint pass gives forward kinematics to the bit at the joints it lists and touches no other") {
  const Skeleton s = legs_and_spine();
  const JointPass whole(s, breadth_first(s, {0, 1, 2, 3, 4, 5, 6, 7, 8, 9}));
  const JointPass legs(s, breadth_first(s, {0, 1, 2, 3, 4, 5, 6, 7}));
  const JointPass below_knees(s, {4, 7});  // the knees' kinematics already in place

  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  Pose a(s.size()), b(s.size());
  const size_t n = static_cast<size_t>(s.size());
  const glm::vec3 untouched(7.0f, 7.0f, 7.0f);
  std::vector<glm::vec3> expected_a, expected_b;
  std::vector<glm::quat> expected_rotations_a, expected_rotations_b;
  for (int k = 0; k < 50; ++k) {
    for (Pose* pose : {&a, &b}) {
      pose->root_position = {u(rng), 1.0f + 0.1f * u(rng), u(rng)};
      for (glm::quat& q : pose->rotations) q = glm::normalize(glm::quat(u(rng), u(rng), u(rng), u(rng)));
    }
    forward_kinematics(s, a, expected_a, &expected_rotations_a);
    forward_kinematics(s, b, expected_b, &expected_rotations_b);
    std::vector<glm::vec3> positions(n, untouched), positions_b(n, untouched);
    std::vector<glm::quat> rotations(n), rotations_b(n);
    whole.run(a, positions, rotations);
    REQUIRE(std::memcmp(positions.data(), expected_a.data(), sizeof(glm::vec3) * n) == 0);
    REQUIRE(std::memcmp(rotations.data(), expected_rotations_a.data(), sizeof(glm::quat) * n) == 0);

    positions.assign(n, untouched);
    legs.run_two(a, positions, rotations, b, positions_b, rotations_b);
    for (size_t j = 0; j < n; ++j) {
      CAPTURE(j);
      if (j < 8) {
        REQUIRE(positions[j] == expected_a[j]);
        REQUIRE(rotations[j] == expected_rotations_a[j]);
        REQUIRE(positions_b[j] == expected_b[j]);
        REQUIRE(rotations_b[j] == expected_rotations_b[j]);
      } else {
        REQUIRE(positions[j] == untouched);
        REQUIRE(positions_b[j] == untouched);
      }
    }
    // The ankles again from the knees left by the pass of the legs: no root listed, none placed.
    positions[0] = untouched;
    positions[4] = positions[7] = untouched;
    below_knees.run(a, positions, rotations);
    REQUIRE(positions[0] == untouched);
    REQUIRE(positions[4] == expected_a[4]);
    REQUIRE(positions[7] == expected_a[7]);
  }
}

TEST_CASE("an End Site's position: the joint's plus its offset turned, glm's arithmetic to the bit") {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  const Skeleton s = three_joint_chain();
  Pose pose(s.size());
  std::vector<glm::vec3> positions;
  std::vector<glm::quat> rotations;
  for (int k = 0; k < 200; ++k) {
    pose.root_position = {u(rng), 1.0f + u(rng), u(rng)};
    for (glm::quat& q : pose.rotations) q = glm::normalize(glm::quat(u(rng), u(rng), u(rng), u(rng)));
    forward_kinematics(s, pose, positions, &rotations);
    // glm's vector rotation, v + 2 (w (q x v) + q x (q x v)), then the sum: each lane as SSE2 computes it.
    const glm::vec3 expected = positions[2] + rotations[2] * s.joints[2].end_site;
    const glm::vec3 got = end_site_position(s, 2, positions, rotations);
    REQUIRE(std::memcmp(&got, &expected, sizeof got) == 0);
  }
}
