#include "app/demo/motions.h"

#include "engine/library/builtin.h"
#include "engine/motion/bvh.h"

namespace prep::demo {

int DemoMotions::find(const std::string& name) const {
  for (size_t i = 0; i < clips.size(); ++i)
    if (clips[i].clip.name == name) return static_cast<int>(i);
  return -1;
}

DemoMotions load_demo_motions(const std::string& motions, const std::string& bvh, float unit_scale, const Params& params) {
  DemoMotions out;
  if (!bvh.empty()) {
    BvhReadOptions options;
    options.unit_scale = unit_scale;
    out.source = bvh;
    out.clips.push_back({read_bvh(bvh, options), std::nullopt, -1});
    return out;
  }
  const MotionSet set = motions == "builtin" ? make_builtin_motion_set(params) : load_motion_set(motions, params);
  out.source = motions;
  for (const MotionClip& m : set.clips) out.clips.push_back({m.clip, m.role, m.target_frame});
  return out;
}

}  // namespace prep::demo
