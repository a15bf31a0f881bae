#include "engine/motion/contacts.h"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>

#include "engine/motion/kinematics.h"

namespace prep {
namespace {

// A point's planted height is read from the clip when it is at least this long: the feet then spend
// many frames on the floor, and the low percentile of a point's height over a window of frames (longer
// than a gait cycle, so that it holds a stance phase) is where it rests when planted.
constexpr int kMinFramesForPlantedHeight = 10;
constexpr float kMinSecondsForPlantedHeight = 0.5f;
constexpr float kPlantedWindow = 1.0f;  // s either side
constexpr float kPlantedPercentile = 0.1f;
constexpr float kSpeedSpan = 2.0f / 30.0f;  // s: one frame either side at 30 fps

glm::vec3 toe_point(const Skeleton& skeleton, const LegChain& leg, const std::vector<glm::vec3>& positions,
                    const std::vector<glm::quat>& rotations) {
  if (leg.toe_tip_joint >= 0 && skeleton.joints[static_cast<size_t>(leg.toe_tip_joint)].has_end_site)
    return end_site_position(skeleton, leg.toe_tip_joint, positions, rotations);
  if (leg.toe >= 0) return positions[static_cast<size_t>(leg.toe)];
  return positions[static_cast<size_t>(leg.ankle)];
}

// How far the ankle joint sits above the sole when the foot is flat: the ankle's height above the toe
// tip in the skeleton's rest pose (all rotations identity, which is a flat foot in every skeleton we read).
// The heel touches the floor when the ankle is this high, so heel heights are measured from it.
float ankle_above_sole(const Skeleton& skeleton, const LegChain& leg) {
  const Pose rest(skeleton.size());
  std::vector<glm::vec3> positions;
  std::vector<glm::quat> rotations;
  forward_kinematics(skeleton, rest, positions, &rotations);
  const glm::vec3 toe = toe_point(skeleton, leg, positions, rotations);
  return std::max(0.0f, positions[static_cast<size_t>(leg.ankle)].y - toe.y);
}

}  // namespace

FootPoints foot_points(const Skeleton& skeleton, const BodyMap& body, const std::vector<glm::vec3>& world_positions,
                       const std::vector<glm::quat>& world_rotations) {
  FootPoints feet;
  for (int side : {kLeft, kRight}) {
    const LegChain& leg = body.legs[static_cast<size_t>(side)];
    feet.heel[static_cast<size_t>(side)] = world_positions[static_cast<size_t>(leg.ankle)];
    feet.toe[static_cast<size_t>(side)] = toe_point(skeleton, leg, world_positions, world_rotations);
  }
  return feet;
}

std::vector<FrameContacts> detect_contacts(const Clip& clip, const BodyMap& body, const ContactParams& params) {
  const int frames = clip.frame_count();
  std::vector<FrameContacts> contacts(static_cast<size_t>(std::max(frames, 0)));
  if (frames == 0 || !clip.skeleton) return contacts;
  const Skeleton& skeleton = *clip.skeleton;

  // Points per frame: [frame][side][0 = heel, 1 = toe].
  std::vector<std::array<std::array<glm::vec3, 2>, 2>> points(static_cast<size_t>(frames));
  std::vector<glm::vec3> positions;
  std::vector<glm::quat> rotations;
  for (int f = 0; f < frames; ++f) {
    forward_kinematics(skeleton, clip.frames[static_cast<size_t>(f)], positions, &rotations);
    const FootPoints feet = foot_points(skeleton, body, positions, rotations);
    for (size_t s = 0; s < 2; ++s) points[static_cast<size_t>(f)][s] = {feet.heel[s], feet.toe[s]};
  }
  // Heights are taken above each point's planted height (see contacts.h): the low percentile of that
  // point's height over a window of frames around it. A window, not the whole clip, because captured
  // floors drift (the daz43 walks rise several cm over a clip); clips too short to tell use the
  // skeleton's rest-pose foot on the floor y = 0.
  std::array<std::array<std::vector<float>, 2>, 2> planted;
  const bool long_enough = frames >= std::max(kMinFramesForPlantedHeight, static_cast<int>(clip.fps * kMinSecondsForPlantedHeight));
  const int window = std::max(1, static_cast<int>(std::lround(kPlantedWindow * clip.fps)));
  std::vector<float> heights;
  for (size_t s = 0; s < 2; ++s) {
    const std::array<float, 2> rest = {ankle_above_sole(skeleton, body.legs[s]), 0.0f};
    for (size_t k = 0; k < 2; ++k) {
      planted[s][k].assign(static_cast<size_t>(frames), rest[k]);
      if (!long_enough) continue;
      for (int f = 0; f < frames; ++f) {
        // The window keeps its full length near the clip's ends by sliding inward.
        const int first = std::clamp(f - window, 0, std::max(0, frames - 1 - 2 * window));
        const int last = std::min(frames - 1, first + 2 * window);
        heights.clear();
        for (int g = first; g <= last; ++g) heights.push_back(points[static_cast<size_t>(g)][s][k].y);
        const size_t at = static_cast<size_t>(kPlantedPercentile * static_cast<float>(heights.size() - 1));
        std::nth_element(heights.begin(), heights.begin() + static_cast<std::ptrdiff_t>(at), heights.end());
        planted[s][k][static_cast<size_t>(f)] = heights[at];
      }
    }
  }

  // The difference spans about kSpeedSpan seconds whatever the frame rate, so that capture jitter at
  // 120 fps (millimetres per frame) does not read as speed.
  const int half_span = std::max(1, static_cast<int>(std::lround(0.5f * kSpeedSpan * clip.fps)));
  for (size_t s = 0; s < 2; ++s) {
    for (size_t k = 0; k < 2; ++k) {
      bool in_contact = false;
      for (int f = 0; f < frames; ++f) {
        // Central differences inside the clip, one-sided at its ends.
        const int a = std::max(f - half_span, 0), b = std::min(f + half_span, frames - 1);
        const float speed = b > a ? glm::length(points[static_cast<size_t>(b)][s][k] - points[static_cast<size_t>(a)][s][k]) *
                                        clip.fps / static_cast<float>(b - a)
                                  : 0.0f;
        const float height = points[static_cast<size_t>(f)][s][k].y - planted[s][k][static_cast<size_t>(f)];
        if (in_contact)
          in_contact = height <= params.height_off && speed <= params.speed_off;
        else
          in_contact = height < params.height_on && speed < params.speed_on;
        FootContact& c = contacts[static_cast<size_t>(f)][s];
        (k == 0 ? c.heel : c.toe) = in_contact;
      }
    }
  }
  return contacts;
}

}  // namespace prep
