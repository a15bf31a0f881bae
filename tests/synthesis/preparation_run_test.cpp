#include "engine/synthesis/preparation_run.h"

#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "engine/library/builtin.h"
#include "engine/motion/kinematics.h"
#include "engine/motion/motion_set.h"

namespace prep {
namespace {

struct RunSummary {
  int balance_frames = 0;       // alpha >= the optimizer's threshold and some foot in contact
  int inside_before = 0, inside_after = 0;
  int double_frames = 0, double_inside_after = 0;
  int distance_increased = 0;
  float max_slide = 0.0f;       // m per frame, planted heel or toe points
  float max_shift = 0.0f;       // m, the optimizer's largest move of a body-part centroid
  double distance_before = 0.0, distance_after = 0.0;  // sums over balance frames
};

RunSummary summarize(const PreparationRun& run, const Params& params) {
  RunSummary s;
  for (size_t i = 0; i < run.frames.size(); ++i) {
    const SynthesisReport& r = run.reports[i];
    if (i > 0) s.max_slide = std::max(s.max_slide, run.foot_slide[i]);
    if (r.alpha < params.balance.alpha_threshold || !r.has_support) continue;
    ++s.balance_frames;
    s.inside_before += r.com_inside_before;
    s.inside_after += r.com_inside_after;
    if (run.contacts[i][kLeft].any() && run.contacts[i][kRight].any()) {
      ++s.double_frames;
      s.double_inside_after += r.com_inside_after;
    }
    s.distance_increased += r.com_distance_after > r.com_distance_before;
    s.max_shift = std::max(s.max_shift, r.balance_shift);
    s.distance_before += r.com_distance_before;
    s.distance_after += r.com_distance_after;
  }
  return s;
}

// Walk -> every target motion of the set, alpha ramping 0 -> 1 over 3 s (the synthesis acceptance run).
//
// What is asserted, for every target of the built-in library and both CMU manifests:
//  - a heel or toe the foot IK holds moves at most 2 mm per frame (the criterion, met: 1.2 mm built-in,
//    under 1 mm on daz43 at 120 fps, under 0.1 mm on cmu31);
//  - the COM's distance to the support centre never increases through the optimization, on any frame;
//  - no body part is moved more than balance.max_part_shift by the optimizer (the trust region, balance.h);
//  - the optimizer lowers the mean COM distance and never lowers the fraction of frames inside.
//
// What is NOT met, and why (measured on these runs; the test prints the figures): the aim is that the
// COM lie inside the support polygon on at least 95% of the frames with alpha >= 0.3. After optimization
// it is 31-35% on the built-in library, 16-27% on daz43's jumps and kicks (6% with kick_10_03) and 0-69%
// on cmu31. The frames that fail are single support (66% of the built-in runs' frames, 76% daz43's, 69%
// cmu31's), where the COM passes 5-40 cm from the stance foot's centre: the blended motion is still a
// walk, and a walk's COM passes over the stance foot only briefly (the locomotion clips themselves have it
// inside the polygon on 35% of their frames built-in, 44% daz43 walk_02_01, 66% cmu31 walk_69_01). In
// double support it is inside on 86-100% built-in, 67-95% daz43 (26% kick_10_03), 0-100% cmu31. Moving
// the COM 5-40 cm with the upper body alone takes a 30-60 degree lean: with the trust region off the
// optimizer reaches 64-74% on the built-in library (38-100% daz43, 56-100% cmu31), the trunk bending up to
// 62-65 degrees built-in and swinging from one foot to the other at every step (a drunk), which is worse
// than the blend (the test after these measures walk -> duck). Two more findings:
// at high alpha the legs are nearly T_p's while the contacts stay the walk's (the paper keeps them, Sec.
// 5.2), so the body stands on both feet while one is labelled "swing" (counting a foot within 5 cm of the
// floor as support would add 17-41% of the frames, still short of 95%); and cmu31's duck and punches and
// daz43's kick_10_03 have no statically balanced frame before T_t (`prep info --json`, condition
// com_in_support), so T_p falls back to T_0; the duck's is a running pose whose COM is 10-40 cm ahead of
// the feet.
void check_library(const MotionSet& set, const Params& params) {
  const int walk = find_cyclic_clip(set, Role::Walk);
  REQUIRE(walk >= 0);
  int targets = 0;
  for (const MotionClip& target : set.clips) {
    if (target.target_frame < 0) continue;
    ++targets;
    CAPTURE(set.name);
    CAPTURE(target.clip.name);
    PreparationRunOptions options;
    options.locomotion_clip = walk;
    options.reference = target.clip.frames[static_cast<size_t>(scan_reference_frame(set, target, params))];
    options.alpha_start = 0.0f;
    options.alpha_end = 1.0f;
    options.seconds = 3.0f;
    const PreparationRun run = run_preparation(set, params, options);
    REQUIRE(run.frames.size() == static_cast<size_t>(std::lround(3.0f * run.fps)) + 1);
    const RunSummary s = summarize(run, params);
    REQUIRE(s.balance_frames > static_cast<int>(run.frames.size()) / 2);
    CHECK(s.max_slide <= 0.002f);
    CHECK(s.distance_increased == 0);
    CHECK(s.max_shift <= params.balance.max_part_shift + 1e-4f);
    CHECK(s.distance_after < s.distance_before);
    CHECK(s.inside_after >= s.inside_before);
    std::printf("%-7s %-20s slide %.2f mm  COM inside %5.1f%% -> %5.1f%% (double support %5.1f%%)  mean distance %.3f -> %.3f m\n",
                set.name.c_str(), target.clip.name.c_str(), 1000.0f * s.max_slide,
                100.0 * s.inside_before / s.balance_frames, 100.0 * s.inside_after / s.balance_frames,
                s.double_frames ? 100.0 * s.double_inside_after / s.double_frames : 0.0,
                s.distance_before / s.balance_frames, s.distance_after / s.balance_frames);
  }
  CHECK(targets >= 2);
}

}  // namespace

TEST_CASE("walk -> every target, alpha 0 -> 1 over 3 s: the built-in library") {
  const Params params;
  check_library(make_builtin_motion_set(params), params);
}

TEST_CASE("walk -> every target, alpha 0 -> 1 over 3 s: the daz43 and cmu31 CMU manifests") {
  const Params params;
  for (const char* manifest : {"/assets/manifests/daz43.json", "/assets/manifests/cmu31.json"}) {
    check_library(load_motion_set(std::string(PREP_SOURCE_DIR) + manifest, params), params);
  }
}

namespace {

// The largest trunk lean (degrees) the optimizer adds over the frames it runs on: the angle between the
// pelvis -> neck direction of `balanced` and of `blended` (the same run with the optimizer off; the legs and
// root are the same in both, the optimizer moves only the upper body).
float largest_added_lean(const MotionSet& set, const PreparationRun& blended, const PreparationRun& balanced,
                         float alpha_threshold) {
  std::vector<glm::vec3> a, b;
  float largest = 0.0f;
  for (size_t i = 0; i < blended.frames.size(); ++i) {
    if (balanced.reports[i].alpha < alpha_threshold) continue;
    forward_kinematics(*set.skeleton, blended.frames[i], a);
    forward_kinematics(*set.skeleton, balanced.frames[i], b);
    const size_t neck = static_cast<size_t>(set.body.neck), root = static_cast<size_t>(set.body.root);
    const glm::vec3 u = glm::normalize(a[neck] - a[root]), v = glm::normalize(b[neck] - b[root]);
    largest = std::max(largest, std::acos(std::clamp(glm::dot(u, v), -1.0f, 1.0f)) * 57.29578f);
  }
  return largest;
}

float fraction_inside(const PreparationRun& run, const Params& params) {
  const RunSummary s = summarize(run, params);
  return static_cast<float>(s.inside_after) / static_cast<float>(s.balance_frames);
}

}  // namespace

// Why the optimizer has a trust region (balance.h), and why the 95% of the acceptance run is out of its
// reach: with the region the added trunk lean stays slight; without it Eq. 6-10 bend the trunk by tens of
// degrees at every step, fling the arms half a metre, and still leave the COM outside the stance foot on a
// quarter of the prepared frames (single support of a walk).
TEST_CASE("balance optimizer: the trust region keeps the lean slight, without it the trunk bends and the COM is still outside") {
  const Params params;
  const MotionSet set = make_builtin_motion_set(params);
  const MotionClip* duck = nullptr;
  for (const MotionClip& c : set.clips) {
    if (c.role == Role::Duck) duck = &c;
  }
  REQUIRE(duck != nullptr);
  PreparationRunOptions options;
  options.locomotion_clip = find_cyclic_clip(set, Role::Walk);
  options.reference = duck->clip.frames[static_cast<size_t>(scan_reference_frame(set, *duck, params))];
  Params off = params;
  off.balance.enabled = false;
  Params unbounded = params;
  unbounded.balance.max_part_shift = 0.0f;  // <= 0 removes each bound
  unbounded.balance.max_shift_speed = 0.0f;
  const PreparationRun blended = run_preparation(set, off, options);
  const PreparationRun ours = run_preparation(set, params, options);
  const PreparationRun free_run = run_preparation(set, unbounded, options);
  const float lean_ours = largest_added_lean(set, blended, ours, params.balance.alpha_threshold);
  const float lean_free = largest_added_lean(set, blended, free_run, params.balance.alpha_threshold);
  const RunSummary free_summary = summarize(free_run, params);
  std::printf("walk -> duck: added trunk lean %.1f deg with the trust region (COM inside %.0f%%), %.1f deg without "
              "(COM inside %.0f%%, a body part moved %.2f m)\n",
              lean_ours, 100.0f * fraction_inside(ours, params), lean_free, 100.0f * fraction_inside(free_run, params),
              free_summary.max_shift);
  CHECK(lean_ours <= 8.0f);
  CHECK(lean_free >= 30.0f);
  CHECK(free_summary.max_shift >= 0.3f);
  CHECK(fraction_inside(free_run, params) > fraction_inside(ours, params));  // it does buy balance ...
  CHECK(fraction_inside(free_run, params) < 0.95f);                          // ... but not the 95%
}

TEST_CASE("foot IK over a long walk: the pelvis drop does not grow from cycle to cycle, swinging feet stay above the floor") {
  // A foot that swung down with the lowered pelvis landed that much too low, and the next stance asked for
  // a deeper drop: on cmu31's walk the pelvis sank from 6 to 14 cm over 8 s.
  const Params params;
  for (const std::string manifest : {"/assets/manifests/cmu31.json", "/assets/manifests/daz43.json"}) {
    CAPTURE(manifest);
    const MotionSet set = load_motion_set(PREP_SOURCE_DIR + manifest, params);
    for (const Role role : {Role::Walk, Role::TurnRight}) {
      const std::string locomotion = role_name(role);
      CAPTURE(locomotion);
      PreparationRunOptions options;
      options.locomotion_clip = find_cyclic_clip(set, role);
      REQUIRE(options.locomotion_clip >= 0);
      options.reference = set.clips[static_cast<size_t>(options.locomotion_clip)].clip.frames.front();
      options.alpha_start = options.alpha_end = 0.0f;  // no blending: Eq. 5 leaves the root height alone
      options.seconds = 8.0f;
      const PreparationRun run = run_preparation(set, params, options);
      const size_t n = run.frames.size(), eighth = n / 8;
      float first = 0.0f, last = 0.0f;
      std::array<int, 2> free_frames{0, 0};
      const int faded = static_cast<int>(std::ceil(params.ik.release_s * run.fps));  // lift-off correction gone
      for (size_t f = 0; f < n; ++f) {
        const float drop = run.locomotion[f].root_position.y - run.frames[f].root_position.y;
        if (f < 2 * eighth) first = std::max(first, drop);
        if (f >= n - 2 * eighth) last = std::max(last, drop);
        // A swinging foot (free, its lift-off correction faded) is as high as the locomotion has it, not
        // carried down with the pelvis.
        std::vector<glm::vec3> out, loco;
        forward_kinematics(*set.skeleton, run.frames[f], out);
        forward_kinematics(*set.skeleton, run.locomotion[f], loco);
        for (size_t side = 0; side < 2; ++side) {
          free_frames[side] = run.reports[f].pinned[side].any() ? 0 : free_frames[side] + 1;
          if (free_frames[side] <= faded) continue;
          const size_t ankle = static_cast<size_t>(set.body.legs[side].ankle);
          CHECK(std::abs(out[ankle].y - loco[ankle].y) <= 0.002f);
        }
      }
      MESSAGE("pelvis drop: " << 100.0f * first << " cm in the first quarter, " << 100.0f * last << " cm in the last");
      CHECK(last <= first + 0.005f);
    }
  }
}

TEST_CASE("the locomotion loop continues across its wrap without a jump") {
  const Params params;
  const MotionSet set = make_builtin_motion_set(params);
  const MotionClip& walk = set.clips[static_cast<size_t>(find_cyclic_clip(set, Role::Walk))];
  LocomotionLoop loop(walk);
  Pose previous, pose;
  FrameContacts contacts{};
  loop.next(previous, contacts);
  float largest_step = 0.0f, median_step = 0.0f;
  const int cycle = walk.loop_last - walk.loop_first + 1;
  std::vector<float> steps;
  for (int f = 1; f < 3 * cycle; ++f) {
    loop.next(pose, contacts);
    const glm::vec3 d = pose.root_position - previous.root_position;
    steps.push_back(std::sqrt(d.x * d.x + d.z * d.z));
    previous = pose;
  }
  std::vector<float> sorted = steps;
  std::sort(sorted.begin(), sorted.end());
  median_step = sorted[sorted.size() / 2];
  for (float s : steps) largest_step = std::max(largest_step, s);
  CHECK(median_step > 0.01f);                // it walks
  CHECK(largest_step < 2.0f * median_step);  // and never jumps, at the wraps either
}

}  // namespace prep
