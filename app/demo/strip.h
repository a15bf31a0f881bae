// A strip of frames of one clip, side by side, for judging motion by eye: `frames` tiles spread
// evenly over the clip (first and last frame included), each tile_width x tile_height, all seen from the
// same side at the same scale (clip_view.h strip_camera), the camera sliding along with the character.
#pragma once

#include "app/demo/motions.h"
#include "app/render/image.h"

namespace prep::demo {

struct StripOptions {
  int frames = 8;
  int tile_width = 320;
  int tile_height = 480;
  bool props = true;   // the obstacle of the clip's role
  bool labels = true;  // clip name and time of each tile (ImGui text)
};

// Renders headless through its own OSMesa context.
render::Image render_strip(const DemoClip& clip, const StripOptions& options);

}  // namespace prep::demo
