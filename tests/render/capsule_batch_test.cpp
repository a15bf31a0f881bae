// Light bodies drawn many capsules to an instance (app/render/capsule_batch.h): every capsule shows where
// its body is, in the full instances and in the part-mesh draw of the rest alike.
#include "app/render/capsule_batch.h"

#include <doctest/doctest.h>

#include "app/render/camera.h"
#include "app/render/gl_context.h"
#include "app/render/image.h"
#include "app/render/palette.h"
#include "app/render/renderer.h"
#include "engine/motion/body_volumes.h"
#include "tests/render/pixels.h"
#include "tests/render/test_scene.h"

using namespace prep;
using namespace prep::render;
using render::palette::PixelClass;

TEST_CASE("light bodies, many capsules to an instance: each capsule of each body shows at its middle") {
  const std::shared_ptr<const Skeleton> skeleton = test::stick_skeleton();
  const BodyVolumes volumes(*skeleton);
  const int per_body = static_cast<int>(volumes.capsules().size());
  // Enough bodies for two full instances and a part-mesh rest, none a multiple of the copies.
  const int bodies = 2 * CapsuleBatches::kCopies / per_body + 2;
  REQUIRE(bodies * per_body > 2 * CapsuleBatches::kCopies);
  REQUIRE((bodies * per_body) % CapsuleBatches::kCopies != 0);
  Scene scene;
  for (int i = 0; i < bodies; ++i) {
    const float x = 0.9f * (static_cast<float>(i) - 0.5f * static_cast<float>(bodies - 1));
    SceneCharacter c = make_scene_character(skeleton, test::standing_clip({x, 0.0f, 0.0f}).frames[0], palette::kOtherCharacter);
    c.light = true;
    scene.characters.push_back(c);
  }
  scene.focus = {0.0f, 1.0f, 0.0f};
  Camera camera;
  camera.target = {0.0f, 1.0f, 0.0f};
  camera.yaw = 0.0f;
  camera.pitch = 0.0f;
  camera.distance = 0.5f * 0.9f * static_cast<float>(bodies) / std::tan(0.5f * camera.fov_y) / (1280.0f / 720.0f) + 1.5f;
  OsMesaContext context(1280, 720);
  Renderer renderer;
  renderer.draw(scene, camera, 0, 0, 1280, 720);
  const Image image = context.read_pixels();
  CHECK(renderer.triangles_last_frame() >= bodies * per_body * 24);
  const glm::mat4 vp = camera.view_projection(1280.0f / 720.0f);
  std::vector<PlacedCapsule> placed;
  int shown = 0, capsules = 0;
  for (const SceneCharacter& c : scene.characters) {
    volumes.place(c.joint_positions, c.joint_rotations, placed);
    for (const PlacedCapsule& p : placed) {
      ++capsules;
      shown += test::class_of_point(image, vp, 0.5f * (p.a + p.b)) == PixelClass::OtherCharacter;
    }
  }
  CHECK(capsules == bodies * per_body);
  CHECK(shown == capsules);
}
