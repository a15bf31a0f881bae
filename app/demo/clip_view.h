// A clip on show: a player (time, play/pause, speed, loop) and the scene it makes, with the obstacle its
// role is about (crawl: a bar, duck: a beam, jump: a hurdle, kick: a ball) placed where the clip meets it,
// so that clearance can be judged by eye.
#pragma once

#include <vector>

#include "app/demo/motions.h"
#include "app/render/camera.h"
#include "app/render/scene.h"

namespace prep::demo {

// Obstacle sizes the built-in clips were made for: bar underside 0.65 m, beam underside 1.2 m, hurdle top 0.4 m, ball 0.22 m.
constexpr float kBarClearance = 0.65f;
constexpr float kBeamClearance = 1.2f;
constexpr float kHurdleHeight = 0.4f;
constexpr float kBallDiameter = 0.22f;
constexpr float kObstacleWidth = 1.4f;

struct ClipPlayer {
  int clip = 0;
  float time = 0.0f;     // s into the clip
  float speed = 1.0f;    // playback rate
  bool playing = true;
  bool loop = true;

  void advance(const DemoMotions& motions, float dt);
  void select(const DemoMotions& motions, int index);
};

// The prop for a clip's role, placed from the clip's own motion; none for roles without one.
std::vector<render::SceneObject> clip_props(const DemoClip& clip);

// The scene of clip `c` at time t (the character in palette::kCharacter, plus its props).
render::Scene clip_scene(const DemoClip& c, float t, bool with_props);

// A side view for strips: orthographic, from the character's right (travel goes left to right), tall
// enough for the highest point of the whole clip, so every tile has the same scale.
render::Camera strip_camera(const DemoClip& c);

}  // namespace prep::demo
