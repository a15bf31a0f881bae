#include "engine/motion/center_of_mass.h"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "engine/library/builtin.h"
#include "engine/motion/bvh.h"
#include "engine/motion/motion_set.h"
#include "engine/motion/contacts.h"
#include "engine/motion/kinematics.h"
#include "engine/motion/support_polygon.h"
#include "tests/motion/hand_skeleton.h"
#include "tests/support/paths.h"

using namespace prep;

namespace {

glm::vec3 com_of(const Skeleton& sk, const MassModel& model, const Pose& pose) {
  std::vector<glm::vec3> pos, centroids;
  std::vector<glm::quat> rot;
  forward_kinematics(sk, pose, pos, &rot);
  segment_centroids(sk, model, pos, rot, centroids);
  return center_of_mass(model, centroids);
}

float mass_sum(const MassModel& model) {
  float sum = 0;
  for (const BodySegment& s : model.segments) sum += s.mass_fraction;
  return sum;
}

const BodySegment* segment(const MassModel& model, const std::string& name) {
  for (const BodySegment& s : model.segments)
    if (s.name == name) return &s;
  return nullptr;
}

}  // namespace

TEST_CASE("centre of mass: a symmetric T-pose has its COM on the midline at ~56% of stature") {
  auto sk = test::t_pose_skeleton();
  const BodyMap body = BodyMap::detect(*sk);
  const MassModel model = MassModel::build(*sk, body);
  CHECK(mass_sum(model) == doctest::Approx(1.0f).epsilon(1e-6));
  // Spine, Spine1, Spine2 sit at 10/52, 25/52, 40/52 of the trunk: navel and xiphoid found, trunk split.
  REQUIRE(segment(model, "lower_trunk") != nullptr);
  CHECK(segment(model, "trunk") == nullptr);
  CHECK(model.segments.size() == 3 + 1 + 2 * 6);
  Pose pose(sk->size());
  pose.root_position = {0, 0.95f, 0};
  const glm::vec3 com = com_of(*sk, model, pose);
  CHECK(std::abs(com.x) < 1e-5f);
  // The rest pose stands on y = 0 and the vertex is 1.75 m up. Adult males' COM lies at 55-57% of
  // stature (de Leva's own data give ~0.56); the T-pose raises it slightly (arms at shoulder height).
  const float stature = 1.75f;
  CHECK(com.y / stature > 0.53f);
  CHECK(com.y / stature < 0.60f);
  // The feet stick forward (+Z) a little: the COM is slightly in front of the ankles, never behind.
  CHECK(com.z > 0.0f);
  CHECK(com.z < 0.02f);
}

TEST_CASE("centre of mass: moves rigidly with the body, and an arm raised forward moves it forward") {
  auto sk = test::t_pose_skeleton();
  const MassModel model = MassModel::build(*sk, BodyMap::detect(*sk));
  Pose pose(sk->size());
  pose.root_position = {0, 0.95f, 0};
  const glm::vec3 rest = com_of(*sk, model, pose);
  Pose moved = pose;
  moved.root_position += glm::vec3(1.0f, 0.0f, -2.0f);
  const glm::quat yaw = glm::angleAxis(0.7f, glm::vec3(0, 1, 0));
  moved.rotations[0] = yaw;
  const glm::vec3 expect = moved.root_position + yaw * (rest - pose.root_position);
  const glm::vec3 got = com_of(*sk, model, moved);
  CHECK(got.x == doctest::Approx(expect.x).epsilon(1e-5));
  CHECK(got.y == doctest::Approx(expect.y).epsilon(1e-5));
  CHECK(got.z == doctest::Approx(expect.z).epsilon(1e-5));
  // Swing the left arm (shoulder joint = "LeftArm") from sideways to straight forward.
  Pose reach = pose;
  reach.rotations[static_cast<size_t>(sk->find("LeftArm"))] = glm::angleAxis(glm::radians(-90.0f), glm::vec3(0, 1, 0));
  const glm::vec3 forward = com_of(*sk, model, reach);
  // The arm (upper arm + forearm + hand = 4.94% of the mass) moves its centroid ~0.3 m: ~1.5 cm of COM.
  CHECK(forward.z - rest.z > 0.01f);
  CHECK(forward.x < rest.x);
}

namespace {

struct Frame {
  const char* folder;
  const char* file;
  int frame;
};

}  // namespace

