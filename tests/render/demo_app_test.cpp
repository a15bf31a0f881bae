// The demo on the three scenarios of Sec. 7.2, headless through OSMesa at the window's default size:
// the screenshots show the scene where the engine says it is (the user's root and head, the opponents,
// the obstacles and the ball, the source ring, the balance overlay) with the panels drawn around it; keys
// and clicks change the world the way the demo's help says.
#include <doctest/doctest.h>

#include <GLFW/glfw3.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <memory>
#include <set>

#include "app/demo/demo_app.h"
#include "app/demo/headless.h"
#include "app/demo/world_session.h"
#include "engine/motion/kinematics.h"
#include "tests/render/pixels.h"
#include "tests/support/paths.h"

using namespace prep;
using render::palette::PixelClass;

namespace {

demo::SessionOptions test_session_options() {
  demo::SessionOptions o;
  o.cache_dir = test::tmp_dir() + "/policy-cache";  // shared with the world tests: trained once per build tree
  o.background = false;
  return o;
}

// A scenario run `seconds` without drawing, then drawn for the settle frames (1/30 s each).
struct DemoRun {
  demo::WorldSession session{test_session_options()};
  render::OsMesaContext context{1280, 720};
  std::unique_ptr<demo::DemoApp> app;
  render::Image image;

  DemoRun(const std::string& name, float seconds) {
    session.open(test::repo() + "/assets/scenarios/" + name + ".json");
    app = std::make_unique<demo::DemoApp>(context, session, nullptr);
    const int ticks_before = static_cast<int>(std::lround(seconds * 30.0f));
    for (int i = 0; i < ticks_before; ++i) session.advance(1.0 / 30.0);
    for (int i = 0; i < demo::kSettleFrames; ++i) app->frame(1.0f / 30.0f);
    image = context.read_pixels();
    std::filesystem::create_directories(test::tmp_dir());
    render::write_png(image, test::tmp_dir() + "/demo_" + name + ".png");  // for a look by eye
  }
  const World& world() const { return *session.world(); }
  glm::mat4 vp() const { return app->last_view_projection(); }
};

// Joint positions of a character's pose as the engine has it (not the interpolated drawing).
std::vector<glm::vec3> joints_of(const World& world, int character) {
  std::vector<glm::vec3> p;
  forward_kinematics(*world.assets().set->skeleton, world.characters()[static_cast<size_t>(character)].pose, p);
  return p;
}

void check_not_blank(const render::Image& image) {
  std::map<PixelClass, int> counts;
  std::set<std::uint32_t> colours;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      const std::uint8_t* c = image.pixel(x, y);
      counts[render::palette::classify(c[0], c[1], c[2])]++;
      colours.insert(static_cast<std::uint32_t>(c[0] << 16 | c[1] << 8 | c[2]));
    }
  CHECK(counts[PixelClass::Sky] > 5000);
  CHECK(counts[PixelClass::Ground] > 50000);
  CHECK(counts[PixelClass::Character] > 400);
  CHECK(counts[PixelClass::Support] > 20);  // the support polygon under the feet (the overlay is on by default)
  CHECK(colours.size() > 500);
}

// The user's root and head show the user's colour, and neither is under a panel.
void check_user(const DemoRun& run) {
  const int user = run.world().user();
  const auto joints = joints_of(run.world(), user);
  const glm::vec3 root = joints[0], head = joints[static_cast<size_t>(render::head_joint(*run.world().assets().set->skeleton))];
  const glm::vec2 root_px = test::pixel_of(run.image, run.vp(), root), head_px = test::pixel_of(run.image, run.vp(), head);
  CHECK(test::class_at(run.image, root_px) == PixelClass::Character);
  CHECK(test::class_at(run.image, head_px) == PixelClass::Character);
  CHECK_FALSE(test::inside_any(run.app->panel_rects(), root_px));
  CHECK_FALSE(test::inside_any(run.app->panel_rects(), head_px));
}

