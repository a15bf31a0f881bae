#include "engine/motion/clip.h"

#include <algorithm>
#include <cmath>

namespace prep {

void Clip::sample(float t, Pose& out) const {
  if (frames.empty()) {
    out = Pose();
    return;
  }
  const float f = std::clamp(t * fps, 0.0f, static_cast<float>(frame_count() - 1));
  const int i0 = static_cast<int>(std::floor(f));
  const int i1 = std::min(i0 + 1, frame_count() - 1);
  interpolate(frames[static_cast<size_t>(i0)], frames[static_cast<size_t>(i1)], f - static_cast<float>(i0), out);
}

void make_hemisphere_continuous(Clip& clip) {
  for (size_t f = 1; f < clip.frames.size(); ++f) {
    auto& cur = clip.frames[f].rotations;
    const auto& prev = clip.frames[f - 1].rotations;
    for (size_t j = 0; j < cur.size() && j < prev.size(); ++j)
      if (glm::dot(cur[j], prev[j]) < 0.0f) cur[j] = -cur[j];
  }
}

}  // namespace prep
