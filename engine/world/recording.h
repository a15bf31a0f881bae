// Recording a world's run as clips: what `prep export --scenario` writes (glTF or BVH) and what tools and
// tests look at in Blender or any engine.
#pragma once

#include <vector>

#include "engine/motion/clip.h"
#include "engine/world/world.h"

namespace prep {

// Steps the world for `seconds` (RuntimeParams::fixed_dt ticks) and returns one clip per character
// ("character<i>", on the motion set's skeleton, at 1 / fixed_dt frames per second), holding the pose
// synthesis gave that character at every tick.
std::vector<Clip> record_world(World& world, float seconds);

}  // namespace prep
