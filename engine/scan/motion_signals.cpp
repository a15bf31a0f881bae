#include "engine/scan/motion_signals.h"

#include <algorithm>
#include <cmath>

#include <glm/gtc/constants.hpp>
#include <glm/geometric.hpp>

#include "engine/motion/kinematics.h"

namespace prep {
namespace {

constexpr float kRateSpanSeconds = 1.0f / 15.0f;  // the span of a central difference

// Facing from the hips: the horizontal normal to the left-to-right hip line, as a yaw about +Y.
float hips_heading(const glm::vec3& left_hip, const glm::vec3& right_hip) {
  const glm::vec3 across = left_hip - right_hip;
  // forward = across x up: with left at +X and up +Y, forward is +Z (yaw 0).
  const glm::vec3 forward(-across.z, 0.0f, across.x);
  return std::atan2(forward.x, forward.z);
}

template <typename T, typename Length>
std::vector<float> rate_of(const std::vector<T>& v, int half, float fps, Length length) {
  const int n = static_cast<int>(v.size());
  std::vector<float> out(v.size(), 0.0f);
  for (int f = 0; f < n; ++f) {
    const int a = std::max(0, f - half), b = std::min(n - 1, f + half);
    if (b > a) out[static_cast<size_t>(f)] = length(v[static_cast<size_t>(b)], v[static_cast<size_t>(a)]) * fps / static_cast<float>(b - a);
  }
  return out;
}

}  // namespace

int MotionSignals::frames_in(float s) const { return std::max(1, static_cast<int>(std::lround(s * fps))); }

MotionSignals measure_motion(const Clip& clip, const BodyMap& body, const ContactParams& contact_params) {
  const Skeleton& skeleton = *clip.skeleton;
  MotionSignals s;
  s.fps = clip.fps;
  s.frames = clip.frame_count();
  std::vector<glm::vec3> positions;
  std::vector<glm::quat> rotations;

  // The rest pose standing on the floor: where the head is when standing up straight.
  {
    Pose rest(skeleton.size());
    forward_kinematics(skeleton, rest, positions, &rotations);
    const FootPoints feet = foot_points(skeleton, body, positions, rotations);
    const float lowest = std::min({feet.heel[0].y, feet.heel[1].y, feet.toe[0].y, feet.toe[1].y});
    s.standing_head = positions[static_cast<size_t>(body.head >= 0 ? body.head : body.neck)].y - lowest;
  }

  float previous_heading = 0.0f;
  for (int f = 0; f < s.frames; ++f) {
    forward_kinematics(skeleton, clip.frames[static_cast<size_t>(f)], positions, &rotations);
    const FootPoints feet = foot_points(skeleton, body, positions, rotations);
    auto at = [&](int joint) { return positions[static_cast<size_t>(joint)]; };
    s.root.push_back(at(body.root));
    float h = hips_heading(at(body.legs[kLeft].hip), at(body.legs[kRight].hip));
    if (f > 0) {
      // Unwrapped: each frame within half a turn of the one before.
      while (h - previous_heading > glm::pi<float>()) h -= 2.0f * glm::pi<float>();
      while (h - previous_heading < -glm::pi<float>()) h += 2.0f * glm::pi<float>();
    }
    previous_heading = h;
    s.heading.push_back(h);
    s.head_height.push_back(at(body.head >= 0 ? body.head : body.neck).y);
    s.lowest_foot.push_back(std::min({feet.heel[0].y, feet.heel[1].y, feet.toe[0].y, feet.toe[1].y}));
    for (int side : {kLeft, kRight}) {
      const size_t k = static_cast<size_t>(side);
      s.toe_height[k].push_back(feet.toe[k].y);
      s.hand[k].push_back(at(body.arms[k].wrist));
      s.ankle[k].push_back(at(body.legs[k].ankle));
    }
  }
  s.contacts = detect_contacts(clip, body, contact_params);

  const int half = std::max(1, static_cast<int>(std::lround(0.5f * kRateSpanSeconds * s.fps)));
  s.ground_speed = rate_of(s.root, half, s.fps, [](const glm::vec3& b, const glm::vec3& a) {
    return glm::length(glm::vec2(b.x - a.x, b.z - a.z));
  });
  s.turn_rate = rate_of(s.heading, half, s.fps, [](float b, float a) { return b - a; });
  for (int side : {kLeft, kRight}) {
    const size_t k = static_cast<size_t>(side);
    std::vector<glm::vec3> relative(s.hand[k].size());
    for (size_t f = 0; f < relative.size(); ++f) relative[f] = s.hand[k][f] - s.root[f];
    auto distance = [](const glm::vec3& b, const glm::vec3& a) { return glm::length(b - a); };
    s.hand_speed[k] = rate_of(relative, half, s.fps, distance);
    s.foot_speed[k] = rate_of(s.ankle[k], half, s.fps, distance);
  }
  return s;
}

std::vector<Flight> flights(const MotionSignals& s, int first, int last) {
  std::vector<Flight> out;
  for (int f = first; f <= last; ++f) {
    const FrameContacts& c = s.contacts[static_cast<size_t>(f)];
    const bool airborne = !c[0].any() && !c[1].any();
    if (!airborne) continue;
    if (!out.empty() && out.back().last == f - 1)
      out.back().last = f;
    else
      out.push_back({f, f});
  }
  return out;
}

std::vector<float> smoothed(const std::vector<float>& v, int half) {
  const int n = static_cast<int>(v.size());
  std::vector<float> out(v.size());
  for (int f = 0; f < n; ++f) {
    const int a = std::max(0, f - half), b = std::min(n - 1, f + half);
    float sum = 0.0f;
    for (int g = a; g <= b; ++g) sum += v[static_cast<size_t>(g)];
    out[static_cast<size_t>(f)] = sum / static_cast<float>(b - a + 1);
  }
  return out;
}

float median_of(const std::vector<float>& v, int first, int last) {
  std::vector<float> part(v.begin() + first, v.begin() + last + 1);
  std::nth_element(part.begin(), part.begin() + static_cast<std::ptrdiff_t>(part.size() / 2), part.end());
  return part[part.size() / 2];
}

}  // namespace prep
