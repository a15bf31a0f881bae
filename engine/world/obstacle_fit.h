// Fitting an obstacle clip to the obstacle in front of it. A crawl, duck or jump clip was made for one
// obstacle height; scenarios have others. The clip's body (its capsules, body_volumes.h) is swept over
// the obstacle's rail or board, placed as the launch places it (the obstacle `reach` ahead of the T_p root):
// - Under a bar or beam: the highest point of the body under the rail (within the rail's depth) is what the
//   clip needs; a lower rail lowers the body by the difference plus kFitMargin while it passes, the feet
//   kept exactly where the clip puts them (the knees bend: a deeper crouch).
// - Over a hurdle: the lowest point of the body over the board; a taller board raises the body by the
//   difference plus kFitMargin while it passes, feet in contact kept planted (a higher flight).
// The change fades in and out over kFitRamp seconds around the frames where the body is over or under it.
// How far a clip may be changed is bounded per action (max_fit): a crawl's knees and forearms are on
// the floor, so it can hardly go lower. An obstacle beyond that cannot be passed by the set's clip, and a
// scenario holding one is refused on loading (World's constructor names the object).
#pragma once

#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "engine/motion/body_volumes.h"
#include "engine/motion/motion_set.h"
#include "engine/world/scenario.h"

namespace prep {

struct TargetMotion;

constexpr float kFitMargin = 0.02f;  // m kept between the body and the rail or board
constexpr float kFitRamp = 0.35f;    // s over which the fit fades in before, and out after, the passage

// m: how much lower (crawl, duck) or higher (jump) a clip may carry the body than it was made for.
float max_fit(TargetAction action);

// The body of a target clip from T_p to its end, placed per frame in the T_p root's floor frame: z along the
// T_p facing, y up, x to the left.
struct ClipSweep {
  struct Segment {
    float z0, y0, z1, y1, radius;
    float x0, x1;  // the fit does not need these (obstacles are wider than a body); the room beside one does
  };
  int first_frame = 0;                        // T_p
  float fps = 30.0f;
  std::vector<std::vector<Segment>> frames;   // [frame - first_frame][capsule]
  std::vector<float> root_z;                  // [frame - first_frame]: the root's z
};
ClipSweep sweep_clip(const MotionSet& set, const BodyVolumes& volumes, int clip, int reference_frame);

// How far along the T_p facing (z of the sweep) the body of a target clip reaches at each height, from T_p
// up to a last frame, capsule radii included, and how far to either side: the room an obstacle crossed needs
// beyond it before the next one (World::launch_lateral). A body lying low under a bar reaches far at knee
// height and not at all at head height, so a beam beyond a bar takes less room than a hurdle.
struct BodyReach {
  static constexpr float kBand = 0.1f;  // m of height per entry
  std::vector<float> z;                 // [band]: the farthest z within heights [b, b + 1) * kBand; -inf: none
  float half_width = 0.0f;              // m: the farthest the body reaches to either side of the T_p root's line
  // The farthest z of the body at any height from y0 to y1 (-inf when it has none there).
  float over(float y0, float y1) const;
};
// Frames first_frame..last_frame of the sweep (clip frames; last_frame < 0: to its end).
BodyReach body_reach(const ClipSweep& sweep, int last_frame);

struct ObstacleFit {
  float lift = 0.0f;        // m: > 0 raises the body over a hurdle, < 0 lowers it under a bar or beam
  float clip_height = 0.0f; // m: the clip's own: the lowest rail it passes under / the highest board it clears
  int first = 0, last = -1; // clip frames with the body under or over the rail (no frames: last < first)
  float ramp_frames = 0.0f;
  bool possible = true;     // within max_fit
  // 0..1: how much of the lift applies at a clip frame (fractional frames blend).
  float weight(float frame) const;
};

// The fit of `target`'s clip (swept) to an obstacle of this type and size (scenario.h: size.y the underside
// of a bar or beam, the top of a hurdle; size.z its depth), met at the target's reach.
ObstacleFit fit_obstacle(const ClipSweep& sweep, const TargetMotion& target, ObjectType type, glm::vec3 size);

}  // namespace prep
