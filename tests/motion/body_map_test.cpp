#include "engine/motion/body_map.h"

#include <doctest/doctest.h>

#include <stdexcept>
#include <string>

#include "engine/motion/bvh.h"
#include "tests/motion/hand_skeleton.h"
#include "tests/support/paths.h"

using namespace prep;

namespace {

std::string name_of(const Skeleton& sk, int j) { return j < 0 ? "(none)" : sk.joints[static_cast<size_t>(j)].name; }

bool upper(const Skeleton& sk, const BodyMap& b, const std::string& joint) {
  const int j = sk.find(joint);
  REQUIRE(j >= 0);
  CHECK(b.upper_body[static_cast<size_t>(j)] != b.lower_body[static_cast<size_t>(j)]);
  return b.upper_body[static_cast<size_t>(j)];
}

void check_builtin_names(const Skeleton& sk, const std::string& p) {
  const BodyMap b = BodyMap::detect(sk);
  CHECK(b.root == 0);
  REQUIRE(b.spine.size() == 3);
  CHECK(name_of(sk, b.spine[0]) == p + "Spine");
  CHECK(name_of(sk, b.spine[2]) == p + "Spine2");
  CHECK(name_of(sk, b.neck) == p + "Neck");
  CHECK(name_of(sk, b.head) == p + "Head");
  const char* sides[2] = {"Left", "Right"};
  for (int s = 0; s < 2; ++s) {
    const std::string side = p + sides[s];
    const LegChain& leg = b.legs[static_cast<size_t>(s)];
    CHECK(name_of(sk, leg.hip) == side + "UpLeg");
    CHECK(name_of(sk, leg.knee) == side + "Leg");
    CHECK(name_of(sk, leg.ankle) == side + "Foot");
    CHECK(name_of(sk, leg.toe) == side + "ToeBase");
    CHECK(name_of(sk, leg.toe_tip_joint) == side + "ToeBase");
    const ArmChain& arm = b.arms[static_cast<size_t>(s)];
    // Mixamo's "Shoulder" is the clavicle; "Arm" is the upper arm.
    CHECK(name_of(sk, arm.collar) == side + "Shoulder");
    CHECK(name_of(sk, arm.shoulder) == side + "Arm");
    CHECK(name_of(sk, arm.elbow) == side + "ForeArm");
    CHECK(name_of(sk, arm.wrist) == side + "Hand");
  }
  CHECK_FALSE(upper(sk, b, p + "Hips"));
  CHECK_FALSE(upper(sk, b, p + "LeftUpLeg"));
  CHECK_FALSE(upper(sk, b, p + "RightToeBase"));
  CHECK(upper(sk, b, p + "Spine"));
  CHECK(upper(sk, b, p + "Head"));
  CHECK(upper(sk, b, p + "LeftHand"));
  CHECK(upper(sk, b, p + "RightShoulder"));
}

Clip load(const std::string& folder, const std::string& file) {
  BvhReadOptions options;
  options.unit_scale = folder == "cmu31" ? 0.05644f : 0.01f;
  return read_bvh(test::mocap() + "/" + folder + "/" + file, options);
}

}  // namespace

TEST_CASE("body map: our built-in naming, with and without Mixamo's prefix") {
  check_builtin_names(*test::t_pose_skeleton(), "");
  check_builtin_names(*test::t_pose_skeleton("mixamorig:"), "mixamorig:");
}

