// Culling before a pass (app/render/culling.h): a sphere is left out only when wholly outside the clip
// volume or beyond the fog, the bounding spheres hold their instances, and a frame drawn with culling is the
// frame drawn without it, pixel for pixel, with fewer triangles.
#include "app/render/culling.h"

#include <doctest/doctest.h>

#include <cmath>
#include <filesystem>
#include <random>

#include "app/render/camera.h"
#include "app/render/gl_context.h"
#include "app/render/image.h"
#include "app/render/renderer.h"
#include "tests/render/test_scene.h"
#include "tests/support/paths.h"

using namespace prep;

namespace {

render::Camera looking_down_minus_z() {
  render::Camera camera;
  camera.target = {0.0f, 1.0f, 0.0f};
  camera.yaw = 0.0f;  // from +Z toward -Z
  camera.pitch = 0.0f;
  camera.distance = 10.0f;
  return camera;
}

}  // namespace

TEST_CASE("clip volume: spheres wholly outside a plane or beyond the fog are excluded, any overlap kept") {
  const render::Camera camera = looking_down_minus_z();
  const glm::vec3 eye = camera.eye();
  REQUIRE(std::fabs(eye.z - 10.0f) < 1e-3f);
  const glm::mat4 vp = camera.view_projection(16.0f / 9.0f);
  const render::ClipVolume volume(vp);
  CHECK_FALSE(volume.excludes({0.0f, 1.0f, 0.0f}, 0.1f));    // straight ahead
  CHECK(volume.excludes({0.0f, 1.0f, 12.0f}, 0.5f));         // behind the eye
  CHECK_FALSE(volume.excludes({0.0f, 1.0f, 12.0f}, 2.5f));   // behind, but reaching past the eye
  // At 10 m ahead the half-width seen is 10 tan(fov/2) * aspect; a sphere just past the left edge is out,
  // one reaching back over it is kept.
  const float half_width = 10.0f * std::tan(0.5f * camera.fov_y) * 16.0f / 9.0f;
  const float slant = std::cos(std::atan(half_width / 10.0f));  // the side plane's normal leans toward the eye
  CHECK(volume.excludes({-half_width - 0.5f / slant - 0.01f, 1.0f, 0.0f}, 0.5f));
  CHECK_FALSE(volume.excludes({-half_width - 0.5f / slant + 0.05f, 1.0f, 0.0f}, 0.5f));
  CHECK(volume.excludes({0.0f, 1.0f, 10.0f - camera.far_plane - 1.0f}, 0.5f));  // past the far plane

  const render::ClipVolume fogged(vp, eye, 90.0f);
  CHECK(fogged.excludes({0.0f, 1.0f, 10.0f - 91.0f}, 0.5f));
  CHECK_FALSE(fogged.excludes({0.0f, 1.0f, 10.0f - 90.2f}, 0.5f));
  CHECK_FALSE(volume.excludes({0.0f, 1.0f, 10.0f - 91.0f}, 0.5f));  // without the fog's limit: in view
}

TEST_CASE("bounding spheres hold every point of their capsule or box") {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-2.0f, 2.0f);
  for (int trial = 0; trial < 200; ++trial) {
    const glm::vec3 a(u(rng), u(rng), u(rng)), b(u(rng), u(rng), u(rng));
    const float radius = 0.05f + 0.1f * std::fabs(u(rng));
    const render::CapsuleInstance capsule{glm::vec4(a, radius), glm::vec4(b, 0.0f), glm::vec3(1.0f)};
    const render::BoundingSphere s = render::bounding_sphere(capsule);
    for (const glm::vec3& end : {a, b}) CHECK(glm::length(end - s.centre) + radius <= s.radius + 1e-5f);

    glm::mat4 model(1.0f);
    for (int c = 0; c < 3; ++c) model[c] = glm::vec4(u(rng), u(rng), u(rng), 0.0f);  // any linear part, skew included
    model[3] = glm::vec4(u(rng), u(rng), u(rng), 1.0f);
    const render::BoundingSphere box = render::bounding_sphere(render::BoxInstance{model, glm::vec4(1.0f)});
    float farthest = 0.0f;
    for (int corner = 0; corner < 8; ++corner) {
      const glm::vec4 local((corner & 1) ? 0.5f : -0.5f, (corner & 2) ? 0.5f : -0.5f, (corner & 4) ? 0.5f : -0.5f, 1.0f);
      farthest = std::max(farthest, glm::length(glm::vec3(model * local) - box.centre));
    }
    CHECK(farthest <= box.radius + 1e-5f);
    CHECK(farthest >= box.radius - 1e-4f);  // and no larger than it must be: some corner is that far
  }
}

