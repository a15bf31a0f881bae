// The clip viewer's input: keys (from the window or a --script) change the camera and the clip player.
#include <doctest/doctest.h>

#include <GLFW/glfw3.h>

#include "app/demo/clip_viewer_app.h"
#include "tests/render/test_scene.h"

using namespace prep;

TEST_CASE("keys orbit the camera, pause, step frames and switch clips") {
  demo::DemoMotions motions;
  motions.source = "test";
  Clip a = test::standing_clip(glm::vec3(0.0f));
  a.frames.resize(10, a.frames[0]);
  Clip b = a;
  b.name = "second";
  motions.clips.push_back({a, std::nullopt, -1});
  motions.clips.push_back({b, std::nullopt, -1});
  render::OsMesaContext context(320, 240);
  demo::ClipViewerApp app(context, motions, nullptr);

  const float yaw = app.camera.yaw;
  app.on_key(GLFW_KEY_E);
  CHECK(app.camera.yaw > yaw);
  app.on_key(GLFW_KEY_Q);
  CHECK(app.camera.yaw == doctest::Approx(yaw));
  const float distance = app.camera.distance;
  app.on_key(GLFW_KEY_Z);
  CHECK(app.camera.distance < distance);

  CHECK(app.player.playing);
  app.on_key(GLFW_KEY_SPACE);
  CHECK_FALSE(app.player.playing);
  app.player.time = 0.0f;
  app.on_key(GLFW_KEY_RIGHT);
  CHECK(app.player.time == doctest::Approx(1.0f / a.fps));
  app.frame(0.5f);  // paused: time stays
  CHECK(app.player.time == doctest::Approx(1.0f / a.fps));

  app.on_key(GLFW_KEY_DOWN);
  CHECK(app.player.clip == 1);
  app.on_key(GLFW_KEY_DOWN);  // clamped at the last clip
  CHECK(app.player.clip == 1);
  app.on_key(GLFW_KEY_ESCAPE);
  CHECK(app.quit_requested);
}

TEST_CASE("the clip player loops or clamps") {
  demo::DemoMotions motions;
  Clip a = test::standing_clip(glm::vec3(0.0f));
  a.frames.resize(31, a.frames[0]);  // 1 s at 30 fps
  motions.clips.push_back({a, std::nullopt, -1});
  demo::ClipPlayer player;
  player.advance(motions, 1.25f);
  CHECK(player.time == doctest::Approx(0.25f));
  player.loop = false;
  player.advance(motions, 2.0f);
  CHECK(player.time == doctest::Approx(1.0f));
}
