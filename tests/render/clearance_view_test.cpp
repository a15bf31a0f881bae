// The clearance view in pixels: a body pushed into an obstacle shows red where the capsules that went in
// are, and nowhere else; with nothing flagged (or the view off) there is no red at all. First the renderer
// alone on a pose made to overlap a bar, then the demo on a scenario whose beam runs through the body.
#include <doctest/doctest.h>

#include <GLFW/glfw3.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <limits>

#include "app/demo/demo_app.h"
#include "app/demo/headless.h"
#include "app/demo/world_session.h"
#include "app/render/gl_context.h"
#include "app/render/renderer.h"
#include "engine/library/builtin.h"
#include "engine/world/clearance.h"
#include "tests/render/pixels.h"
#include "tests/support/paths.h"

using namespace prep;
using render::palette::PixelClass;

namespace {

// Where on the screen a set of capsules can show: the pixel box around their projected ends, grown by the
// largest projected radius (the radius seen at the nearest end, which is larger than at the far one).
struct ScreenBox {
  glm::vec2 lo{std::numeric_limits<float>::max()}, hi{std::numeric_limits<float>::lowest()};
  bool contains(glm::vec2 p, float margin) const {
    return p.x >= lo.x - margin && p.y >= lo.y - margin && p.x <= hi.x + margin && p.y <= hi.y + margin;
  }
};

ScreenBox screen_box(const std::vector<PlacedCapsule>& capsules, const glm::mat4& vp, int width, int height) {
  ScreenBox box;
  for (const PlacedCapsule& c : capsules)
    for (const glm::vec3& end : {c.a, c.b}) {
      glm::vec2 centre, side;
      REQUIRE(render::project_to_pixel(vp, end, width, height, centre));
      float r = 0.0f;  // the radius on screen: the farthest of six points on the sphere around this end
      for (const glm::vec3& d : {glm::vec3(1, 0, 0), glm::vec3(0, 1, 0), glm::vec3(0, 0, 1)})
        for (float sign : {-1.0f, 1.0f})
          if (render::project_to_pixel(vp, end + sign * c.radius * d, width, height, side)) r = std::max(r, glm::length(side - centre));
      box.lo = glm::min(box.lo, centre - glm::vec2(r));
      box.hi = glm::max(box.hi, centre + glm::vec2(r));
    }
  return box;
}

// Every pixel of the clearance colour.
std::vector<glm::vec2> red_pixels(const render::Image& image) {
  std::vector<glm::vec2> out;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      const std::uint8_t* c = image.pixel(x, y);
      if (render::palette::classify(c[0], c[1], c[2]) == PixelClass::Clearance) out.emplace_back(x, y);
    }
  return out;
}

// The capsules of a body deeper than the tolerance in an object's solids, found with the engine's own
// pieces (object frame, segment-to-box distance), as ClearanceMeter::measure does for a world.
std::vector<int> deep_in(const std::vector<PlacedCapsule>& capsules, const render::SceneObject& o, prep::ObjectType type) {
  std::vector<int> out;
  const std::vector<ObjectSolid> solids = object_solids(type, o.size);
  for (size_t k = 0; k < capsules.size(); ++k) {
    const glm::vec3 a = to_object_frame(capsules[k].a, {o.position.x, o.position.z}, o.heading);
    const glm::vec3 b = to_object_frame(capsules[k].b, {o.position.x, o.position.z}, o.heading);
    for (const ObjectSolid& s : solids)
      if (!s.sphere && segment_box_distance(a, b, s.centre, 0.5f * s.extents) - capsules[k].radius < -clearance_metric::kObjectTolerance) {
        out.push_back(static_cast<int>(k));
        break;
      }
  }
  return out;
}

}  // namespace

