#include <doctest/doctest.h>

#include <cstdint>
#include <vector>

#include "engine/util/plot.h"

using namespace prep;

TEST_CASE("nice ticks are 1, 2 or 5 times a power of ten and cover the range") {
  const std::vector<double> t = nice_ticks(0.0, 10.4, 6);
  REQUIRE(t.size() == 6);
  CHECK(t.front() == doctest::Approx(0.0));
  CHECK(t[1] == doctest::Approx(2.0));
  CHECK(t.back() == doctest::Approx(10.0));
  const std::vector<double> small = nice_ticks(0.81, 0.93, 6);
  CHECK(small.front() >= 0.81 - 1e-9);
  CHECK(small.back() <= 0.93 + 1e-9);
  CHECK(small[1] - small[0] == doctest::Approx(0.02));
}

TEST_CASE("a rising line is drawn low on the left and high on the right, inside the axes") {
  PlotSeries s;
  s.rgb = 0xff0000;
  for (int i = 0; i <= 100; ++i) {
    s.x.push_back(i);
    s.y.push_back(i);
  }
  PlotOptions o;
  o.title = "Test";
  o.x_label = "x";
  o.y_label = "y";
  const std::vector<std::uint8_t> img = render_line_plot({s}, o);
  REQUIRE(img.size() == static_cast<size_t>(o.width * o.height * 3));
  auto red = [&](int x, int y) {
    const std::uint8_t* p = &img[(static_cast<size_t>(y) * o.width + x) * 3];
    return p[0] == 255 && p[1] == 0 && p[2] == 0;
  };
  int left_y = -1, right_y = -1;
  for (int y = 0; y < o.height; ++y) {
    if (red(120, y)) left_y = y;
    if (red(o.width - 60, y) && right_y < 0) right_y = y;
  }
  REQUIRE(left_y >= 0);
  REQUIRE(right_y >= 0);
  CHECK(left_y > right_y + 200);  // image y grows downward
  // Nothing red in the margins, where ticks and labels go.
  for (int y = 0; y < o.height; ++y)
    for (int x = 0; x < 60; ++x) CHECK_FALSE(red(x, y));
  // The title is drawn in dark ink at the top centre.
  int dark = 0;
  for (int y = 5; y < 30; ++y)
    for (int x = o.width / 2 - 40; x < o.width / 2 + 40; ++x) dark += img[(static_cast<size_t>(y) * o.width + x) * 3] < 80;
  CHECK(dark > 20);
}
