#include "app/demo/clip_view.h"

#include <algorithm>
#include <cmath>

#include "app/render/palette.h"
#include "engine/motion/kinematics.h"

namespace prep::demo {

void ClipPlayer::select(const DemoMotions& motions, int index) {
  if (motions.clips.empty()) return;
  clip = std::clamp(index, 0, static_cast<int>(motions.clips.size()) - 1);
  time = 0.0f;
}

void ClipPlayer::advance(const DemoMotions& motions, float dt) {
  if (motions.clips.empty()) return;
  const float duration = motions.clips[clip].clip.duration();
  if (playing) time += dt * speed;
  if (duration <= 0.0f) {
    time = 0.0f;
  } else if (loop) {
    time = std::fmod(time, duration);
    if (time < 0.0f) time += duration;
  } else {
    time = std::clamp(time, 0.0f, duration);
  }
}

namespace {

// Unit horizontal direction the clip travels in (first to last root), or the root's initial forward
// axis for clips that stay in place (idle, punches).
glm::vec3 travel_direction(const Clip& clip) {
  if (clip.frames.empty()) return {0, 0, 1};
  glm::vec3 d = clip.frames.back().root_position - clip.frames.front().root_position;
  d.y = 0.0f;
  if (glm::length(d) > 0.3f) return glm::normalize(d);
  const float h = heading_of(clip.frames.front().rotations[0]);
  return {std::sin(h), 0.0f, std::cos(h)};
}

}  // namespace

std::vector<render::SceneObject> clip_props(const DemoClip& c) {
  std::vector<render::SceneObject> props;
  if (!c.role || c.clip.frames.empty()) return props;
  const Role role = *c.role;
  if (role != Role::Crawl && role != Role::Duck && role != Role::Jump && role != Role::Kick) return props;
  const Skeleton& skeleton = *c.clip.skeleton;
  const glm::vec3 dir = travel_direction(c.clip);
  const float heading = std::atan2(dir.x, dir.z);
  const int head = render::head_joint(skeleton);
  // Where the clip meets its obstacle: crawl and duck pass under it where the head is lowest, the jump
  // crosses it where the root is highest; the kick strikes the ball where the feet move fastest.
  std::vector<glm::vec3> world, previous;
  float best = -1e9f;
  glm::vec3 where(0.0f);
  for (int f = 0; f < c.clip.frame_count(); ++f) {
    forward_kinematics(skeleton, c.clip.frames[f], world);
    float score = 0.0f;
    glm::vec3 point = world[0];
    if (role == Role::Crawl || role == Role::Duck) {
      score = -world[head].y;
    } else if (role == Role::Jump) {
      score = world[0].y;
    } else if (!previous.empty()) {  // kick: fastest leaf joint below the knees
      score = -1e9f;
      for (int j = 0; j < skeleton.size(); ++j)
        if (world[j].y < 0.35f && glm::length(world[j] - previous[j]) > score) {
          score = glm::length(world[j] - previous[j]);
          point = world[j];
        }
    } else {
      score = -1e9f;
    }
    if (score > best) best = score, where = point;
    previous = world;
  }
  render::SceneObject o;
  o.position = glm::vec3(where.x, 0.0f, where.z);
  o.heading = heading;
  switch (role) {
    case Role::Crawl: o.type = render::ObjectType::Bar, o.size = {kObstacleWidth, kBarClearance, 0.08f}; break;
    case Role::Duck: o.type = render::ObjectType::Beam, o.size = {kObstacleWidth, kBeamClearance, 0.12f}; break;
    case Role::Jump: o.type = render::ObjectType::Hurdle, o.size = {kObstacleWidth, kHurdleHeight, 0.03f}; break;
    default:
      o.type = render::ObjectType::Ball, o.size = glm::vec3(kBallDiameter);
      o.position += dir * (0.5f * kBallDiameter);  // just ahead of the striking foot
      break;
  }
  props.push_back(o);
  return props;
}

render::Scene clip_scene(const DemoClip& c, float t, bool with_props) {
  render::Scene scene;
  if (c.clip.frames.empty()) return scene;
  scene.characters.push_back(render::make_scene_character(c.clip.skeleton, c.clip.sample(t), render::palette::kCharacter));
  scene.focus = scene.characters[0].joint_positions[0];
  if (with_props) scene.objects = clip_props(c);
  return scene;
}

render::Camera strip_camera(const DemoClip& c) {
  render::Camera camera;
  camera.orthographic = true;
  float top = 1.0f;
  std::vector<glm::vec3> world;
  for (const Pose& pose : c.clip.frames) {
    forward_kinematics(*c.clip.skeleton, pose, world);
    for (const glm::vec3& p : world) top = std::max(top, p.y);
  }
  const float margin = 0.25f;  // m below the floor line, and above the head with the tile's caption
  const float head = 0.15f;    // m: the top of the head above its highest joint (the skull's end site is not a joint)
  camera.ortho_height = top + head + 2.0f * margin;
  const glm::vec3 forward = travel_direction(c.clip);
  const glm::vec3 right(-forward.z, 0.0f, forward.x);
  camera.yaw = std::atan2(right.x, right.z);
  camera.pitch = 0.12f;
  camera.distance = 8.0f;
  camera.target = glm::vec3(0.0f, 0.5f * camera.ortho_height - margin, 0.0f);
  return camera;
}

}  // namespace prep::demo