// Each panel is drawn: drawn again at the same instant without panels, its rectangle changes almost
// everywhere (ImGui's window background is 94% opaque), and it is mostly dark.
void check_panels(DemoRun& run) {
  const auto rects = run.app->panel_rects();
  for (const char* name : {"Scenario", "Preparation", "Plots", "Timings", "Camera"}) {
    CAPTURE(name);
    REQUIRE(rects.count(name) == 1);
  }
  run.app->view.show_panels = false;
  run.app->frame(0.0f);  // dt 0: the world does not move
  const render::Image bare = run.context.read_pixels();
  run.app->view.show_panels = true;
  for (const auto& entry : rects) {
    const std::string& name = entry.first;  // not a structured binding: CAPTURE's lambda captures it
    const glm::vec4& r = entry.second;
    CAPTURE(name);
    CHECK(r.z > 200.0f);
    CHECK(r.w > 100.0f);
    int changed = 0, dark = 0, total = 0;
    for (int y = static_cast<int>(r.y) + 2; y < static_cast<int>(r.y + r.w) - 2 && y < run.image.height; ++y)
      for (int x = static_cast<int>(r.x) + 2; x < static_cast<int>(r.x + r.z) - 2 && x < run.image.width; ++x) {
        const std::uint8_t* a = run.image.pixel(x, y);
        const std::uint8_t* b = bare.pixel(x, y);
        changed += a[0] != b[0] || a[1] != b[1] || a[2] != b[2];
        dark += std::max({a[0], a[1], a[2]}) < 90;
        ++total;
      }
    REQUIRE(total > 0);
    CHECK(changed > total * 8 / 10);
    CHECK(dark > total / 2);
  }
}

// The source of influence's ring: most of its visible samples show the source colour.
void check_source_ring(const DemoRun& run) {
  const WorldScene ws = run.world().scene();
  REQUIRE(ws.source.has_value());
  int visible = 0, source = 0;
  for (int k = 0; k < 24; ++k) {
    const float a = 2.0f * 3.14159265f * k / 24.0f;
    const glm::vec3 p = *ws.source + 0.91f * ws.source_radius * glm::vec3(std::cos(a), 0.0f, std::sin(a));
    glm::vec2 px;
    if (!render::project_to_pixel(run.vp(), p, run.image.width, run.image.height, px) || !test::in_image(run.image, px) ||
        test::inside_any(run.app->panel_rects(), px))
      continue;
    ++visible;
    source += test::class_at(run.image, px) == PixelClass::Source;
  }
  CHECK(visible >= 8);
  CHECK(source * 2 >= visible);  // the rest hidden behind the obstacle or the character
}

}  // namespace

TEST_CASE("demo screenshot, obstacle course: the character, the obstacles where they stand, the source ring, the panels") {
  DemoRun run("obstacles", 2.5f);
  check_not_blank(run.image);
  check_user(run);
  // Every obstacle's top rail, sampled across its width, shows the obstacle colour where it is in view.
  for (const WorldObject& o : run.world().objects()) {
    CAPTURE(object_type_name(o.spec.type));
    const float top = o.spec.type == ObjectType::Hurdle ? o.spec.size.y - 0.05f : o.spec.size.y + 0.5f * o.spec.size.z;
    int visible = 0, obstacle = 0;
    for (float x = -0.45f; x <= 0.451f; x += 0.15f) {
      const glm::vec3 p = o.position + glm::vec3(x * o.spec.size.x, top, 0.0f);  // heading 0: spans X
      glm::vec2 px;
      if (!render::project_to_pixel(run.vp(), p, run.image.width, run.image.height, px) || !test::in_image(run.image, px) ||
          test::inside_any(run.app->panel_rects(), px))
        continue;
      ++visible;
      obstacle += test::class_at(run.image, px) == PixelClass::Obstacle;
    }
    CHECK(visible >= 3);
    CHECK(obstacle * 3 >= visible * 2);
  }
  // Between the bar's posts, under the bar, the floor shows (the bar is where it stands, not a wall).
  const WorldObject& bar = run.world().objects()[0];
  REQUIRE(bar.spec.type == ObjectType::Bar);
  CHECK(test::class_of_point(run.image, run.vp(), bar.position + glm::vec3(0.35f * bar.spec.size.x, 0.05f, 0.0f)) == PixelClass::Ground);
  // The bar is the source of influence: the user prepares to crawl.
  CHECK(run.world().characters()[0].source_object == 0);
  check_source_ring(run);
  check_panels(run);
}

