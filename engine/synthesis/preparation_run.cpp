#include "engine/synthesis/preparation_run.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "engine/motion/kinematics.h"
#include "engine/synthesis/trajectory.h"

namespace prep {

LocomotionLoop::LocomotionLoop(const MotionClip& clip) : clip_(&clip) {
  const int n = clip.clip.frame_count();
  if (n < 2) throw std::invalid_argument("locomotion loop: clip \"" + clip.clip.name + "\" has fewer than 2 frames");
  first_ = clip.cyclic ? std::clamp(clip.loop_first, 0, n - 2) : 0;
  last_ = clip.cyclic && clip.loop_last > first_ ? std::min(clip.loop_last, n - 1) : n - 1;
  frame_ = first_;
}

void LocomotionLoop::next(Pose& pose, FrameContacts& contacts) {
  if (frame_ > last_) {
    // Wrap: place frame `first_` where frame `last_` would have stepped next, turned by last_'s turn rate.
    const Pose& a = clip_->clip.frames[static_cast<size_t>(last_ - 1)];
    const Pose& b = clip_->clip.frames[static_cast<size_t>(last_)];
    const Pose& f = clip_->clip.frames[static_cast<size_t>(first_)];
    const float turn_rate = heading_of(b.rotations[0]) - heading_of(a.rotations[0]);
    const glm::vec3 step = turn_ * (b.root_position - a.root_position);
    const glm::vec3 end = turn_ * b.root_position + shift_;
    const float new_heading = heading_of(turn_ * b.rotations[0]) + turn_rate;
    turn_ = heading_rotation(new_heading - heading_of(f.rotations[0]));
    glm::vec3 target = end + step;
    shift_ = target - turn_ * f.root_position;
    shift_.y = 0.0f;
    frame_ = first_;
  }
  const Pose& src = clip_->clip.frames[static_cast<size_t>(frame_)];
  pose.rotations = src.rotations;
  pose.rotations[0] = glm::normalize(turn_ * src.rotations[0]);
  pose.root_position = turn_ * src.root_position + shift_;
  pose.root_position.y = src.root_position.y;
  contacts = frame_ < static_cast<int>(clip_->contacts.size()) ? clip_->contacts[static_cast<size_t>(frame_)]
                                                                : FrameContacts{};
  ++frame_;
}

PreparationRun run_preparation(const MotionSet& set, const Params& params, const PreparationRunOptions& options) {
  if (options.locomotion_clip < 0 || options.locomotion_clip >= static_cast<int>(set.clips.size())) {
    throw std::invalid_argument("run_preparation: no locomotion clip " + std::to_string(options.locomotion_clip));
  }
  if (static_cast<int>(options.reference.rotations.size()) != set.skeleton->size()) {
    throw std::invalid_argument("run_preparation: the reference posture is not on the set's skeleton");
  }
  const MotionClip& walk = set.clips[static_cast<size_t>(options.locomotion_clip)];
  const Synthesizer synth(set, params);
  SynthesisScratch scratch = synth.make_scratch();
  SynthesisState state;
  LocomotionLoop loop(walk);

  PreparationRun run;
  run.fps = walk.clip.fps;
  const int frames = static_cast<int>(std::lround(options.seconds * run.fps)) + 1;
  run.frames.reserve(static_cast<size_t>(frames));
  run.locomotion.reserve(static_cast<size_t>(frames));
  run.contacts.reserve(static_cast<size_t>(frames));
  run.reports.reserve(static_cast<size_t>(frames));
  run.foot_slide.reserve(static_cast<size_t>(frames));
  Pose loco = synth.make_pose();
  Pose out = synth.make_pose();
  SynthesisInput in;
  in.locomotion = &loco;
  in.reference = &options.reference;
  in.dt = 1.0f / run.fps;
  for (int i = 0; i < frames; ++i) {
    const float t = frames > 1 ? static_cast<float>(i) / static_cast<float>(frames - 1) : 1.0f;
    loop.next(loco, in.contacts);
    in.alpha = options.alpha_start + (options.alpha_end - options.alpha_start) * t;
    SynthesisReport report;
    synth.step(in, state, scratch, out, &report);
    run.frames.push_back(out);
    run.locomotion.push_back(loco);
    run.contacts.push_back(in.contacts);
    run.reports.push_back(report);
    float slide = 0.0f;
    if (i > 0) {
      const SynthesisReport& before = run.reports[static_cast<size_t>(i - 1)];
      const FrameContacts& was = before.pinned;
      const FrameContacts& now = report.pinned;
      for (int side = 0; side < 2; ++side) {
        if (was[side].heel && now[side].heel) slide = std::max(slide, glm::length(report.feet.heel[side] - before.feet.heel[side]));
        if (was[side].toe && now[side].toe) slide = std::max(slide, glm::length(report.feet.toe[side] - before.feet.toe[side]));
      }
    }
    run.foot_slide.push_back(slide);
  }
  return run;
}

namespace {

// Leg joint positions relative to the root, turned into the root's heading frame.
void leg_points(const MotionSet& set, const std::vector<glm::vec3>& positions, const glm::quat& root, glm::vec3* out) {
  const glm::quat unturn = glm::inverse(heading_rotation(heading_of(root)));
  int k = 0;
  for (const LegChain& leg : set.body.legs) {
    for (int j : {leg.hip, leg.knee, leg.ankle, leg.toe}) {
      out[k++] = j >= 0 ? unturn * (positions[static_cast<size_t>(j)] - positions[0]) : glm::vec3(0.0f);
    }
  }
}

}  // namespace

int scan_reference_frame(const MotionSet& set, const MotionClip& target, const Params& params) {
  if (target.target_frame < 0 || target.clip.frames.empty()) {
    throw std::invalid_argument("clip \"" + target.clip.name + "\" has no target frame T_t");
  }
  const Skeleton& skeleton = *set.skeleton;
  std::vector<glm::vec3> positions, centroids;
  std::vector<glm::quat> rotations;
  glm::vec3 legs0[8], legs[8];
  forward_kinematics(skeleton, target.clip.frames[0], positions, &rotations);
  leg_points(set, positions, target.clip.frames[0].rotations[0], legs0);
  const FrameContacts contacts0 = target.contacts.empty() ? FrameContacts{} : target.contacts[0];
  const int last = std::min(target.target_frame, target.clip.frame_count() - 1);
  for (int f = last; f >= 0; --f) {
    const Pose& pose = target.clip.frames[static_cast<size_t>(f)];
    const FrameContacts& contacts = target.contacts[static_cast<size_t>(f)];
    if (!(contacts == contacts0)) continue;  // condition 2
    forward_kinematics(skeleton, pose, positions, &rotations);
    leg_points(set, positions, pose.rotations[0], legs);
    float squared = 0.0f;
    for (int k = 0; k < 8; ++k) squared += glm::dot(legs[k] - legs0[k], legs[k] - legs0[k]);
    if (squared > params.reference.legs_threshold) continue;  // condition 3
    const SupportPolygon polygon =
        support_polygon(foot_points(skeleton, set.body, positions, rotations), contacts, params.contacts);
    segment_centroids(skeleton, set.mass, positions, rotations, centroids);
    const glm::vec3 com = center_of_mass(set.mass, centroids);
    if (polygon.empty() || !polygon.contains({com.x, com.z})) continue;  // condition 1
    return f;
  }
  return 0;
}

}  // namespace prep