TEST_CASE("a frame drawn with culling is the frame drawn without it, with fewer triangles") {
  // Light bodies and boxes all around the camera: ahead, to the sides, behind, beyond the fog, and some
  // straddling the picture's left and right edges.
  render::Scene scene;
  const std::shared_ptr<const Skeleton> skeleton = test::stick_skeleton();
  const render::Camera camera = looking_down_minus_z();
  const float aspect = 640.0f / 360.0f;
  std::vector<glm::vec3> places;
  for (int i = 0; i < 40; ++i) {
    const float angle = 0.157f * static_cast<float>(i);
    const float distance = 3.0f + 2.6f * static_cast<float>(i);
    places.emplace_back(distance * std::sin(angle), 0.0f, 10.0f - distance * std::cos(angle));
  }
  for (const glm::vec3& at : places) {
    render::SceneCharacter c = render::make_scene_character(skeleton, test::standing_clip(at).frames[0], glm::vec3(0.85f, 0.45f, 0.2f));
    c.light = true;
    scene.characters.push_back(c);
    render::SceneObject box;
    box.type = render::ObjectType::Box;
    box.position = at + glm::vec3(0.6f, 0.0f, 0.0f);
    box.size = {0.3f, 0.5f, 0.3f};
    scene.objects.push_back(box);
  }
  // Boxes straddling the picture's four edges 5 m ahead, their centres up to 0.2 m in or out.
  const float half_height = 5.0f * std::tan(0.5f * camera.fov_y), half_width = half_height * aspect;
  for (int i = 0; i < 20; ++i) {
    const float offset = 0.02f * static_cast<float>(i - 10);
    const float along = -0.8f + 0.08f * static_cast<float>(i);  // spread along the edge: none hides another
    const glm::vec3 centre(0.0f, 1.0f, 5.0f);
    const glm::vec3 at[4] = {centre + glm::vec3(-half_width - offset, along * half_height, 0.0f),
                             centre + glm::vec3(half_width + offset, along * half_height, 0.0f),
                             centre + glm::vec3(along * half_width, half_height + offset, 0.0f),
                             centre + glm::vec3(along * half_width, -half_height - offset, 0.0f)};
    for (const glm::vec3& p : at) {
      render::SceneObject box;
      box.type = render::ObjectType::Box;
      box.position = p - glm::vec3(0.0f, 0.15f, 0.0f);  // a box stands on its position: its centre at p
      box.size = glm::vec3(0.3f);
      scene.objects.push_back(box);
    }
  }
  scene.focus = {0.0f, 0.0f, 0.0f};

  render::OsMesaContext context(640, 360);
  render::Image with, without;
  int triangles_with = 0, triangles_without = 0;
  for (const bool cull : {true, false}) {
    render::RenderSettings settings;
    settings.cull = cull;
    settings.distant_capsules_from = INFINITY;  // the same mesh for every light capsule: the frames may be compared
    render::Renderer renderer(settings);
    renderer.draw(scene, camera, 0, 0, 640, 360);
    (cull ? with : without) = context.read_pixels();
    (cull ? triangles_with : triangles_without) = renderer.triangles_last_frame();
  }
  std::filesystem::create_directories(test::tmp_dir());
  render::write_png(with, test::tmp_dir() + "/culled.png");  // for a look by eye
  REQUIRE(with.width == without.width);
  CHECK(with.rgba == without.rgba);
  CHECK(triangles_with < triangles_without / 2);
}