TEST_CASE("demo screenshot, kick: the character and the ball (source and goal) where the engine has them") {
  DemoRun run("kick", 2.5f);
  check_not_blank(run.image);
  check_user(run);
  const WorldObject& ball = run.world().objects()[0];
  REQUIRE(ball.spec.type == ObjectType::Ball);
  const glm::vec2 ball_px = test::pixel_of(run.image, run.vp(), ball.position + glm::vec3(0.0f, 0.5f * ball.spec.size.x, 0.0f));
  CHECK(test::class_near(run.image, ball_px, 2, PixelClass::Ball));
  CHECK_FALSE(test::inside_any(run.app->panel_rects(), ball_px));
  check_source_ring(run);
  check_panels(run);
}

TEST_CASE("demo screenshot, fight: the user and the opponents where the engine has them") {
  DemoRun run("fight", 2.0f);
  check_not_blank(run.image);
  check_user(run);
  int opponents = 0;
  for (int i = 0; i < static_cast<int>(run.world().characters().size()); ++i) {
    if (i == run.world().user()) continue;
    ++opponents;
    const glm::vec2 px = test::pixel_of(run.image, run.vp(), joints_of(run.world(), i)[0]);
    CHECK(test::class_near(run.image, px, 2, PixelClass::OtherCharacter));
  }
  CHECK(opponents == 2);
  check_source_ring(run);
  check_panels(run);
}

TEST_CASE("demo keys: WASD held steer relative to the camera, digits launch, T toggles auto, P pauses") {
  DemoRun run("kick", 0.5f);
  demo::DemoApp& app = *run.app;
  demo::WorldSession& s = run.session;
  const auto user = [&]() -> const WorldCharacter& { return s.world()->characters()[static_cast<size_t>(s.world()->user())]; };
  const glm::vec3 f = app.view.camera.target - app.view.camera.eye();
  const glm::vec2 forward = glm::normalize(glm::vec2(f.x, f.z)), right(-forward.y, forward.x);
  // D held: the goal leads the character to the camera's right (away from the ball ahead); the character
  // turns that way (its turning motions, a gait cycle each, the first when the stride playing ends) and
  // walks on that way.
  app.on_key_state(GLFW_KEY_D, true);
  glm::vec2 before_last(0.0f);
  for (int i = 0; i < 100; ++i) {
    app.skip_frame(1.0f / 30.0f);
    if (i == 84) before_last = user().position;
  }
  glm::vec2 lead = s.goal() - user().position;
  CHECK(glm::length(lead) == doctest::Approx(demo::WorldSession::kSteerLead).epsilon(0.03));
  CHECK(glm::dot(glm::normalize(lead), right) > 0.99f);
  CHECK(glm::dot(glm::vec2(std::sin(user().heading), std::cos(user().heading)), right) > 0.7f);  // turned
  CHECK(glm::dot(user().position - before_last, right) > 0.1f);  // and walking that way
  // The world's goal is the one steered (the user's single waypoint).
  REQUIRE(user().goal.size() == 1);
  CHECK(glm::length(user().goal.front() - s.goal()) < 1e-5f);
  // W with it: the diagonal; a repeat of the press changes nothing.
  app.on_key_state(GLFW_KEY_W, true);
  app.on_key(GLFW_KEY_W);
  app.skip_frame(1.0f / 30.0f);
  lead = s.goal() - user().position;
  CHECK(glm::dot(glm::normalize(lead), glm::normalize(forward + right)) > 0.99f);
  // A against D cancels (W still steers forward); the arrow of a held key adds nothing.
  app.on_key_state(GLFW_KEY_A, true);
  app.on_key_state(GLFW_KEY_UP, true);
  app.skip_frame(1.0f / 30.0f);
  CHECK(glm::dot(glm::normalize(s.goal() - user().position), forward) > 0.99f);
  // All let go: the goal stays where it was last placed.
  for (int key : {GLFW_KEY_W, GLFW_KEY_A, GLFW_KEY_D, GLFW_KEY_UP}) app.on_key_state(key, false);
  app.skip_frame(1.0f / 30.0f);
  const glm::vec2 kept = s.goal();
  for (int i = 0; i < 10; ++i) app.skip_frame(1.0f / 30.0f);
  CHECK(s.goal() == kept);
  CHECK(s.steering() == glm::vec2(0.0f));

  const bool auto_on = s.auto_launch();
  app.on_key(GLFW_KEY_T);
  CHECK(s.auto_launch() == !auto_on);
  CHECK(s.world()->auto_launch() == !auto_on);

  const size_t launches = s.world()->launches().size();
  app.on_key(GLFW_KEY_1);  // kick
  REQUIRE(s.world()->launches().size() == launches + 1);
  CHECK(s.world()->launches().back().action == TargetAction::Kick);
  CHECK_FALSE(s.world()->launches().back().automatic);

  app.on_key(GLFW_KEY_P);
  const float t = s.world()->time();
  app.frame(0.5f);
  CHECK(s.world()->time() == t);  // paused: no ticks
  app.on_key(GLFW_KEY_PERIOD);  // one tick while paused
  CHECK(s.world()->time() == doctest::Approx(t + s.params().runtime.fixed_dt));
  app.on_key(GLFW_KEY_ESCAPE);
  CHECK(app.quit_requested);
  CHECK(app.closing_report().find("scenario kick") != std::string::npos);
}

