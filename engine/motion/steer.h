// Steering a straight locomotion clip into a turn, for motion sets that have a walk but no loopable turn
// (the CMU sets: the controller of Sec. 6 needs core motions that turn both ways to steer toward a goal).
#pragma once

#include <vector>

#include "engine/motion/body_map.h"
#include "engine/motion/clip.h"
#include "engine/motion/contacts.h"

namespace prep {

// Turns the clip's heading at an average rate of `rate` (rad/s, about the vertical, positive to the left:
// counter-clockwise seen from above) by turning the whole body, frame after frame, about the foot it
// stands on, the way a walker turns: while exactly one foot is in contact (contacts: the clip's own, one
// per frame) the body turns about that foot's heel (the ankle joint), or its toe tip on tiptoe; in double
// support it does not turn, so neither planted foot moves; in flight (no contact) it turns about the root.
// The rate in single support is raised so that the heading gains rate x duration over the clip. Joint
// rotations other than the root's and the root's height are kept; planted feet stay as still as they
// were in the clip. Turning about the root instead would drag a planted foot by rate x its distance
// from the root, 10-20 cm over a stance phase at 40 degrees per second.
void steer_clip(Clip& clip, const BodyMap& body, const std::vector<FrameContacts>& contacts, float rate);

}  // namespace prep
