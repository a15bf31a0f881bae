// Per-frame foot contacts (heel and toe of each foot) from heights and speeds with hysteresis.
#pragma once

#include <array>
#include <vector>

#include "engine/motion/body_map.h"
#include "engine/motion/clip.h"
#include "engine/params/params.h"

namespace prep {

struct FootContact {
  bool heel = false;
  bool toe = false;
  bool any() const { return heel || toe; }
  bool operator==(const FootContact& o) const { return heel == o.heel && toe == o.toe; }
};

using FrameContacts = std::array<FootContact, 2>;  // [kLeft], [kRight]

// Floor height is y = 0. A heel or toe point enters contact when below contacts.height_on and slower
// than speed_on, and leaves it when above height_off or faster than speed_off (hysteresis). Speeds use
// central differences over the clip's frames (spanning ~1/15 s whatever the frame rate).
// Heights count from where each point rests when planted: the ankle joint sits above the sole and
// captured floors are offset and drift (daz43 walks rise several cm), so in clips of 0.5 s or more the
// planted height is the 10th percentile of that point's height within +-1 s; shorter clips use the
// skeleton's rest pose standing on y = 0 (the ankle's height above the toe tip, and 0 for the toe).
std::vector<FrameContacts> detect_contacts(const Clip& clip, const BodyMap& body, const ContactParams& params);

// World positions of the heel (ankle joint) and toe tip of each foot for a pose already through FK.
struct FootPoints {
  std::array<glm::vec3, 2> heel;
  std::array<glm::vec3, 2> toe;
};
FootPoints foot_points(const Skeleton& skeleton, const BodyMap& body, const std::vector<glm::vec3>& world_positions,
                       const std::vector<glm::quat>& world_rotations);

}  // namespace prep
