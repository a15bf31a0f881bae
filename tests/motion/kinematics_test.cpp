#include <doctest/doctest.h>

#include <glm/gtc/constants.hpp>
#include <glm/gtc/quaternion.hpp>

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
