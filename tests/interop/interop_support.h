// Shared helpers of the interop tests: real clips from ../shared/mocap, pose comparison, a scratch folder.
#pragma once

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>

#include "engine/motion/bvh.h"
#include "engine/motion/kinematics.h"
#include "tests/support/paths.h"

namespace prep::test {

inline std::string scratch(const std::string& name) {
  const std::string dir = tmp_dir() + "/interop";
  std::filesystem::create_directories(dir);
  return dir + "/" + name;
}

// A daz43 clip (centimetres, 120 fps; frame 0 is the converter's reference pose and is dropped).
inline Clip daz43_clip(const std::string& file, int first = 1, int count = 120) {
  BvhReadOptions options;
  options.unit_scale = 0.01f;
  Clip clip = read_bvh(mocap() + "/daz43/" + file, options);
  const int last = std::min(clip.frame_count(), first + count);
  clip.frames = std::vector<Pose>(clip.frames.begin() + first, clip.frames.begin() + last);
  return clip;
}

// A cmu31 clip (CMU units of 1/0.45 inch, 30 fps).
inline Clip cmu31_clip(const std::string& file) {
  BvhReadOptions options;
  options.unit_scale = 0.0254f / 0.45f;
  return read_bvh(mocap() + "/cmu31/" + file, options);
}

inline float quat_distance(glm::quat a, glm::quat b) {
  if (glm::dot(a, b) < 0.0f) b = -b;
  return std::max({std::fabs(a.w - b.w), std::fabs(a.x - b.x), std::fabs(a.y - b.y), std::fabs(a.z - b.z)});
}

// Largest difference of world joint positions (m) and world rotations (quaternion components) over all
// frames of two clips on skeletons with the same joint names (b's joints found by a's names).
struct PoseDifference {
  float position = 0.0f;
  float rotation = 0.0f;
};
inline PoseDifference clip_difference(const Clip& a, const Clip& b) {
  PoseDifference d;
  REQUIRE(a.frame_count() == b.frame_count());
  std::vector<glm::vec3> pa, pb;
  std::vector<glm::quat> qa, qb;
  for (int f = 0; f < a.frame_count(); ++f) {
    forward_kinematics(*a.skeleton, a.frames[static_cast<size_t>(f)], pa, &qa);
    forward_kinematics(*b.skeleton, b.frames[static_cast<size_t>(f)], pb, &qb);
    for (int j = 0; j < a.skeleton->size(); ++j) {
      const int k = b.skeleton->find(a.skeleton->joints[static_cast<size_t>(j)].name);
      REQUIRE(k >= 0);
      d.position = std::max(d.position, glm::length(pa[static_cast<size_t>(j)] - pb[static_cast<size_t>(k)]));
      d.rotation = std::max(d.rotation, quat_distance(qa[static_cast<size_t>(j)], qb[static_cast<size_t>(k)]));
    }
  }
  return d;
}

}  // namespace prep::test
