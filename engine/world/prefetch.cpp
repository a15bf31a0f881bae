// Prefetching a world's memory ahead of its step (World::prefetch, prefetch_ahead): a crowd steps thousands
// of worlds one after another, each owning a few kilobytes spread over dozens of allocations, and would
// otherwise meet every one of them cold.
#include "engine/util/prefetch.h"

#include "engine/control/arrival.h"
#include "engine/world/world.h"
#include "engine/world/world_runtime.h"

namespace prep {

void World::prefetch(int level) const {
  switch (level) {
    case 0:
      prefetch_object(*this);
      break;
    case 1:
      prefetch_vector(characters_);
      prefetch_vector(objects_);
      prefetch_vector(runtime_);
      prefetch_object(*arrival_);
      break;
    case 2:
      for (const WorldCharacter& c : characters_) {
        prefetch_vector(c.pose.rotations);
        prefetch_vector(c.support.hull);
        prefetch_vector(c.goal);  // choose_source reads the next waypoint first thing
      }
      for (const auto& rt : runtime_) prefetch_object(*rt);
      break;
    case 3:
      for (const auto& r : runtime_) {
        const Runtime& rt = *r;
        prefetch_vector(rt.scratch.positions);
        prefetch_vector(rt.scratch.rotations);
        prefetch_vector(rt.out.rotations);
        if (rt.fade_left > 0.0f) prefetch_vector(rt.fade_from.rotations);  // read only while a cross-fade lasts
        prefetch_vector(rt.scratch.weights);
        prefetch_vector(rt.scratch.support.hull);
        prefetch_vector(rt.capsules);
        rt.stream.prefetch(0);
        rt.controller->prefetch(0);
      }
      break;
    default:
      for (const auto& rt : runtime_) {
        rt->stream.prefetch(level - 3);
        rt->controller->prefetch(level - 3);
      }
  }
}

void prefetch_ahead(const std::vector<std::unique_ptr<World>>& worlds, size_t i, size_t end) {
  for (int level = 0; level < World::kPrefetchLevels; ++level) {
    const size_t ahead = i + static_cast<size_t>(World::kPrefetchLevels - level);
    if (ahead < end) worlds[ahead]->prefetch(level);
  }
}

}  // namespace prep
