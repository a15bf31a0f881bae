// The clips the demo plays: the built-in library, a motion-set manifest, or one BVH file.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "engine/motion/clip.h"
#include "engine/motion/motion_set.h"

namespace prep::demo {

struct DemoClip {
  Clip clip;
  std::optional<Role> role;  // unknown for a lone BVH
  int target_frame = -1;     // T_t, -1 if none
};

struct DemoMotions {
  std::string source;  // "builtin", a manifest path or a BVH path
  std::vector<DemoClip> clips;
  int find(const std::string& name) const;  // index or -1
};

// motions: "builtin" or a manifest path. If bvh is not empty it is read instead (unit_scale: file units
// to metres). Throws InputError for bad files.
DemoMotions load_demo_motions(const std::string& motions, const std::string& bvh, float unit_scale, const Params& params);

}  // namespace prep::demo
