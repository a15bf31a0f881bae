#include "engine/motion/contacts.h"

#include <doctest/doctest.h>

#include <string>
#include <vector>

#include "engine/motion/bvh.h"
#include "engine/motion/kinematics.h"
#include "tests/motion/hand_skeleton.h"
#include "tests/support/paths.h"

using namespace prep;

namespace {

enum class Support { None, Left, Right, Both };

Support support_of(const FrameContacts& c) {
  if (c[kLeft].any() && c[kRight].any()) return Support::Both;
  if (c[kLeft].any()) return Support::Left;
  if (c[kRight].any()) return Support::Right;
  return Support::None;
}

struct Gait {
  float left = 0, right = 0;     // fraction of frames each foot is in contact
  int alternations = 0;          // single-support phases followed by one on the other foot
  int repeats = 0;               // single-support phases followed by another on the same foot
  int switches_without_double = 0;  // left-only straight to right-only (or back) with no double support
};

// Single-support phases shorter than `min_frames` are ignored (a toe brushing the floor for one frame).
Gait gait_of(const std::vector<FrameContacts>& contacts, int min_frames) {
  Gait g;
  for (const FrameContacts& c : contacts) {
    g.left += c[kLeft].any();
    g.right += c[kRight].any();
  }
  g.left /= static_cast<float>(contacts.size());
  g.right /= static_cast<float>(contacts.size());
  Support last_single = Support::None;
  bool double_since = false;
  for (size_t f = 0; f < contacts.size();) {
    const Support s = support_of(contacts[f]);
    size_t end = f;
    while (end < contacts.size() && support_of(contacts[end]) == s) ++end;
    if (s == Support::Both) double_since = true;
    if ((s == Support::Left || s == Support::Right) && static_cast<int>(end - f) >= min_frames) {
      if (last_single != Support::None) {
        if (s == last_single) ++g.repeats;
        else ++g.alternations;
        if (s != last_single && !double_since) ++g.switches_without_double;
      }
      last_single = s;
      double_since = false;
    }
    f = end;
  }
  return g;
}

std::vector<FrameContacts> contacts_of(const std::string& folder, const std::string& file, const ContactParams& p) {
  BvhReadOptions options;
  options.unit_scale = folder == "cmu31" ? 0.05644f : 0.01f;
  Clip clip = read_bvh(test::mocap() + "/" + folder + "/" + file, options);
  if (folder == "daz43") clip.frames.erase(clip.frames.begin(), clip.frames.begin() + 5);  // reference pose and the converter's ramp
  return detect_contacts(clip, BodyMap::detect(*clip.skeleton), p);
}

}  // namespace

TEST_CASE("contacts: CMU walks alternate single and double support, each foot down >= 40% of frames") {
  const ContactParams p;
  struct Walk {
    const char* folder;
    const char* file;
  };
  const Walk walks[] = {{"cmu31", "walk_69_01.bvh"},      {"daz43", "walk_02_01.bvh"},      {"daz43", "walk_07_01.bvh"},
                        {"daz43", "walk_10_04.bvh"},      {"daz43", "walk_slow_12_02.bvh"}, {"daz43", "walk_08_01.bvh"},
                        {"daz43", "walk_slow_07_04.bvh"}, {"cmu31", "turn_left_69_27.bvh"}};
  for (const Walk& w : walks) {
    CAPTURE(w.file);
    const auto contacts = contacts_of(w.folder, w.file, p);
    const bool daz = std::string(w.folder) == "daz43";
    const Gait g = gait_of(contacts, daz ? 6 : 2);  // 50-67 ms
    CHECK(g.left >= 0.4f);
    CHECK(g.right >= 0.4f);
    CHECK(g.left <= 0.8f);   // a walking foot swings for a third of the cycle or more
    CHECK(g.right <= 0.8f);
    CHECK(g.alternations >= 3);  // the clips hold two gait cycles or more
    CHECK(g.repeats == 0);
    CHECK(g.switches_without_double == 0);
  }
}

TEST_CASE("contacts: the running clip has flight phases and less contact than walking") {
  const auto contacts = contacts_of("daz43", "run_09_01.bvh", ContactParams());
  int flight = 0;
  for (const FrameContacts& c : contacts) flight += support_of(c) == Support::None;
  CHECK(flight > static_cast<int>(contacts.size()) / 4);
  const Gait g = gait_of(contacts, 6);
  CHECK(g.left < 0.4f);
  CHECK(g.right < 0.4f);
}

