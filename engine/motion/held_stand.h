// A standing clip for a motion set that has none, made from its walk.
//
// Characters stop on the set's idle clip (engine/world/world.h). A set without one (cmu31's takes have no
// quiet standing) had them stop on the walk, which kept walking where they should stand: a user at
// its goal, a beaten opponent at its spot aside, walking on until an obstacle stopped them. Any one frame of
// the walk, held, would freeze a stride, and the walk's mean posture leans and bends its knees as walking
// does. A stand is the skeleton's rest pose for the trunk and legs (upright, knees straight, feet under the
// hips) with the arms, which that pose holds out, as they hang on average through the walk.
#pragma once

#include "engine/motion/body_map.h"
#include "engine/motion/motion_set.h"

namespace prep {

// The stand above, facing where the walk's loop (its whole clip if it has none) starts: each arm joint's
// rotations over the loop turned to the hemisphere of the first, summed and normalized; the lowest heel or
// toe tip set on the floor (estimate_floor_heights). Held for `seconds`: a cyclic clip of role idle named
// "<walk>_stand".
MotionClip held_stand_from_walk(const MotionClip& walk, const BodyMap& body, float seconds = 1.0f);

}  // namespace prep