TEST_CASE("renderer: a body standing in a bar shows its flagged capsules in red, there only, and no red unflagged") {
  const auto skeleton = builtin_skeleton();
  Pose pose(skeleton->size());  // the T-pose, standing on the floor at the origin, facing +Z
  pose.root_position = {0.0f, skeleton->joints[0].offset.y, 0.0f};
  render::SceneCharacter character = render::make_scene_character(skeleton, pose, render::palette::kCharacter);
  // A bar whose rail runs through the trunk, halfway between the hips and the neck, below the arms.
  const float hips = character.joint_positions[0].y;
  float neck = hips;
  for (int j = 0; j < skeleton->size(); ++j)
    if (skeleton->joints[static_cast<size_t>(j)].name == "Neck") neck = character.joint_positions[static_cast<size_t>(j)].y;
  REQUIRE(neck > hips + 0.3f);
  render::SceneObject bar;
  bar.type = render::ObjectType::Bar;
  bar.size = {1.0f, 0.5f * (hips + neck), 0.1f};

  const BodyVolumes volumes(*skeleton);
  std::vector<PlacedCapsule> placed;
  volumes.place(character.joint_positions, character.joint_rotations, placed);
  const std::vector<int> deep = deep_in(placed, bar, prep::ObjectType::Bar);
  REQUIRE_FALSE(deep.empty());
  CHECK(deep.size() < placed.size() / 3);  // the trunk's middle, not the whole body
  std::vector<PlacedCapsule> deep_capsules;
  for (int k : deep) deep_capsules.push_back(placed[static_cast<size_t>(k)]);

  render::Camera camera;  // in front of the body, a little above the rail, looking at it
  camera.target = {0.0f, 0.5f * (hips + neck), 0.0f};
  camera.yaw = 0.5f;
  camera.pitch = 0.25f;
  camera.distance = 3.0f;
  const int width = 640, height = 480;
  const glm::mat4 vp = camera.view_projection(static_cast<float>(width) / height);
  render::OsMesaContext context(width, height);

  for (bool skinned : {true, false}) {
    CAPTURE(skinned);
    render::RenderSettings settings;
    settings.skinned_bodies = skinned;
    render::Renderer renderer(settings);
    auto draw = [&](const std::vector<int>& flagged) {
      render::Scene scene;
      character.flagged = flagged;
      scene.characters = {character};
      scene.objects = {bar};
      renderer.draw(scene, camera, 0, 0, width, height);
      return context.read_pixels();
    };
    const render::Image on = draw(deep);
    std::filesystem::create_directories(test::tmp_dir());
    render::write_png(on, test::tmp_dir() + (skinned ? "/clearance_view_skinned.png" : "/clearance_view_capsules.png"));
    // Red where each flagged capsule is: its middle, in front of the rail (which runs through its axis).
    for (const PlacedCapsule& c : deep_capsules) {
      const glm::vec3 front = 0.5f * (c.a + c.b) + glm::vec3(0.0f, 0.0f, 0.8f * c.radius);
      CHECK(test::class_near(on, test::pixel_of(on, vp, front), 2, PixelClass::Clearance));
    }
    // ... and nowhere else: every red pixel lies where the flagged capsules project.
    const std::vector<glm::vec2> red = red_pixels(on);
    CHECK(red.size() > 300);
    const ScreenBox box = screen_box(deep_capsules, vp, width, height);
    int outside = 0;
    for (const glm::vec2& p : red) outside += !box.contains(p, 2.0f);
    CHECK(outside == 0);
    // The body's other parts keep the body's colour: the head and a hand.
    CHECK(test::class_of_point(on, vp, placed.back().a) == PixelClass::Character);  // the head capsule
    // Nothing flagged: not a red pixel.
    CHECK(red_pixels(draw({})).empty());
  }
}

namespace {

// A beam whose rail runs through the standing character's chest (a world never walks a body into one, so
// the test puts it there): the body is in it from the first frame.
std::string beam_through_body_scenario() {
  const std::string path = test::tmp_dir() + "/clearance_beam_through_body.json";
  std::filesystem::create_directories(test::tmp_dir());
  std::ofstream(path) << R"({
  "name": "beam through the body", "description": "a beam 1.3 m high across the standing character",
  "auto": false, "motions": "builtin",
  "characters": [{"position": [0, 0], "heading": 0, "control": "user"}],
  "objects": [{"type": "beam", "action": "duck", "position": [0.0, 0.0], "heading": 0, "size": [5.0, 1.3, 0.1]}],
  "goal": [0.0, 6.0]
})";
  return path;
}

}  // namespace

