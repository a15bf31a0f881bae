#include "engine/world/recording.h"

#include <cmath>
#include <string>

namespace prep {

std::vector<Clip> record_world(World& world, float seconds) {
  const float dt = world.params().runtime.fixed_dt;
  std::vector<Clip> clips(world.characters().size());
  const int ticks = static_cast<int>(std::lround(seconds / dt));
  for (size_t i = 0; i < clips.size(); ++i) {
    clips[i].name = "character" + std::to_string(i);
    clips[i].skeleton = world.assets().set->skeleton;
    clips[i].fps = 1.0f / dt;
    clips[i].frames.reserve(static_cast<size_t>(ticks));
  }
  for (int t = 0; t < ticks; ++t) {
    world.step();
    for (size_t i = 0; i < clips.size(); ++i) clips[i].frames.push_back(world.characters()[i].pose);
  }
  return clips;
}

}  // namespace prep
