// The crowd demo drawn headless: every lane's character where the engine has it, the nearest in view as
// skinned bodies and the rest as light ones.
#include "app/demo/crowd_app.h"

#include <doctest/doctest.h>

#include <algorithm>
#include <filesystem>

#include "app/demo/crowd_run.h"
#include "app/render/gl_context.h"
#include "app/render/image.h"
#include "app/render/palette.h"
#include "tests/render/pixels.h"
#include "tests/support/paths.h"

using namespace prep;
using render::palette::PixelClass;

TEST_CASE("crowd demo: each character in view shows at its pelvis, the nearest four skinned, the others light") {
  demo::CrowdRunOptions o;
  o.scenario = test::repo() + "/assets/scenarios/stadium.json";
  o.lanes = 30;
  o.cache_dir = test::tmp_dir() + "/policy-cache";
  std::unique_ptr<Crowd> crowd = demo::make_crowd(o);
  render::OsMesaContext context(960, 540);
  demo::CrowdApp app(context, *crowd, nullptr);
  app.show_panel = false;
  const float dt = 1.0f / 60.0f;
  for (int f = 0; f < 240; ++f) app.skip_frame(dt);  // 4 s: walking up to the hurdles, preparing
  for (int f = 0; f < 3; ++f) app.frame(dt);
  const render::Image image = context.read_pixels();
  std::filesystem::create_directories(test::tmp_dir());
  render::write_png(image, test::tmp_dir() + "/crowd.png");  // for a look by eye

  const glm::mat4 vp = app.camera.view_projection(960.0f / 540.0f);
  const glm::vec3 eye = app.camera.eye();
  const render::Scene& scene = app.scene();
  REQUIRE(scene.characters.size() == 30);
  int in_view = 0, shown = 0, detailed = 0;
  float farthest_detailed = 0.0f, nearest_light_in_view = 1e9f;
  for (const render::SceneCharacter& c : scene.characters) {
    const glm::vec3 pelvis = c.joint_positions[0];
    glm::vec2 px;
    const bool visible = render::project_to_pixel(vp, pelvis, image.width, image.height, px) && test::in_image(image, px);
    const float distance = glm::length(pelvis - eye);
    if (!c.light) {
      ++detailed;
      farthest_detailed = std::max(farthest_detailed, distance);
    } else if (visible) {
      nearest_light_in_view = std::min(nearest_light_in_view, distance);
    }
    if (!visible) continue;
    ++in_view;
    shown += test::class_near(image, px, 3, PixelClass::Character);
  }
  CHECK(in_view >= 15);
  // A character may stand behind a nearer one or a hurdle: nearly all show.
  CHECK(shown * 10 >= in_view * 9);
  CHECK(detailed == demo::CrowdApp::kDetailedBodies);
  CHECK(farthest_detailed <= nearest_light_in_view);
}
