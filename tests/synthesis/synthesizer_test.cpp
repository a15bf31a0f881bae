#include "engine/synthesis/synthesizer.h"

#include <doctest/doctest.h>

#include <cmath>
#include <string>
#include <vector>

#include "engine/library/builtin.h"
#include "engine/motion/kinematics.h"
#include "engine/motion/motion_set.h"
#include "engine/synthesis/preparation_run.h"

namespace {

using namespace prep;

// Joints below an optimized joint that no body part reads: the balance optimizer's trial kinematics skip
// them, so the synthesizer must bring them up to date itself.
int joints_the_optimizer_skips(const BalanceModel& model, const Skeleton& skeleton) {
  std::vector<char> below(static_cast<size_t>(skeleton.size()), 0);
  int skipped = 0;
  for (int j = 0; j < skeleton.size(); ++j) {
    const size_t jj = static_cast<size_t>(j);
    const int parent = skeleton.joints[jj].parent;
    below[jj] = model.optimized_index[jj] >= 0 || (parent >= 0 && below[static_cast<size_t>(parent)]);
    skipped += below[jj] && !model.is_moved[jj];
  }
  return skipped;
}

// The kinematics the synthesizer left in its scratch are a fresh forward-kinematics pass of `pose`, to the bit.
void require_fresh_kinematics(const Synthesizer& synth, const SynthesisScratch& scratch, const Pose& pose, size_t frame) {
  std::vector<glm::vec3> positions;
  std::vector<glm::quat> rotations;
  forward_kinematics(synth.skeleton(), pose, positions, &rotations);
  for (size_t j = 0; j < positions.size(); ++j) {
    CAPTURE(frame);
    CAPTURE(j);
    REQUIRE(scratch.positions[j] == positions[j]);
    REQUIRE(scratch.rotations[j] == rotations[j]);
  }
}

// Walks the set's walk toward its first target's T_p at alpha 0.8 (the optimizer runs) and checks that the
// forward kinematics the synthesizer leaves in its scratch are exactly those of the pose it returns, with
// and without its own floor stage: the world reads its COM from them.
void check_kinematics_left_in_scratch(const MotionSet& set, bool keep_toes) {
  const Params params;
  const Synthesizer synth(set, params);
  int target = -1;
  for (size_t i = 0; i < set.clips.size() && target < 0; ++i) {
    if (set.clips[i].target_frame >= 0) target = static_cast<int>(i);
  }
  REQUIRE(target >= 0);
  const MotionClip& tc = set.clips[static_cast<size_t>(target)];
  const Pose reference = tc.clip.frames[static_cast<size_t>(scan_reference_frame(set, tc, params))];
  const int walk = find_cyclic_clip(set, Role::Walk);
  REQUIRE(walk >= 0);
  LocomotionLoop loop(set.clips[static_cast<size_t>(walk)]);
  SynthesisState state;
  SynthesisScratch scratch = synth.make_scratch();
  Pose locomotion, out = synth.make_pose();
  int balanced = 0;
  for (int frame = 0; frame < 90; ++frame) {
    SynthesisInput in;
    loop.next(locomotion, in.contacts);
    in.locomotion = &locomotion;
    in.reference = &reference;
    in.alpha = 0.8f;
    in.dt = 1.0f / set.clips[static_cast<size_t>(walk)].clip.fps;
    in.keep_toes_above_floor = keep_toes;
    SynthesisReport report;
    synth.step(in, state, scratch, out, &report);
    balanced += report.balanced;
    require_fresh_kinematics(synth, scratch, out, static_cast<size_t>(frame));
    // The locomotion's feet (their speeds pick the pinned points) are those of a fresh pass too.
    std::vector<glm::vec3> positions;
    std::vector<glm::quat> rotations;
    forward_kinematics(synth.skeleton(), locomotion, positions, &rotations);
    const FootPoints feet = foot_points(synth.skeleton(), synth.body(), positions, rotations);
    for (size_t side = 0; side < 2; ++side) {
      REQUIRE(state.previous_locomotion_feet.heel[side] == feet.heel[side]);
      REQUIRE(state.previous_locomotion_feet.toe[side] == feet.toe[side]);
    }
  }
  CHECK(balanced > 45);  // most frames went through the optimizer
}

}  // namespace