namespace {

// Moves the whole rest skeleton: both feet follow the root. Rest pose: ankles 0.08 m up, toe tips on y = 0.
Clip moving_clip(const std::vector<glm::vec3>& root_offsets, float fps) {
  auto sk = test::t_pose_skeleton();
  Clip clip = test::still_clip(sk, static_cast<int>(root_offsets.size()), fps);
  for (size_t f = 0; f < root_offsets.size(); ++f) clip.frames[f].root_position += root_offsets[f];
  return clip;
}

// Appends `n` frames going linearly from the last offset to `to`.
void ramp(std::vector<glm::vec3>& path, glm::vec3 to, int n) {
  const glm::vec3 from = path.empty() ? glm::vec3(0.0f) : path.back();
  for (int i = 1; i <= n; ++i) path.push_back(from + (to - from) * (static_cast<float>(i) / static_cast<float>(n)));
}

}  // namespace

TEST_CASE("contacts: height hysteresis at the thresholds") {
  ContactParams p;
  const float between = 0.5f * (p.height_on + p.height_off);  // above "on", below "off"
  const float above = p.height_off + 0.04f;
  const float below = 0.5f * p.height_on;
  // Standing on the floor at both ends of a 3 s clip at 30 fps (so the planted height is the floor),
  // moving slowly (under 0.5 m/s) so that speed never decides.
  std::vector<glm::vec3> path(25, glm::vec3(0.0f));
  ramp(path, {0, between, 0}, 10);   // 25..34: lifted to between the thresholds
  ramp(path, {0, between, 0}, 10);   // 35..44: held there: still in contact (never went above height_off)
  ramp(path, {0, above, 0}, 5);      // 45..49
  ramp(path, {0, above, 0}, 5);      // 50..54: above height_off: released
  ramp(path, {0, between, 0}, 5);    // 55..59
  ramp(path, {0, between, 0}, 5);    // 60..64: back between the thresholds: still released
  ramp(path, {0, below, 0}, 5);      // 65..69
  ramp(path, {0, 0, 0}, 20);         // 70..89: down again
  const Clip clip = moving_clip(path, 30.0f);
  const BodyMap body = BodyMap::detect(*clip.skeleton);
  const auto contacts = detect_contacts(clip, body, p);
  REQUIRE(contacts.size() == 90);
  for (int side : {kLeft, kRight}) {
    for (int f : {0, 10, 24, 36, 40, 44}) {
      CAPTURE(f);
      CHECK(contacts[static_cast<size_t>(f)][static_cast<size_t>(side)].heel);
      CHECK(contacts[static_cast<size_t>(f)][static_cast<size_t>(side)].toe);
    }
    for (int f : {50, 54, 60, 62, 64}) {
      CAPTURE(f);
      CHECK_FALSE(contacts[static_cast<size_t>(f)][static_cast<size_t>(side)].any());
    }
    for (int f : {69, 75, 89}) {
      CAPTURE(f);
      CHECK(contacts[static_cast<size_t>(f)][static_cast<size_t>(side)].heel);
      CHECK(contacts[static_cast<size_t>(f)][static_cast<size_t>(side)].toe);
    }
  }
}

