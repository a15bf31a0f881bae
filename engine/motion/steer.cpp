#include "engine/motion/steer.h"

#include <glm/gtc/quaternion.hpp>
#include <stdexcept>

#include "engine/motion/kinematics.h"

namespace prep {
namespace {

// The point a foot in contact turns about: the heel (the ankle joint, foot_points) whenever it is down,
// else the toe tip. Turning about the ankle keeps its distance to the hip, so the foot IK holding a flat
// foot only twists the leg; turning about a point ahead of it would walk the ankle away from the hip by
// a millimetre or two a frame, and the IK would lower the pelvis further at every step to keep it in reach.
glm::vec3 pivot_point(const FootPoints& feet, const FootContact& c, size_t side) {
  return c.heel ? feet.heel[side] : feet.toe[side];
}

}  // namespace

void steer_clip(Clip& clip, const BodyMap& body, const std::vector<FrameContacts>& contacts, float rate) {
  const size_t n = clip.frames.size();
  if (contacts.size() != n) throw std::invalid_argument("steer_clip: one FrameContacts per frame is needed");
  if (n < 2 || !(clip.fps > 0.0f) || !clip.skeleton) return;

  // Frames that turn: single support and flight; double support holds still. The rate while turning is
  // raised to keep the average.
  int turning = 0;
  for (size_t f = 1; f < n; ++f) turning += !(contacts[f][kLeft].any() && contacts[f][kRight].any());
  if (turning == 0) return;  // always on both feet (standing): nothing to turn about
  const float step_angle = rate * static_cast<float>(n - 1) / clip.fps / static_cast<float>(turning);

  // The floor transform applied to each source frame: x -> yaw * x + shift (x, z only), composed
  // frame after frame with a turn about that frame's pivot.
  const glm::vec3 up(0.0f, 1.0f, 0.0f);
  glm::quat yaw(1.0f, 0.0f, 0.0f, 0.0f);
  glm::vec3 shift(0.0f);
  std::vector<glm::vec3> positions;
  std::vector<glm::quat> rotations;
  const std::vector<Pose> source = clip.frames;
  for (size_t f = 1; f < n; ++f) {
    const FrameContacts& c = contacts[f];
    const bool left = c[kLeft].any(), right = c[kRight].any();
    if (!(left && right)) {
      glm::vec3 pivot = source[f].root_position;  // flight: about the root
      if (left != right) {
        forward_kinematics(*clip.skeleton, source[f], positions, &rotations);
        const FootPoints feet = foot_points(*clip.skeleton, body, positions, rotations);
        const size_t side = left ? kLeft : kRight;
        pivot = pivot_point(feet, c[side], side);
      }
      const glm::vec3 at = yaw * pivot + shift;  // where the previous transform puts the pivot
      const glm::quat turn = glm::angleAxis(step_angle, up);
      yaw = turn * yaw;
      shift = turn * (shift - at) + at;  // the new transform leaves `at` where it was
    }
    Pose& pose = clip.frames[f];
    const float height = source[f].root_position.y;
    pose.root_position = yaw * source[f].root_position + shift;
    pose.root_position.y = height;
    pose.rotations[0] = yaw * source[f].rotations[0];
  }
}

}  // namespace prep