TEST_CASE("demo: the clearance view (key O) draws the user's capsules that are in the beam in red, and its readout") {
  demo::SessionOptions options;
  options.cache_dir = test::tmp_dir() + "/policy-cache";  // shared with the other demo tests
  options.background = false;
  demo::WorldSession session(options);
  Params through;  // a world that lets the body into the beam, to be seen
  through.runtime.keep_clear = false;
  session.open(beam_through_body_scenario(), through);
  render::OsMesaContext context(1280, 720);
  demo::DemoApp app(context, session, nullptr);
  app.view.show_balance = false;  // its COM marker outside the support polygon is red too
  app.view.show_panels = false;
  const World& world = *session.world();
  const int user = world.user();

  // On until the body is a few centimetres into the beam (measured by a meter of the test's own).
  ClearanceMeter probe(*world.assets().set->skeleton);
  bool deep = false;
  for (int frame = 0; frame < 15 * 30 && !deep; ++frame) {
    app.skip_frame(1.0f / 30.0f);
    probe.measure(world);
    deep = probe.result()[static_cast<size_t>(user)].object.distance < -0.05f;
  }
  REQUIRE(deep);
  const std::vector<int> flagged = probe.result()[static_cast<size_t>(user)].penetrating;
  REQUIRE_FALSE(flagged.empty());

  CHECK_FALSE(app.view.show_clearance);
  app.on_key(GLFW_KEY_O);
  REQUIRE(app.view.show_clearance);
  for (int i = 0; i < demo::kSettleFrames; ++i) app.frame(0.0f);  // the same instant: the world does not move
  const render::Image on = context.read_pixels();
  render::write_png(on, test::tmp_dir() + "/clearance_demo_on.png");
  REQUIRE(app.clearance() != nullptr);
  CHECK(app.clearance()->result()[static_cast<size_t>(user)].penetrating == flagged);
  CHECK(app.scene().characters.at(static_cast<size_t>(user)).flagged == flagged);

  // The red is where the flagged capsules are drawn (the drawn pose: the renderer's volumes placed at it).
  const render::SceneCharacter& drawn = app.scene().characters.at(static_cast<size_t>(user));
  std::vector<PlacedCapsule> placed, flagged_capsules;
  BodyVolumes(*drawn.skeleton).place(drawn.joint_positions, drawn.joint_rotations, placed);
  for (int k : flagged) flagged_capsules.push_back(placed[static_cast<size_t>(k)]);
  const std::vector<glm::vec2> red = red_pixels(on);
  CHECK(red.size() > 100);
  const ScreenBox box = screen_box(flagged_capsules, app.last_view_projection(), on.width, on.height);
  int outside = 0;
  for (const glm::vec2& p : red) outside += !box.contains(p, 2.0f);
  CHECK(outside == 0);

  // Off again (the key): nothing measured, nothing flagged, not a red pixel.
  app.on_key(GLFW_KEY_O);
  app.frame(0.0f);
  CHECK(app.clearance() == nullptr);
  CHECK(app.scene().characters.at(static_cast<size_t>(user)).flagged.empty());
  CHECK(red_pixels(context.read_pixels()).empty());

  // The readout: a panel of its own while the view is on.
  app.view.show_panels = true;
  for (int i = 0; i < demo::kSettleFrames; ++i) app.frame(0.0f);
  CHECK(app.panel_rects().count("Clearance") == 0);
  app.view.show_clearance = true;
  for (int i = 0; i < demo::kSettleFrames; ++i) app.frame(0.0f);
  REQUIRE(app.panel_rects().count("Clearance") == 1);
  const glm::vec4 r = app.panel_rects().at("Clearance");
  CHECK(r.y + r.w <= 720.0f);
  for (const char* column : {"Preparation", "Timings", "Camera"}) {  // clear of the columns' panels
    CAPTURE(column);
    const glm::vec4 c = app.panel_rects().at(column);
    CHECK((r.x >= c.x + c.z || c.x >= r.x + r.z || r.y >= c.y + c.w || c.y >= r.y + r.w));
  }
}