TEST_CASE("contacts: speed hysteresis at the thresholds") {
  ContactParams p;
  const float fps = 30.0f;
  const float between = 0.5f * (p.speed_on + p.speed_off) / fps;  // metres per frame
  const float fast = (p.speed_off + 0.3f) / fps;
  // Sliding on the floor: still, then between the speed thresholds (stays in contact), then faster than
  // speed_off (released), then between again (stays released).
  std::vector<glm::vec3> path(20, glm::vec3(0.0f));
  for (int i = 0; i < 20; ++i) path.push_back(path.back() + glm::vec3(0, 0, between));
  for (int i = 0; i < 10; ++i) path.push_back(path.back() + glm::vec3(0, 0, fast));
  for (int i = 0; i < 15; ++i) path.push_back(path.back() + glm::vec3(0, 0, between));
  const Clip clip = moving_clip(path, fps);
  const auto contacts = detect_contacts(clip, BodyMap::detect(*clip.skeleton), p);
  for (int f : {5, 25, 35}) {
    CAPTURE(f);
    CHECK(contacts[static_cast<size_t>(f)][kLeft].heel);
    CHECK(contacts[static_cast<size_t>(f)][kRight].toe);
  }
  for (int f : {44, 48, 55, 62}) {
    CAPTURE(f);
    CHECK_FALSE(contacts[static_cast<size_t>(f)][kLeft].any());
    CHECK_FALSE(contacts[static_cast<size_t>(f)][kRight].any());
  }
  // Starting at that in-between speed never enters contact.
  std::vector<glm::vec3> sliding(1, glm::vec3(0.0f));
  for (int i = 0; i < 40; ++i) sliding.push_back(sliding.back() + glm::vec3(between, 0, 0));
  const Clip slide = moving_clip(sliding, fps);
  for (const FrameContacts& c : detect_contacts(slide, BodyMap::detect(*slide.skeleton), p)) {
    CHECK_FALSE(c[kLeft].any());
    CHECK_FALSE(c[kRight].any());
  }
}

TEST_CASE("contacts: a heel raised on a planted toe (short clip: rest-pose planted heights)") {
  auto sk = test::t_pose_skeleton();
  Clip clip = test::still_clip(sk, 5, 30.0f);  // 5 frames: too short to read planted heights from the clip
  // Rotate both feet about the ankle so that the heel lifts: pitch the ankle down by 35 degrees.
  const BodyMap body = BodyMap::detect(*sk);
  for (Pose& pose : clip.frames)
    for (const LegChain& leg : body.legs)
      pose.rotations[static_cast<size_t>(leg.ankle)] = glm::angleAxis(glm::radians(35.0f), glm::vec3(1, 0, 0));
  // Lower the body so that the toe tips are back on the floor.
  std::vector<glm::vec3> pos;
  std::vector<glm::quat> rot;
  forward_kinematics(*sk, clip.frames[0], pos, &rot);
  const FootPoints feet = foot_points(*sk, body, pos, rot);
  for (Pose& pose : clip.frames) pose.root_position.y -= feet.toe[kLeft].y;
  forward_kinematics(*sk, clip.frames[0], pos, &rot);
  const FootPoints lowered = foot_points(*sk, body, pos, rot);
  CHECK(lowered.toe[kLeft].y == doctest::Approx(0.0f).epsilon(1e-5));
  const float ankle_rest = 0.08f;  // hand_skeleton.h: ankle above the toe tip in the rest pose
  REQUIRE(lowered.heel[kLeft].y - ankle_rest > ContactParams().height_on);
  const auto contacts = detect_contacts(clip, body, ContactParams());
  for (const FrameContacts& c : contacts) {
    CHECK(c[kLeft].toe);
    CHECK_FALSE(c[kLeft].heel);
    CHECK(c[kRight].toe);
    CHECK_FALSE(c[kRight].heel);
  }
}

TEST_CASE("contacts: foot points are the ankle and the toe tip") {
  auto sk = test::t_pose_skeleton();
  const BodyMap body = BodyMap::detect(*sk);
  Pose pose(sk->size());
  pose.root_position = {1.0f, 0.95f, 2.0f};
  std::vector<glm::vec3> pos;
  std::vector<glm::quat> rot;
  forward_kinematics(*sk, pose, pos, &rot);
  const FootPoints feet = foot_points(*sk, body, pos, rot);
  // Left ankle: hips (1, .95, 2) + (.10, -.05, 0) + (0, -.42, 0) + (0, -.40, 0); toe tip (0, -.08, .18) ahead.
  CHECK(feet.heel[kLeft].x == doctest::Approx(1.10f));
  CHECK(feet.heel[kLeft].y == doctest::Approx(0.08f));
  CHECK(feet.heel[kLeft].z == doctest::Approx(2.0f));
  CHECK(feet.toe[kLeft].x == doctest::Approx(1.10f));
  CHECK(feet.toe[kLeft].y == doctest::Approx(0.0f).epsilon(1e-5));
  CHECK(feet.toe[kLeft].z == doctest::Approx(2.18f));
  CHECK(feet.heel[kRight].x == doctest::Approx(0.90f));
}
