// Headless screenshots: the character's pixels are where the camera matrices put its root and head,
// the floor and the sky are where expected, obstacles, ball, goal and source show in their own colours,
// and the ImGui panels are drawn into the image.
#include <doctest/doctest.h>

#include <filesystem>
#include <set>

#include "app/demo/clip_viewer_app.h"
#include "app/demo/headless.h"
#include "app/render/gl_context.h"
#include "app/render/palette.h"
#include "app/render/renderer.h"
#include "engine/motion/kinematics.h"
#include "tests/render/test_scene.h"
#include "tests/support/paths.h"

using namespace prep;
using namespace prep::render;
using palette::PixelClass;

namespace {

PixelClass class_at(const Image& image, const glm::vec2& p) {
  const int x = static_cast<int>(p.x), y = static_cast<int>(p.y);
  REQUIRE(x >= 0);
  REQUIRE(y >= 0);
  REQUIRE(x < image.width);
  REQUIRE(y < image.height);
  const std::uint8_t* c = image.pixel(x, y);
  return palette::classify(c[0], c[1], c[2]);
}

PixelClass class_of_point(const Image& image, const glm::mat4& view_proj, const glm::vec3& world) {
  glm::vec2 pixel;
  REQUIRE(project_to_pixel(view_proj, world, image.width, image.height, pixel));
  return class_at(image, pixel);
}

bool inside_any(const std::map<std::string, glm::vec4>& rects, const glm::vec2& p) {
  for (const auto& [name, r] : rects)
    if (p.x >= r.x && p.y >= r.y && p.x < r.x + r.z && p.y < r.y + r.w) return true;
  return false;
}

}  // namespace

TEST_CASE("palette colours classify as themselves") {
  auto cls = [](const glm::vec3& c, float light) {
    return palette::classify(int(c.r * light * 255), int(c.g * light * 255), int(c.b * light * 255));
  };
  for (float light : {0.45f, 0.8f, 1.0f}) {  // in shadow, half lit, fully lit
    CHECK(cls(palette::kCharacter, light) == PixelClass::Character);
    CHECK(cls(palette::kOtherCharacter, light) == PixelClass::OtherCharacter);
    CHECK(cls(palette::kObstacle, light) == PixelClass::Obstacle);
    CHECK(cls(palette::kBall, light) == PixelClass::Ball);
    CHECK(cls(palette::kGoal, light) == PixelClass::Goal);
    CHECK(cls(palette::kSource, light) == PixelClass::Source);
    CHECK(cls(palette::kGround, light) == PixelClass::Ground);
    CHECK(cls(palette::kClearance, light) == PixelClass::Clearance);
  }
  CHECK(cls(palette::kSky, 1.0f) == PixelClass::Sky);
}

TEST_CASE("headless demo frame: character at its projected root and head, floor, sky and panels") {
  const glm::vec3 at(0.6f, 0.0f, -0.4f);
  demo::DemoMotions motions;
  motions.source = "test";
  motions.clips.push_back({test::standing_clip(at), std::nullopt, -1});
  OsMesaContext context(1280, 720);  // the demo's default size: its panels leave the centre clear
  demo::ClipViewerApp app(context, motions, nullptr);
  app.player.playing = false;
  app.follow = false;
  app.camera = demo::default_camera(demo::clip_scene(motions.clips[0], 0.0f, false));
  for (int i = 0; i < demo::kSettleFrames; ++i) app.frame(1.0f / 60.0f);
  const Image image = context.read_pixels();
  std::filesystem::create_directories(test::tmp_dir());
  write_png(image, test::tmp_dir() + "/render_demo_frame.png");  // for a look by eye
  REQUIRE(image.width == 1280);
  REQUIRE(image.height == 720);

  // Not blank: sky, ground and character all appear, and many distinct colours.
  std::map<PixelClass, int> counts;
  std::set<std::uint32_t> colours;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      const std::uint8_t* c = image.pixel(x, y);
      counts[palette::classify(c[0], c[1], c[2])]++;
      colours.insert(c[0] << 16 | c[1] << 8 | c[2]);
    }
  CHECK(counts[PixelClass::Sky] > 1000);
  CHECK(counts[PixelClass::Ground] > 10000);
  CHECK(counts[PixelClass::Character] > 500);
  CHECK(colours.size() > 200);

  // The character where the engine's pose puts it: project its root and head joints.
  const glm::mat4 vp = app.last_view_projection();
  const SceneCharacter& character = app.scene().characters.at(0);
  const glm::vec3 root = character.joint_positions[0];
  const glm::vec3 head = character.joint_positions[head_joint(*character.skeleton)];
  CHECK(root.x == doctest::Approx(at.x));
  CHECK(class_of_point(image, vp, root) == PixelClass::Character);
  CHECK(class_of_point(image, vp, head) == PixelClass::Character);
  // Beside it (a metre to its side, on the floor) is the floor; far above the horizon is the sky.
  CHECK(class_of_point(image, vp, at + glm::vec3(-1.0f, 0.0f, 1.0f)) == PixelClass::Ground);
  glm::vec3 away = app.camera.target - app.camera.eye();
  away.y = 0.0f;
  const glm::vec3 high_and_far = app.camera.eye() + 40.0f * glm::normalize(away) + glm::vec3(0.0f, 1.0f, 0.0f);
  CHECK(class_of_point(image, vp, high_and_far) == PixelClass::Sky);

  // The panels: ImGui's dark window background fills most of each panel's rectangle.
  const auto rects = app.panel_rects();
  REQUIRE(rects.count("Clip player") == 1);
  REQUIRE(rects.count("Timings") == 1);
  for (const auto& entry : rects) {
    const std::string& name = entry.first;  // not a structured binding: CAPTURE's lambda captures it
    const glm::vec4& r = entry.second;
    CAPTURE(name);
    CHECK(r.z > 100.0f);
    CHECK(r.w > 50.0f);
    int dark = 0, total = 0;
    for (int y = int(r.y) + 2; y < int(r.y + r.w) - 2 && y < image.height; ++y)
      for (int x = int(r.x) + 2; x < int(r.x + r.z) - 2 && x < image.width; ++x) {
        const std::uint8_t* c = image.pixel(x, y);
        dark += palette::classify(c[0], c[1], c[2]) == PixelClass::Dark;
        ++total;
      }
    REQUIRE(total > 0);
    CHECK(dark > total / 2);
  }
  // The character is not hidden under a panel (the test's camera keeps it in the clear).
  glm::vec2 root_px;
  REQUIRE(project_to_pixel(vp, root, image.width, image.height, root_px));
  CHECK_FALSE(inside_any(rects, root_px));

  // Without panels the same rectangle shows the scene.
  app.show_panels = false;
  app.frame(0.0f);
  const Image bare = context.read_pixels();
  const glm::vec4 r = rects.at("Clip player");
  const std::uint8_t* c = bare.pixel(int(r.x + r.z / 2), int(r.y + r.w / 2));
  CHECK(palette::classify(c[0], c[1], c[2]) != PixelClass::Dark);
}