TEST_CASE("the synthesizer leaves the forward kinematics of the pose it returns, the balance optimizer's included") {
  const Params params;
  const MotionSet builtin = make_builtin_motion_set(params);
  const MotionSet daz43 = load_motion_set(std::string(PREP_SOURCE_DIR) + "/assets/manifests/daz43.json", params);
  // daz43 has fingers below the optimized arms: the kinematics the optimizer skips are exercised.
  CHECK(joints_the_optimizer_skips(Synthesizer(daz43, params).balance_model(), *daz43.skeleton) > 0);
  for (const MotionSet* set : {&builtin, &daz43}) {
    CAPTURE(set->name);
    check_kinematics_left_in_scratch(*set, true);
    check_kinematics_left_in_scratch(*set, false);
  }
}

TEST_CASE("the floor stage's kinematics after a toe is pitched up or the body lifted equal a fresh pass") {
  // A foot turned about its ankle needs the kinematics again from the ankle down only; a body lifted needs
  // them whole. Either way they must be those of the pose returned, to the bit.
  const Params params;
  const MotionSet set = make_builtin_motion_set(params);
  const Synthesizer synth(set, params);
  const int walk = find_cyclic_clip(set, Role::Walk);
  REQUIRE(walk >= 0);
  const Clip& clip = set.clips[static_cast<size_t>(walk)].clip;
  const int ankle = set.body.legs[0].ankle;
  SynthesisScratch scratch = synth.make_scratch();
  int pitched_only = 0, lifted = 0;
  for (size_t f = 0; f < clip.frames.size(); ++f) {
    for (float sink : {0.0f, 0.02f, 0.3f}) {  // as it is, its toes into the floor, the whole body into it
      Pose pose = clip.frames[f];
      pose.root_position.y -= sink;
      // The left foot pitched toe-down by 25 degrees about the ankle's local x.
      pose.rotations[static_cast<size_t>(ankle)] =
          glm::angleAxis(0.44f, glm::vec3(1.0f, 0.0f, 0.0f)) * pose.rotations[static_cast<size_t>(ankle)];
      const float root_before = pose.root_position.y;
      const Pose before = pose;
      synth.stage_floor(scratch, pose, false);
      bool turned = false;
      for (size_t j = 0; j < pose.rotations.size(); ++j) turned = turned || pose.rotations[j] != before.rotations[j];
      pitched_only += turned && pose.root_position.y == root_before;
      lifted += pose.root_position.y != root_before;
      require_fresh_kinematics(synth, scratch, pose, f);
    }
  }
  CHECK(pitched_only > 10);  // both ways were taken
  CHECK(lifted > 10);
}

TEST_CASE("the blend weights kept for a held alpha are taken again when the curves change") {
  // A scratch keeps Eq. 1's weights while alpha holds; new constants (the demo's panels) or another
  // synthesizer on the same scratch must not see the old ones.
  Params params;
  const MotionSet set = make_builtin_motion_set(params);
  Synthesizer synth(set, params);
  const int walk = find_cyclic_clip(set, Role::Walk);
  REQUIRE(walk >= 0);
  const Clip& clip = set.clips[static_cast<size_t>(walk)].clip;
  const Pose& reference = clip.frames.back();
  SynthesisState state;
  SynthesisScratch scratch = synth.make_scratch();
  Pose out = synth.make_pose();
  const auto step_at_half = [&](const Synthesizer& s, size_t frame) {
    SynthesisInput in;
    in.locomotion = &clip.frames[frame];
    in.reference = &reference;
    in.alpha = 0.5f;
    in.dt = 1.0f / clip.fps;
    s.step(in, state, scratch, out);
    std::vector<float> expected(static_cast<size_t>(set.skeleton->size()));
    blend_weights(s.curves(), 0.5f, expected.data());
    return scratch.weights == expected;
  };
  CHECK(step_at_half(synth, 0));
  CHECK(step_at_half(synth, 1));
  const std::vector<float> before = scratch.weights;
  params.blend.C_upper *= 3.0f;
  synth.set_params(params);
  CHECK(step_at_half(synth, 2));
  CHECK(scratch.weights != before);
  Params linear = params;
  linear.blend.method = "linear";
  const Synthesizer other(set, linear);
  CHECK(step_at_half(other, 3));
  CHECK(scratch.weights[1] == 0.5f);
}

