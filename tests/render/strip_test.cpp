#include <doctest/doctest.h>

#include <stdexcept>

#include "app/demo/strip.h"
#include "app/demo/windowed.h"
#include "app/render/palette.h"
#include "tests/render/test_scene.h"

using namespace prep;
using namespace prep::render;

TEST_CASE("a strip has one tile per frame, each showing the character near its middle") {
  demo::DemoClip clip{test::standing_clip(glm::vec3(2.0f, 0.0f, 3.0f)), std::nullopt, -1};
  demo::StripOptions options;
  options.frames = 3;
  options.tile_width = 160;
  options.tile_height = 240;
  const Image strip = demo::render_strip(clip, options);
  REQUIRE(strip.width == 3 * 160);
  REQUIRE(strip.height == 240);
  for (int tile = 0; tile < 3; ++tile) {
    CAPTURE(tile);
    int character = 0, character_x_sum = 0;
    for (int y = 0; y < strip.height; ++y)
      for (int x = tile * 160; x < (tile + 1) * 160; ++x) {
        const std::uint8_t* c = strip.pixel(x, y);
        if (palette::classify(c[0], c[1], c[2]) == palette::PixelClass::Character) ++character, character_x_sum += x;
      }
    REQUIRE(character > 300);
    const float mean_x = static_cast<float>(character_x_sum) / character - tile * 160;
    CHECK(mean_x == doctest::Approx(80.0f).epsilon(0.15));
  }
}

TEST_CASE("key scripts parse and reject bad items") {
  const auto keys = demo::parse_key_script("3:e,10:space,12:Left,20:7");
  REQUIRE(keys.size() == 4);
  CHECK(keys[0].frame == 3);
  CHECK(keys[1].frame == 10);
  CHECK(keys[3].frame == 20);
  CHECK(keys[0].key != keys[1].key);
  CHECK(keys[0].release == 4);  // a press lasts a frame
  // FROM-TO: held from FROM, released at TO.
  const auto held = demo::parse_key_script("30-90:w");
  REQUIRE(held.size() == 1);
  CHECK(held[0].frame == 30);
  CHECK(held[0].release == 90);
  CHECK_THROWS_AS(demo::parse_key_script("30-20:w"), std::invalid_argument);
  CHECK_THROWS_AS(demo::parse_key_script("30-:w"), std::invalid_argument);
  CHECK_THROWS_AS(demo::parse_key_script("30x:w"), std::invalid_argument);
  CHECK_THROWS_AS(demo::parse_key_script("x:e"), std::invalid_argument);
  CHECK_THROWS_AS(demo::parse_key_script("5:nosuchkey"), std::invalid_argument);
  CHECK_THROWS_AS(demo::parse_key_script("5"), std::invalid_argument);
  CHECK(demo::parse_key_script("").empty());
}