TEST_CASE("demo mouse: a click on the floor sets the goal there, on an object makes it the source, a right click launches") {
  DemoRun run("obstacles", 0.5f);
  demo::DemoApp& app = *run.app;
  demo::WorldSession& s = run.session;
  // The floor point under a pixel is the goal (the ray from the camera meets the floor there; in front
  // of the bar: a click behind it, under the bar, would pick the bar).
  const glm::vec3 target(0.8f, 0.0f, 2.6f);
  app.on_click(test::pixel_of(run.image, run.vp(), target), false);
  CHECK(s.goal().x == doctest::Approx(target.x).epsilon(0.02));
  CHECK(s.goal().y == doctest::Approx(target.z).epsilon(0.02));

  // A click on the beam (index 1), though the bar is closer: the beam becomes the source of influence and
  // the goal lies 2 m beyond it.
  const WorldObject& beam = s.world()->objects()[1];
  REQUIRE(beam.spec.type == ObjectType::Beam);
  const glm::vec2 beam_px = test::pixel_of(run.image, run.vp(), beam.position + glm::vec3(0.3f, beam.spec.size.y + 0.1f, 0.0f));
  REQUIRE_FALSE(test::inside_any(app.panel_rects(), beam_px));
  app.on_click(beam_px, false);
  CHECK(s.world()->picked_source() == 1);
  s.step_once();
  const WorldCharacter& u = s.world()->characters()[0];
  CHECK(u.source_object == 1);
  CHECK(u.prepared_for == TargetAction::Duck);
  CHECK(s.goal().y == doctest::Approx(beam.position.z + 2.0f));
  CHECK(s.prepared_action() == TargetAction::Duck);

  const size_t launches = s.world()->launches().size();
  app.on_click(glm::vec2(640.0f, 400.0f), true);  // right click: the prepared action
  REQUIRE(s.world()->launches().size() == launches + 1);
  CHECK(s.world()->launches().back().action == TargetAction::Duck);
}