TEST_CASE("synthesizers of two skeletons interleaved on one thread give what each gives alone") {
  // The balance optimizer's buffers belong to the thread (one per skeleton size), not to the character:
  // a frame of one body between two of another must change nothing.
  const Params params;
  const MotionSet builtin = make_builtin_motion_set(params);
  const MotionSet daz43 = load_motion_set(std::string(PREP_SOURCE_DIR) + "/assets/manifests/daz43.json", params);
  struct Run {
    const MotionSet* set;
    Synthesizer synth;
    Pose reference;
    LocomotionLoop loop;
    SynthesisState state;
    SynthesisScratch scratch;
    Pose locomotion, out;
    std::vector<Pose> frames;
    Run(const MotionSet& s, const Params& p)
        : set(&s), synth(s, p), reference(s.clips[static_cast<size_t>(find_cyclic_clip(s, Role::Walk))].clip.frames.front()),
          loop(s.clips[static_cast<size_t>(find_cyclic_clip(s, Role::Walk))]), scratch(synth.make_scratch()), out(synth.make_pose()) {
      // The reference: the walk's first frame turned at the waist, so that blending and balance have work.
      for (glm::quat& q : reference.rotations) q = glm::normalize(glm::angleAxis(0.3f, glm::vec3(1, 0, 0)) * q);
    }
    void step(int frame) {
      SynthesisInput in;
      loop.next(locomotion, in.contacts);
      in.locomotion = &locomotion;
      in.reference = &reference;
      in.alpha = 0.5f + 0.4f * std::sin(0.1f * static_cast<float>(frame));
      in.dt = 1.0f / 60.0f;
      synth.step(in, state, scratch, out);
      frames.push_back(out);
    }
  };
  Run a_alone(builtin, params), b_alone(daz43, params), a(builtin, params), b(daz43, params);
  for (int f = 0; f < 60; ++f) a_alone.step(f);
  for (int f = 0; f < 60; ++f) b_alone.step(f);
  for (int f = 0; f < 60; ++f) {
    a.step(f);
    b.step(f);
  }
  for (size_t f = 0; f < 60; ++f) {
    CAPTURE(f);
    REQUIRE(a.frames[f].rotations == a_alone.frames[f].rotations);
    REQUIRE(a.frames[f].root_position == a_alone.frames[f].root_position);
    REQUIRE(b.frames[f].rotations == b_alone.frames[f].rotations);
    REQUIRE(b.frames[f].root_position == b_alone.frames[f].root_position);
  }
}