TEST_CASE("centre of mass: standing frames of CMU clips project inside their support polygon") {
  // Quiet standing before the action (../shared/mocap/README.md): 13_11 crouches from f118, 02_04 from
  // f37, 13_13 from f67; 10_01 (the idle clip) stands still. daz43 frames 1-4 are the converter's ramp
  // from the reference pose, so the first captured standing frames are from 5 on.
  const ContactParams params;
  const Frame frames[] = {{"daz43", "jump_forward_13_11.bvh", 60}, {"daz43", "jump_up_02_04.bvh", 25},
                          {"daz43", "jump_forward_13_13.bvh", 40}, {"daz43", "jump_forward_13_32.bvh", 30},
                          {"cmu31", "punch_right_14_01.bvh", 3}};
  for (const Frame& fr : frames) {
    CAPTURE(fr.file);
    BvhReadOptions options;
    options.unit_scale = std::string(fr.folder) == "cmu31" ? 0.05644f : 0.01f;
    const Clip clip = read_bvh(test::mocap() + "/" + fr.folder + "/" + fr.file, options);
    const BodyMap body = BodyMap::detect(*clip.skeleton);
    const MassModel model = MassModel::build(*clip.skeleton, body);
    CHECK(mass_sum(model) == doctest::Approx(1.0f).epsilon(1e-6));
    const auto contacts = detect_contacts(clip, body, params);
    const FrameContacts& c = contacts[static_cast<size_t>(fr.frame)];
    CHECK(c[kLeft].any());
    CHECK(c[kRight].any());
    std::vector<glm::vec3> pos;
    std::vector<glm::quat> rot;
    forward_kinematics(*clip.skeleton, clip.frames[static_cast<size_t>(fr.frame)], pos, &rot);
    const SupportPolygon support = support_polygon(foot_points(*clip.skeleton, body, pos, rot), c, params);
    const glm::vec3 com = com_of(*clip.skeleton, model, clip.frames[static_cast<size_t>(fr.frame)]);
    CHECK(support.contains({com.x, com.z}));
    // And it is well above the feet: between the knees and the chest.
    CHECK(com.y > 0.7f);
    CHECK(com.y < 1.2f);
  }
}

TEST_CASE("centre of mass: daz43 splits the trunk at abdomen and chest, cmu31 at its spine joints") {
  for (const char* folder : {"daz43", "cmu31"}) {
    CAPTURE(folder);
    BvhReadOptions options;
    options.unit_scale = std::string(folder) == "cmu31" ? 0.05644f : 0.01f;
    const Clip clip = read_bvh(test::mocap() + "/" + folder + (std::string(folder) == "cmu31" ? "/walk_69_01.bvh" : "/walk_02_01.bvh"), options);
    const MassModel model = MassModel::build(*clip.skeleton, BodyMap::detect(*clip.skeleton));
    CHECK(mass_sum(model) == doctest::Approx(1.0f).epsilon(1e-6));
    const BodySegment* lower = segment(model, "lower_trunk");
    const BodySegment* head = segment(model, "head");
    REQUIRE(head != nullptr);
    if (std::string(folder) == "daz43") {
      REQUIRE(lower != nullptr);
      CHECK(clip.skeleton->joints[static_cast<size_t>(lower->distal)].name == "abdomen");
    }
    // Every segment's centroid in the rest pose lies between the pelvis height and the head's.
    std::vector<glm::vec3> pos, centroids;
    std::vector<glm::quat> rot;
    forward_kinematics(*clip.skeleton, Pose(clip.skeleton->size()), pos, &rot);
    segment_centroids(*clip.skeleton, model, pos, rot, centroids);
    const size_t h = static_cast<size_t>(head - model.segments.data());
    CHECK(centroids[h].y > pos[static_cast<size_t>(BodyMap::detect(*clip.skeleton).neck)].y);
  }
}

TEST_CASE("centre of mass: turning the ankles moves the feet's centroids only, and those taken alone equal a full pass") {
  const Params params;
  const MotionSet builtin = make_builtin_motion_set(params);
  const MotionSet daz43 = load_motion_set(test::repo() + "/assets/manifests/daz43.json", params);
  for (const MotionSet* set : {&builtin, &daz43}) {
    CAPTURE(set->name);
    const Skeleton& sk = *set->skeleton;
    std::vector<int> ankles;
    for (const LegChain& leg : set->body.legs) ankles.push_back(leg.ankle);
    const std::vector<int> moved = segments_moved_by_turning(sk, set->mass, ankles);
    std::vector<std::string> names;
    for (int s : moved) names.push_back(set->mass.segments[static_cast<size_t>(s)].name);
    CHECK(names == std::vector<std::string>{"left_foot", "right_foot"});

    const Pose pose = set->clips.front().clip.frames.front();
    Pose turned = pose;
    for (int a : ankles) turned.rotations[static_cast<size_t>(a)] = glm::angleAxis(0.3f, glm::vec3(1, 0, 0)) * pose.rotations[static_cast<size_t>(a)];
    std::vector<glm::vec3> pos, before, after;
    std::vector<glm::quat> rot;
    forward_kinematics(sk, pose, pos, &rot);
    segment_centroids(sk, set->mass, pos, rot, before);
    forward_kinematics(sk, turned, pos, &rot);
    segment_centroids(sk, set->mass, pos, rot, after);
    std::vector<glm::vec3> partial = before;
    segment_centroids(sk, set->mass, pos, rot, moved, partial);
    for (size_t i = 0; i < after.size(); ++i) {
      CAPTURE(set->mass.segments[i].name);
      const bool listed = std::find(moved.begin(), moved.end(), static_cast<int>(i)) != moved.end();
      CHECK((after[i] != before[i]) == listed);  // exactly the listed ones moved
      CHECK(partial[i] == after[i]);              // to the bit
    }
  }
}
