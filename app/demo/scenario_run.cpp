#include "app/demo/scenario_run.h"

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <unistd.h>

#include "app/render/camera.h"
#include "app/render/gl_context.h"
#include "app/render/image.h"
#include "app/render/palette.h"
#include "app/render/renderer.h"
#include "engine/world/policy_cache.h"

namespace prep::demo {

render::Scene to_render_scene(const WorldScene& world) {
  render::Scene s;
  for (const WorldScene::Character& c : world.characters) {
    render::SceneCharacter rc = render::make_scene_character(
        c.skeleton, *c.pose, c.user ? render::palette::kCharacter : render::palette::kOtherCharacter);
    rc.is_source = c.is_source;
    s.characters.push_back(std::move(rc));
  }
  for (const WorldScene::Object& o : world.objects) {
    render::SceneObject ro;
    switch (o.type) {
      case ObjectType::Ball: ro.type = render::ObjectType::Ball; break;
      case ObjectType::Bar: ro.type = render::ObjectType::Bar; break;
      case ObjectType::Beam: ro.type = render::ObjectType::Beam; break;
      case ObjectType::Hurdle: ro.type = render::ObjectType::Hurdle; break;
      case ObjectType::Opponent: continue;  // drawn as a character
    }
    ro.position = o.position;
    ro.heading = o.heading;
    ro.size = o.size;
    ro.is_source = o.is_source;
    s.objects.push_back(ro);
  }
  s.goal = world.goal;
  s.goal_radius = world.goal_radius;
  s.source = world.source;
  s.source_radius = world.source_radius;
  if (!world.characters.empty()) {
    const glm::vec3 root = world.characters.front().pose->root_position;
    for (const WorldScene::Character& c : world.characters)
      if (c.user) s.focus = glm::vec3(c.pose->root_position.x, 0.9f, c.pose->root_position.z);
    if (s.focus == glm::vec3(0.0f, 0.9f, 0.0f)) s.focus = glm::vec3(root.x, 0.9f, root.z);
  }
  return s;
}

int run_scenario_headless(const ScenarioRunOptions& o) {
  if (!(o.seconds > 0.0f)) throw std::invalid_argument("--seconds must be positive");
  const Scenario scenario = load_scenario(o.scenario);
  const Params params = o.params.empty() ? load_scenario_params(scenario) : load_params(o.params);
  const std::string cache = default_policy_cache_dir();
  bool trained = false;
  if (!o.json) std::cerr << "prep-demo: preparing the motion graph and the controller (policy cache " << cache << ")\n";
  const auto assets = prepare_world_assets(scenario, params, cache, &trained);
  World world(scenario, assets);

  const bool drawing = !o.screenshot.empty() || !o.frames_dir.empty() || !o.video.empty();
  std::unique_ptr<render::OsMesaContext> context;
  std::unique_ptr<render::Renderer> renderer;
  render::Camera camera;
  camera.yaw = 0.9f;
  camera.pitch = 0.28f;
  camera.distance = 6.0f;
  std::string frames_dir = o.frames_dir;
  if (!o.video.empty() && frames_dir.empty())
    frames_dir = (std::filesystem::temp_directory_path() / ("prep-frames-" + std::to_string(::getpid()))).string();
  if (drawing) {
    context = std::make_unique<render::OsMesaContext>(o.width, o.height);
    context->make_current();
    renderer = std::make_unique<render::Renderer>();
    if (!frames_dir.empty()) std::filesystem::create_directories(frames_dir);
  }
  const float dt = params.runtime.fixed_dt;
  const int ticks = static_cast<int>(std::lround(o.seconds / dt));
  const int frame_every = std::max(1, static_cast<int>(std::lround(1.0f / (30.0f * dt))));  // 30 frames/s
  int written = 0;
  auto draw = [&](bool first) {
    const render::Scene scene = to_render_scene(world.scene());
    if (first) camera.target = scene.focus;
    else camera.follow(scene.focus, dt * frame_every);
    renderer->draw(scene, camera, 0, 0, o.width, o.height);
    return context->read_pixels();
  };
  for (int k = 0; k < ticks; ++k) {
    world.step();
    if (drawing && !frames_dir.empty() && k % frame_every == 0) {
      char name[64];
      std::snprintf(name, sizeof name, "/frame_%05d.png", written++);
      render::write_png(draw(k == 0), frames_dir + name);
    }
  }
  if (!o.screenshot.empty()) render::write_png(draw(written == 0), o.screenshot);
  if (!o.video.empty()) {
    const std::string command = "ffmpeg -loglevel error -y -framerate 30 -i '" + frames_dir +
                                "/frame_%05d.png' -pix_fmt yuv420p '" + o.video + "'";
    if (std::system("command -v ffmpeg > /dev/null 2>&1") != 0) {
      std::cerr << "prep-demo: ffmpeg is not installed; the frames are in " << frames_dir << "\n";
    } else if (std::system(command.c_str()) != 0) {
      std::cerr << "prep-demo: ffmpeg failed; the frames are in " << frames_dir << "\n";
    } else if (o.frames_dir.empty()) {
      std::filesystem::remove_all(frames_dir);
    }
  }
  const RunSummary summary = summarize(world);
  if (o.json)
    std::cout << summary_json(summary, world) << "\n";
  else
    std::cout << summary_text(summary);
  return 0;
}

}  // namespace prep::demo