TEST_CASE("obstacles, ball, goal and source of influence appear where they stand, in their colours") {
  OsMesaContext context(800, 600);
  Renderer renderer;
  Scene scene;
  SceneObject bar;
  bar.type = render::ObjectType::Bar;
  bar.position = {-1.5f, 0.0f, 0.0f};
  bar.size = {1.2f, 0.65f, 0.10f};
  SceneObject hurdle;
  hurdle.type = render::ObjectType::Hurdle;
  hurdle.position = {1.5f, 0.0f, 0.0f};
  hurdle.size = {1.2f, 0.4f, 0.03f};
  SceneObject ball;
  ball.type = render::ObjectType::Ball;
  ball.position = {0.0f, 0.0f, 1.0f};
  ball.size = glm::vec3(0.3f);
  ball.is_source = true;
  scene.objects = {bar, hurdle, ball};
  scene.goal = {glm::vec3(0.0f, 0.0f, -1.5f)};
  scene.source = ball.position;
  scene.focus = {0.0f, 0.5f, 0.0f};
  Camera camera;
  camera.target = {0.0f, 0.4f, 0.0f};
  camera.yaw = 0.0f;  // looking along -Z from +Z
  camera.pitch = 0.5f;
  camera.distance = 6.0f;
  renderer.draw(scene, camera, 0, 0, 800, 600);
  const Image image = context.read_pixels();
  const glm::mat4 vp = camera.view_projection(800.0f / 600.0f);
  std::filesystem::create_directories(test::tmp_dir());
  write_png(image, test::tmp_dir() + "/render_objects.png");  // for a look by eye

  CHECK(class_of_point(image, vp, {-1.5f, 0.65f + 0.05f, 0.0f}) == PixelClass::Obstacle);  // the bar, mid-span
  CHECK(class_of_point(image, vp, {1.5f, 0.4f - 0.06f, 0.0f}) == PixelClass::Obstacle);    // the hurdle's board
  CHECK(class_of_point(image, vp, {-1.5f, 0.3f, 0.0f}) == PixelClass::Ground);             // under the bar: floor
  CHECK(class_of_point(image, vp, {0.0f, 0.15f, 1.0f}) == PixelClass::Ball);                // the ball's centre
  // The goal ring (radius goal_radius) and the source ring (radius source_radius) on the floor.
  CHECK(class_of_point(image, vp, {scene.goal_radius * 0.9f, 0.0f, -1.5f}) == PixelClass::Goal);
  CHECK(class_of_point(image, vp, {-scene.source_radius * 0.92f, 0.0f, 1.0f}) == PixelClass::Source);
  // Inside the goal ring (between the centre dot and the ring) the floor shows through.
  CHECK(class_of_point(image, vp, {scene.goal_radius * 0.45f, 0.0f, -1.5f}) == PixelClass::Ground);
}

TEST_CASE("scene primitives: one capsule per bone and End Site, the head whole, boxes per obstacle part") {
  const Clip clip = test::standing_clip(glm::vec3(0.0f));
  const SceneCharacter c = make_scene_character(clip.skeleton, clip.frames[0], palette::kCharacter);
  std::vector<CapsuleInstance> capsules;
  append_character_capsules(c, BodyVolumes(*clip.skeleton), capsules);
  // Bones: every joint but the root has one; End Sites of the feet and hands add 4; the head's End Site
  // is replaced by the head capsule, so: (joints - 1) + 4 + 1.
  CHECK(capsules.size() == static_cast<size_t>(clip.skeleton->size() - 1 + 4 + 1));
  for (const CapsuleInstance& k : capsules) {
    CHECK(k.a_radius.w > 0.0f);
    CHECK(k.colour == palette::kCharacter);
  }
  ScenePrimitives prims;
  SceneObject bar;
  bar.type = render::ObjectType::Bar;
  bar.size = {1.2f, 0.65f, 0.08f};
  append_object_primitives(bar, prims);
  REQUIRE(prims.boxes.size() == 3);  // two posts and the bar
  // The bar's underside is at the clearance height.
  const glm::mat4& m = prims.boxes[2].model;
  const float underside = (m * glm::vec4(0.0f, -0.5f, 0.0f, 1.0f)).y;
  CHECK(underside == doctest::Approx(0.65f));
}
