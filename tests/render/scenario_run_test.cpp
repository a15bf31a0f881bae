// prep-demo --headless --scenario: the strip of frames (the fallback when ffmpeg is missing) and the box
// filter its tiles are shrunk with.
#include "app/demo/scenario_run.h"

#include <doctest/doctest.h>

#include <filesystem>

#include "app/render/palette.h"
#include "tests/support/paths.h"

using namespace prep;
using render::palette::PixelClass;

TEST_CASE("downscale: each pixel is the mean of its factor x factor block") {
  render::Image image(4, 2);
  for (int x = 0; x < 4; ++x)
    for (int y = 0; y < 2; ++y)
      for (int c = 0; c < 4; ++c) image.pixel(x, y)[c] = static_cast<std::uint8_t>(x < 2 ? 10 * (x + y) : 200);
  const render::Image small = demo::downscale(image, 2);
  REQUIRE(small.width == 2);
  REQUIRE(small.height == 1);
  CHECK(small.pixel(0, 0)[0] == 10);  // (0 + 10 + 10 + 20) / 4
  CHECK(small.pixel(1, 0)[2] == 200);
}

TEST_CASE("a headless scenario run writes a strip of its frames, every tile showing the scene") {
  std::filesystem::create_directories(test::tmp_dir());
  demo::ScenarioRunOptions o;
  o.scenario = test::repo() + "/assets/scenarios/obstacles.json";
  o.seconds = 2.5f;
  o.width = 480;
  o.height = 270;
  o.strip = test::tmp_dir() + "/scenario_strip.png";
  o.cache_dir = test::tmp_dir() + "/policy-cache";
  std::filesystem::remove(o.strip);
  REQUIRE(demo::run_scenario_headless(o) == 0);
  const render::Image strip = render::read_png(o.strip);
  const int tw = o.width / 3, th = o.height / 3;
  REQUIRE(strip.width == demo::kStripColumns * tw);
  REQUIRE(strip.height == demo::kStripRows * th);
  for (int t = 0; t < demo::kStripTiles; ++t) {
    CAPTURE(t);
    int ground = 0, character = 0;
    const int x0 = (t % demo::kStripColumns) * tw, y0 = (t / demo::kStripColumns) * th;
    for (int y = y0; y < y0 + th; ++y)
      for (int x = x0; x < x0 + tw; ++x) {
        const std::uint8_t* c = strip.pixel(x, y);
        const PixelClass k = render::palette::classify(c[0], c[1], c[2]);
        ground += k == PixelClass::Ground;
        character += k == PixelClass::Character;
      }
    CHECK(ground > tw * th / 4);
    CHECK(character > 20);  // the camera follows the character in the frames that are not drawn too
  }
}
