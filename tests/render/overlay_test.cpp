// The balance overlay: the support polygon filled and outlined on the floor, the COM's disc white inside the
// polygon and red outside, its plumb line, and the COM drawn over everything; drawn pixels where expected.
#include "app/render/overlay.h"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>

#include "app/render/gl_context.h"
#include "app/render/palette.h"
#include "app/render/renderer.h"
#include "tests/render/pixels.h"

using namespace prep;
using namespace prep::render;

TEST_CASE("overlay geometry: a fan fills the hull, a band outlines each edge, the COM disc says inside or outside") {
  BalanceView b;
  b.support = {{-0.1f, -0.2f}, {0.1f, -0.2f}, {0.1f, 0.2f}, {-0.1f, 0.2f}};
  b.com = {0.0f, 0.9f, 0.05f};
  b.com_inside = true;
  const OverlayGeometry g = build_overlay({b});
  // 2 fan triangles + 4 edges x 2 + 20 disc triangles + 2 plumb strips x 2; the diamond: 8 faces on top.
  CHECK(g.depth_tested.size() == 3u * (2 + 8 + 20 + 4));
  CHECK(g.on_top.size() == 3u * 8);
  for (const OverlayVertex& v : g.depth_tested) CHECK(v.position.y <= b.com.y + 1e-6f);
  // The outline stays inside the hull (the band lies on the inner side of each edge).
  for (size_t i = 6; i < 6 + 8 * 3; ++i) {
    CHECK(std::fabs(g.depth_tested[i].position.x) <= 0.1f + 1e-5f);
    CHECK(std::fabs(g.depth_tested[i].position.z) <= 0.2f + 1e-5f);
  }
  const glm::vec4 inside = g.depth_tested[3 * (2 + 8)].colour;
  CHECK(glm::vec3(inside) == palette::kComInside);
  b.com_inside = false;
  const glm::vec4 outside = build_overlay({b}).depth_tested[3 * (2 + 8)].colour;
  CHECK(glm::vec3(outside) == palette::kComOutside);
  // In flight (no support) only the COM is drawn.
  b.support.clear();
  CHECK(build_overlay({b}).depth_tested.size() == 3u * (20 + 4));
}

TEST_CASE("overlay drawn: the support polygon's colour on the floor, the COM's disc at its projection") {
  OsMesaContext context(640, 480);
  Renderer renderer;
  Overlay overlay;
  Scene scene;
  BalanceView b;
  b.support = {{-0.4f, -0.3f}, {0.4f, -0.3f}, {0.4f, 0.3f}, {-0.4f, 0.3f}};
  b.com = {0.25f, 0.9f, 0.0f};
  b.com_inside = true;
  scene.balance = {b};
  Camera camera;
  camera.target = {0.0f, 0.3f, 0.0f};
  camera.yaw = 0.3f;
  camera.pitch = 0.7f;
  camera.distance = 3.0f;
  renderer.draw(scene, camera, 0, 0, 640, 480);
  const glm::mat4 vp = camera.view_projection(640.0f / 480.0f);
  overlay.draw(scene, vp);
  const Image image = context.read_pixels();
  CHECK(test::class_of_point(image, vp, {-0.2f, 0.0f, 0.1f}) == palette::PixelClass::Support);  // the fill
  CHECK(test::class_of_point(image, vp, {0.0f, 0.0f, 0.8f}) == palette::PixelClass::Ground);    // outside it
  const std::uint8_t* disc = image.pixel(static_cast<int>(test::pixel_of(image, vp, {0.25f, 0.0f, 0.0f}).x),
                                         static_cast<int>(test::pixel_of(image, vp, {0.25f, 0.0f, 0.0f}).y));
  CHECK(std::min({disc[0], disc[1], disc[2]}) > 240);  // white: the COM is inside
  CHECK(overlay.triangles_last_frame() == 2 + 8 + 20 + 4 + 8);
}