TEST_CASE("with balance off a report changes no pose, and turning balance on again reads no stale centroids") {
  // Balance off, the balance stage has nothing to shape: without a report it does nothing, with one it takes
  // the support polygon and the pose's centroids (the World reads them). Either way the pose is the one
  // balance on gives below its alpha threshold. The smoothness history restarts when balance comes back on,
  // as for a new character.
  Params off;
  off.balance.enabled = false;
  const MotionSet set = make_builtin_motion_set(off);
  const Synthesizer synth_off(set, off), synth_on(set, Params{});
  const int walk = find_cyclic_clip(set, Role::Walk);
  REQUIRE(walk >= 0);
  const int target = set.find("duck");
  REQUIRE(target >= 0);
  const MotionClip& tc = set.clips[static_cast<size_t>(target)];
  const Pose reference = tc.clip.frames[static_cast<size_t>(scan_reference_frame(set, tc, off))];
  LocomotionLoop loop(set.clips[static_cast<size_t>(walk)]);
  SynthesisState reported, quiet, below_threshold;
  SynthesisScratch scratch = synth_off.make_scratch();
  Pose locomotion, out_reported = synth_off.make_pose(), out_quiet = synth_off.make_pose(),
                   out_below = synth_off.make_pose();
  const auto input = [&](float alpha) {
    SynthesisInput in;
    loop.next(locomotion, in.contacts);
    in.locomotion = &locomotion;
    in.reference = &reference;
    in.alpha = alpha;
    in.dt = 1.0f / 60.0f;
    return in;
  };
  const float below = 0.9f * Params{}.balance.alpha_threshold;
  int centroids_given = 0;
  for (int frame = 0; frame < 60; ++frame) {
    CAPTURE(frame);
    const SynthesisInput in = input(below);
    SynthesisReport report;
    synth_off.step(in, reported, scratch, out_reported, &report);
    REQUIRE(!report.balanced);
    if (scratch.centroids_of_output) {  // (the floor stage lifted no toe) the World takes this pose's centroids
      REQUIRE(scratch.support_of_output);  // a report asks for the support polygon
      ++centroids_given;
      std::vector<glm::vec3> positions, centroids(synth_off.balance_model().parts.size());
      std::vector<glm::quat> rotations;
      forward_kinematics(*set.skeleton, out_reported, positions, &rotations);
      part_centroids(*set.skeleton, synth_off.balance_model(), positions, rotations, centroids.data());
      for (size_t p = 0; p < centroids.size(); ++p) REQUIRE(reported.previous[p] == centroids[p]);
    }
    synth_off.step(in, quiet, scratch, out_quiet);
    REQUIRE(!scratch.support_of_output);
    REQUIRE(!scratch.centroids_of_output);
    REQUIRE(out_quiet.rotations == out_reported.rotations);
    REQUIRE(out_quiet.root_position == out_reported.root_position);
    synth_on.step(in, below_threshold, scratch, out_below);
    REQUIRE(out_below.rotations == out_reported.rotations);
    REQUIRE(out_below.root_position == out_reported.root_position);
  }
  CHECK(centroids_given > 10);
  // Balance on again: a state whose remembered centroids are nonsense gives the same frames as this one.
  SynthesisState garbled = reported;
  for (glm::vec3& c : garbled.previous) c = glm::vec3(50.0f, -3.0f, 7.0f);
  for (glm::vec3& c : garbled.before_previous) c = glm::vec3(-20.0f, 9.0f, 1.0f);
  int balanced = 0;
  for (int frame = 0; frame < 3; ++frame) {
    const SynthesisInput in = input(0.8f);
    SynthesisReport report;
    synth_on.step(in, reported, scratch, out_reported, &report);
    balanced += report.balanced;
    synth_on.step(in, garbled, scratch, out_quiet);
    CHECK(out_quiet.rotations == out_reported.rotations);
  }
  CHECK(balanced == 3);
}

namespace {

// The built-in walk looped toward a target's T_p: one SynthesisInput per frame at 60 Hz, its locomotion
// pose lowered by `sink` metres.
struct WalkToward {
  Params params;
  MotionSet set = make_builtin_motion_set(params);
  Synthesizer synth{set, params};
  Pose reference, locomotion;
  LocomotionLoop loop;

  explicit WalkToward(const char* target)
      : reference(reference_of(set, target, params)), loop(set.clips[static_cast<size_t>(find_cyclic_clip(set, Role::Walk))]) {}
  SynthesisInput next(float alpha, bool keep_toes_above_floor, float sink = 0.0f) {
    SynthesisInput in;
    loop.next(locomotion, in.contacts);
    locomotion.root_position.y -= sink;
    in.locomotion = &locomotion;
    in.reference = &reference;
    in.alpha = alpha;
    in.dt = 1.0f / 60.0f;
    in.keep_toes_above_floor = keep_toes_above_floor;
    return in;
  }
  static Pose reference_of(const MotionSet& set, const char* target, const Params& params) {
    const int t = set.find(target);
    REQUIRE(t >= 0);
    const MotionClip& tc = set.clips[static_cast<size_t>(t)];
    return tc.clip.frames[static_cast<size_t>(scan_reference_frame(set, tc, params))];
  }
};

}  // namespace

