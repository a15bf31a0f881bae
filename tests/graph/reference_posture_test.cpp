#include "engine/graph/reference_posture.h"

#include <doctest/doctest.h>

#include <cmath>
#include <map>
#include <string>

#include "engine/library/builtin.h"
#include "engine/motion/kinematics.h"
#include "tests/graph/builtin_set.h"
#include "tests/support/paths.h"

using namespace prep;

namespace {

using test::builtin;

struct World {
  std::vector<glm::vec3> p;
  std::vector<glm::quat> r;
};

World world(const MotionSet& set, const MotionClip& mc, int frame) {
  World w;
  forward_kinematics(*set.skeleton, mc.clip.frames[static_cast<size_t>(frame)], w.p, &w.r);
  return w;
}

bool both_feet_down(const MotionClip& mc, int f) {
  return mc.contacts[static_cast<size_t>(f)][kLeft].any() && mc.contacts[static_cast<size_t>(f)][kRight].any();
}

// How far the left ankle is ahead of the right along the character's facing (m).
float left_ahead(const MotionSet& set, const MotionClip& mc, int f) {
  const std::vector<glm::vec3> legs = leg_positions(set, mc.clip.frames[static_cast<size_t>(f)]);
  return legs[2].z - legs[6].z;  // [2] left ankle, [6] right ankle (hip, knee, ankle, toe per leg)
}

float lowest_root(const MotionClip& mc) {
  float low = INFINITY;
  for (const Pose& p : mc.clip.frames) low = std::min(low, p.root_position.y);
  return low;
}

// Independent check of the three conditions at frame f (Sec. 4.2).
bool all_conditions(const MotionSet& set, const MotionClip& mc, int f, const Params& params) {
  return same_feet_down(mc.contacts[static_cast<size_t>(f)], mc.contacts[0]) &&
         legs_distance(leg_positions(set, mc.clip.frames[static_cast<size_t>(f)]), leg_positions(set, mc.clip.frames[0])) <
             params.reference.legs_threshold &&
         com_in_support(set, mc, f, params.contacts);
}

void check_scan(const MotionSet& set, const ReferencePosture& r, const Params& params) {
  const MotionClip& mc = set.clips[static_cast<size_t>(r.clip)];
  CAPTURE(mc.clip.name);
  CHECK(r.t_t == mc.target_frame);
  CHECK(r.frame <= r.t_t);
  if (r.found) {
    CHECK(r.com_in_support);
    CHECK(r.same_contacts);
    CHECK(r.legs_close);
    CHECK(all_conditions(set, mc, r.frame, params));
  } else {
    CHECK(r.frame == 0);  // T_0
  }
  // The scan runs from T_t toward T_0: no later frame qualifies.
  for (int f = r.frame + 1; f <= r.t_t; ++f) {
    CAPTURE(f);
    CHECK_FALSE(all_conditions(set, mc, f, params));
  }
}

}  // namespace

TEST_CASE("reference posture: every built-in target's T_p is its set-up posture") {
  const MotionSet& set = builtin();
  const Params params;
  const auto postures = find_reference_postures(set, params);
  int targets = 0;
  for (const MotionClip& mc : set.clips) targets += is_locomotion(mc.role) ? 0 : 1;
  CHECK(static_cast<int>(postures.size()) == targets);
  for (const ReferencePosture& r : postures) {
    const MotionClip& mc = set.clips[static_cast<size_t>(r.clip)];
    CAPTURE(mc.clip.name);
    check_scan(set, r, params);
    REQUIRE(r.found);
    const int f = r.frame;
    const float fps = mc.clip.fps;
    const World w = world(set, mc, f);
    const BodyMap& b = set.body;
    CHECK(both_feet_down(mc, f));
    switch (mc.role) {
      case Role::Jump:
        // The gathered stance before the counter-movement crouch (T_t): feet side by side, not yet low.
        CHECK(f >= r.t_t - static_cast<int>(0.25f * fps));
        CHECK(std::abs(left_ahead(set, mc, f)) < 0.1f);
        CHECK(w.p[0].y > lowest_root(mc) + 0.15f);
        break;
      case Role::Crawl:
        // Standing with the feet together just before the descent onto hands and knees.
        CHECK(f >= r.t_t - static_cast<int>(0.25f * fps));
        CHECK(std::abs(left_ahead(set, mc, f)) < 0.1f);
        CHECK(w.p[0].y > lowest_root(mc) + 0.3f);
        break;
      case Role::Duck:
        // The last double support of the approach before the dip: the pelvis is still at walking height.
        CHECK(f >= r.t_t - static_cast<int>(0.25f * fps));
        CHECK(w.p[0].y > 0.95f * mc.clip.frames[0].root_position.y);
        CHECK(w.p[0].y > lowest_root(mc) + 0.1f);
        break;
      case Role::PunchLeft:
      case Role::PunchRight:
        // The boxing guard: fists raised well above the elbows, toward the chin; left foot forward.
        for (const ArmChain& arm : b.arms) {
          CHECK(w.p[static_cast<size_t>(arm.wrist)].y > w.p[static_cast<size_t>(arm.elbow)].y + 0.1f);
          CHECK(w.p[static_cast<size_t>(arm.wrist)].y > w.p[static_cast<size_t>(arm.shoulder)].y - 0.2f);
        }
        CHECK(left_ahead(set, mc, f) > 0.2f);
        CHECK(f >= r.t_t - static_cast<int>(0.5f * fps));
        break;
      case Role::Kick:
        // The plant: the supporting left foot set ahead of the kicking right one, just before the swing.
        CHECK(left_ahead(set, mc, f) > 0.3f);
        CHECK(f >= r.t_t - static_cast<int>(0.1f * fps));
        break;
      default:
        FAIL("unexpected target role");
    }
  }
  // The paper's Fig. 11: both punches share their preparation posture.
  int left = -1, right = -1;
  for (const ReferencePosture& r : postures) {
    if (set.clips[static_cast<size_t>(r.clip)].role == Role::PunchLeft) left = r.frame;
    if (set.clips[static_cast<size_t>(r.clip)].role == Role::PunchRight) right = r.frame;
  }
  CHECK(left == right);
}

TEST_CASE("reference posture: a tight legs threshold falls back toward the walk-in (or T_0)") {
  const MotionSet& set = builtin();
  Params params;
  params.reference.legs_threshold = 1e-6f;
  for (const ReferencePosture& r : find_reference_postures(set, params)) {
    check_scan(set, r, params);
    if (!r.found) CHECK(r.frame == 0);
  }
}

TEST_CASE("reference posture: CMU targets satisfy the conditions or fall back to T_0") {
  for (const char* name : {"cmu31", "daz43"}) {
    CAPTURE(name);
    const Params params;
    const MotionSet set = load_motion_set(test::repo() + "/assets/manifests/" + name + ".json", params);
    for (const ReferencePosture& r : find_reference_postures(set, params)) check_scan(set, r, params);
  }
  // daz43's standing broad jumps: T_p at the start of the countermovement (README: crouch starts at T_t).
  const Params params;
  const MotionSet daz = load_motion_set(test::repo() + "/assets/manifests/daz43.json", params);
  for (const char* jump : {"jump_forward_13_11", "jump_forward_13_13", "jump_forward_13_32", "jump_up_02_04"}) {
    CAPTURE(jump);
    const ReferencePosture r = find_reference_posture(daz, daz.find(jump), params);
    CHECK(r.found);
    CHECK(r.frame >= r.t_t - static_cast<int>(0.1f * daz.clips[static_cast<size_t>(r.clip)].clip.fps));
  }
}