TEST_CASE("body map: daz43 (no toe joint: the toe tip is the foot's End Site)") {
  const Clip clip = load("daz43", "walk_02_01.bvh");
  const Skeleton& sk = *clip.skeleton;
  const BodyMap b = BodyMap::detect(sk);
  CHECK(name_of(sk, b.root) == "hip");
  REQUIRE(b.spine.size() == 2);
  CHECK(name_of(sk, b.spine[0]) == "abdomen");
  CHECK(name_of(sk, b.spine[1]) == "chest");
  CHECK(name_of(sk, b.neck) == "neck");
  CHECK(name_of(sk, b.head) == "head");
  const char* p[2] = {"l", "r"};
  for (int s = 0; s < 2; ++s) {
    const std::string side = p[s];
    const LegChain& leg = b.legs[static_cast<size_t>(s)];
    CHECK(name_of(sk, leg.hip) == side + "Thigh");
    CHECK(name_of(sk, leg.knee) == side + "Shin");
    CHECK(name_of(sk, leg.ankle) == side + "Foot");
    CHECK(leg.toe == -1);
    CHECK(leg.toe_tip_joint == leg.ankle);
    const ArmChain& arm = b.arms[static_cast<size_t>(s)];
    CHECK(name_of(sk, arm.collar) == side + "Collar");
    CHECK(name_of(sk, arm.shoulder) == side + "Shldr");
    CHECK(name_of(sk, arm.elbow) == side + "ForeArm");
    CHECK(name_of(sk, arm.wrist) == side + "Hand");
    CHECK_FALSE(upper(sk, b, side + "Buttock"));  // hip helper bone: lower body
    CHECK(upper(sk, b, side + "Index2"));         // fingers: upper body
  }
  CHECK_FALSE(upper(sk, b, "hip"));
  CHECK(upper(sk, b, "leftEye"));
  CHECK(upper(sk, b, "abdomen"));
  // The left leg is on +X in daz43.
  CHECK(sk.joints[static_cast<size_t>(b.legs[kLeft].hip)].offset.x >= 0.0f);
}

TEST_CASE("body map: cmu31 (ankle, toe, wrist and a palm bone - lowerback is not a left joint)") {
  const Clip clip = load("cmu31", "walk_69_01.bvh");
  const Skeleton& sk = *clip.skeleton;
  const BodyMap b = BodyMap::detect(sk);
  CHECK(name_of(sk, b.root) == "Hips");
  REQUIRE(b.spine.size() == 3);
  CHECK(name_of(sk, b.spine[0]) == "lowerback");
  CHECK(name_of(sk, b.spine[1]) == "Chest");
  CHECK(name_of(sk, b.spine[2]) == "Chest2");
  CHECK(name_of(sk, b.neck) == "lowerneck");
  CHECK(name_of(sk, b.head) == "Head");
  const char* p[2] = {"Left", "Right"};
  const char* q[2] = {"L", "R"};
  for (int s = 0; s < 2; ++s) {
    const std::string side = p[s];
    const LegChain& leg = b.legs[static_cast<size_t>(s)];
    CHECK(name_of(sk, leg.hip) == side + "Hip");
    CHECK(name_of(sk, leg.knee) == side + "Knee");
    CHECK(name_of(sk, leg.ankle) == side + "Ankle");
    CHECK(name_of(sk, leg.toe) == side + "Toe");
    CHECK(leg.toe_tip_joint == leg.toe);
    const ArmChain& arm = b.arms[static_cast<size_t>(s)];
    CHECK(name_of(sk, arm.collar) == side + "Collar");
    CHECK(name_of(sk, arm.shoulder) == side + "Shoulder");
    CHECK(name_of(sk, arm.elbow) == side + "Elbow");
    CHECK(name_of(sk, arm.wrist) == side + "Wrist");
    CHECK_FALSE(upper(sk, b, std::string(q[s]) + "HipJoint"));
    CHECK(upper(sk, b, std::string(q[s]) + "Fingers"));
  }
  CHECK_FALSE(upper(sk, b, "Hips"));
  CHECK(upper(sk, b, "lowerback"));
  CHECK(upper(sk, b, "lhand"));
}

TEST_CASE("body map: a skeleton without a right foot is refused, naming what is missing") {
  auto sk = test::t_pose_skeleton();
  sk->joints[static_cast<size_t>(sk->find("RightFoot"))].name = "RightPaw";
  try {
    BodyMap::detect(*sk);
    FAIL("detect accepted a skeleton without a right foot");
  } catch (const std::invalid_argument& e) {
    CHECK(std::string(e.what()).find("right foot") != std::string::npos);
  }
}