TEST_CASE("after the floor stage pitched a foot, the centroids the synthesizer kept still stand above the ankles") {
  // The World takes the kept centroids of every body part but the feet's when the floor stage only pitched
  // a foot up (SynthesisScratch::centroids_but_feet_of_output): they must be those of the pose returned.
  WalkToward w("duck");
  const MotionSet& set = w.set;
  std::vector<int> ankles;
  for (const LegChain& leg : set.body.legs) ankles.push_back(leg.ankle);
  const std::vector<int> feet = segments_moved_by_turning(*set.skeleton, set.mass, ankles);
  std::vector<char> is_foot(set.mass.segments.size(), 0);
  for (int s : feet) is_foot[static_cast<size_t>(s)] = 1;

  SynthesisState state;
  SynthesisScratch scratch = w.synth.make_scratch();
  Pose out = w.synth.make_pose();
  std::vector<glm::vec3> positions, centroids(set.mass.segments.size());
  std::vector<glm::quat> rotations;
  int feet_pitched = 0, foot_centroid_moved = 0;
  for (int frame = 0; frame < 240; ++frame) {
    CAPTURE(frame);
    // The feet 3 cm into the floor: the floor stage pitches toes up.
    w.synth.step(w.next(0.8f, true, 0.03f), state, scratch, out);
    if (!scratch.centroids_but_feet_of_output) continue;
    REQUIRE(!scratch.support_of_output);
    ++feet_pitched;
    forward_kinematics(*set.skeleton, out, positions, &rotations);
    segment_centroids(*set.skeleton, set.mass, positions, rotations, centroids);
    for (size_t p = 0; p < centroids.size(); ++p) {
      CAPTURE(p);
      if (!is_foot[p]) REQUIRE(state.previous[p] == centroids[p]);
      else foot_centroid_moved += state.previous[p] != centroids[p];
    }
  }
  CHECK(feet_pitched > 20);
  CHECK(foot_centroid_moved > 20);  // the feet's kept centroids are stale: the World takes those again
}

TEST_CASE("step() tells whether the balance optimizer ran, as a report would, without one") {
  WalkToward w("crawl");
  const Synthesizer& synth = w.synth;
  SynthesisState reported, quiet;
  SynthesisScratch scratch = synth.make_scratch();
  Pose out_reported = synth.make_pose(), out_quiet = synth.make_pose();
  std::vector<glm::vec3> positions, centroids(synth.balance_model().parts.size());
  std::vector<glm::quat> rotations;
  int balanced = 0, not_balanced = 0;
  for (int frame = 0; frame < 180; ++frame) {
    CAPTURE(frame);
    // Below the optimizer's threshold, then above it; the pose as the balance stage leaves it.
    const SynthesisInput in = w.next(static_cast<float>(frame) / 180.0f, false);
    SynthesisReport report;
    REQUIRE(synth.step(in, reported, scratch, out_reported, &report) == report.balanced);
    REQUIRE(synth.step(in, quiet, scratch, out_quiet) == report.balanced);
    REQUIRE(out_quiet.rotations == out_reported.rotations);
    (report.balanced ? balanced : not_balanced) += 1;
    // Below the optimizer's threshold and without a report, no support polygon is taken; the centroids are,
    // for the smoothness history and the World.
    REQUIRE(scratch.support_of_output == (in.alpha >= w.params.balance.alpha_threshold));
    REQUIRE(scratch.centroids_of_output);
    forward_kinematics(*w.set.skeleton, out_quiet, positions, &rotations);
    part_centroids(*w.set.skeleton, synth.balance_model(), positions, rotations, centroids.data());
    for (size_t p = 0; p < centroids.size(); ++p) REQUIRE(quiet.previous[p] == centroids[p]);
  }
  CHECK(balanced > 30);
  CHECK(not_balanced > 30);
}
