// The demo on a folder of takes: the scan's manifest and a course fitted to the set, played, with the
// Motion capture panel saying what the set lacks and what the course lost.
#include "app/demo/motion_folder.h"

#include <doctest/doctest.h>

#include <filesystem>

#include "app/demo/demo_app.h"
#include "app/demo/headless.h"
#include "app/demo/world_session.h"
#include "app/render/gl_context.h"
#include "engine/world/world.h"
#include "tests/support/paths.h"

using namespace prep;

TEST_CASE("demo on a folder of takes: cmu31 plays the obstacle course without the bar it cannot crawl, and says so") {
  const std::string cache = test::tmp_dir() + "/policy-cache";
  const auto folder = demo::open_motion_folder(test::mocap() + "/cmu31", test::repo() + "/assets/scenarios/obstacles.json", cache);
  CHECK(std::filesystem::exists(folder->manifest));
  const Scenario course = load_scenario(folder->scenario);
  CHECK(course.motions == folder->manifest);
  // The bar is left out (the recorded crawl goes down onto the hands and passes under no bar of 0.55 m or
  // more); the beam and the hurdle stay.
  REQUIRE(course.objects.size() == 2);
  CHECK(course.objects[0].type == ObjectType::Beam);
  CHECK(course.objects[1].type == ObjectType::Hurdle);
  REQUIRE_FALSE(folder->changes.empty());
  CHECK(folder->changes.front().find("left out the bar") == 0);

  demo::SessionOptions options;
  options.cache_dir = cache;
  options.background = false;
  demo::WorldSession session(options);
  session.open(folder->scenario);
  render::OsMesaContext context(1280, 720);
  demo::DemoApp app(context, session, nullptr);
  app.motion_folder = folder;
  for (int frame = 0; frame < 30 * 30 && session.world()->launches().size() < 2; ++frame) app.skip_frame(1.0f / 30.0f);
  const auto& launches = session.world()->launches();
  REQUIRE(launches.size() == 2);
  CHECK(launches[0].action == TargetAction::Duck);
  CHECK(launches[1].action == TargetAction::Jump);
  for (const auto& l : launches) CHECK(l.alpha_at_launch >= 0.85f);

  for (int i = 0; i < demo::kSettleFrames; ++i) app.frame(0.0f);
  REQUIRE(app.panel_rects().count("Motion capture") == 1);
  const glm::vec4 panel = app.panel_rects().at("Motion capture");
  const glm::vec4 plots = app.panel_rects().at("Plots");
  CHECK(panel.x == doctest::Approx(plots.x));  // in the right column, below the plots
  CHECK(panel.y >= plots.y + plots.w);
  CHECK(panel.y + panel.w <= 720.0f);
}
