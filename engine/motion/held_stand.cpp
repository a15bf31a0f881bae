#include "engine/motion/held_stand.h"

#include <algorithm>
#include <cmath>
#include <glm/gtc/quaternion.hpp>
#include <stdexcept>

namespace prep {
namespace {

glm::quat heading_turn(const glm::quat& root_rotation) {
  return glm::angleAxis(heading_of(root_rotation), glm::vec3(0.0f, 1.0f, 0.0f));
}

// The normalized sum of rotations turned to the hemisphere of the first: for rotations this close together
// (a joint over one gait cycle), the mean rotation to well within a degree.
glm::quat mean_rotation(const std::vector<glm::quat>& rotations) {
  glm::vec4 sum(0.0f);
  const glm::quat& first = rotations.front();
  for (const glm::quat& q : rotations) {
    const float sign = glm::dot(q, first) < 0.0f ? -1.0f : 1.0f;
    sum += sign * glm::vec4(q.x, q.y, q.z, q.w);
  }
  const float length = glm::length(sum);
  return length > 1e-6f ? glm::quat(sum.w / length, sum.x / length, sum.y / length, sum.z / length) : first;
}

}  // namespace

MotionClip held_stand_from_walk(const MotionClip& walk, const BodyMap& body, float seconds) {
  const Clip& clip = walk.clip;
  if (clip.frames.empty() || !clip.skeleton) throw std::invalid_argument("held stand: the walk '" + clip.name + "' has no frames");
  const int first = walk.cyclic ? walk.loop_first : 0;
  const int last = walk.cyclic ? walk.loop_last : clip.frame_count() - 1;
  const size_t joints = clip.frames.front().rotations.size();
  const Pose& start = clip.frames[static_cast<size_t>(first)];

  // The trunk and legs as the skeleton's rest pose has them (upright, knees straight: a stand); the arms,
  // which that pose holds out (a T or an A), as they hang on average through the walk's loop.
  Pose stand(static_cast<int>(joints));
  std::vector<bool> trunk(joints, false);
  for (int j : body.spine) trunk[static_cast<size_t>(j)] = true;
  for (int j : {body.neck, body.head})
    if (j >= 0) trunk[static_cast<size_t>(j)] = true;
  std::vector<glm::quat> samples;
  for (size_t j = 1; j < joints; ++j) {
    const bool arm = j < body.upper_body.size() && body.upper_body[j] && !trunk[j];
    if (!arm) continue;
    samples.clear();
    for (int f = first; f <= last; ++f) samples.push_back(clip.frames[static_cast<size_t>(f)].rotations[j]);
    stand.rotations[j] = mean_rotation(samples);
  }
  stand.rotations[0] = heading_turn(start.rotations[0]);  // facing where the loop starts
  stand.root_position = glm::vec3(start.root_position.x, 0.0f, start.root_position.z);

  MotionClip held;
  held.clip.name = clip.name + "_stand";
  held.clip.skeleton = clip.skeleton;
  held.clip.fps = clip.fps;
  const int frames = std::max(3, static_cast<int>(std::lround(seconds * clip.fps)));
  held.clip.frames.assign(static_cast<size_t>(frames), stand);
  // On the floor: the lowest heel or toe tip at its height 0.
  const float floor = estimate_floor_heights(held.clip, body).front();
  for (Pose& p : held.clip.frames) p.root_position.y -= floor;
  held.role = Role::Idle;
  held.cyclic = true;
  held.loop_first = 0;
  held.loop_last = frames - 2;  // a loop edge blends from the frames after loop_last, as a take's does
  held.source_file = walk.source_file;
  held.derived_from = clip.name;
  return held;
}

}  // namespace prep
