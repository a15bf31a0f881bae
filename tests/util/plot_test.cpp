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

TEST_CASE("labelled series get a legend at the top right, marks a dot on the line, a fixed y range holds") {
  PlotSeries flat, rise;
  flat.rgb = 0x00a000;
  flat.label = "flat";
  rise.rgb = 0x0000ff;
  rise.label = "rise";
  for (int i = 0; i <= 10; ++i) {
    flat.x.push_back(i);
    flat.y.push_back(0.5);
    rise.x.push_back(i);
    rise.y.push_back(0.1 * i);
  }
  flat.marks = {5.0};
  PlotOptions o;
  o.y_min = 0.0;
  o.y_max = 2.0;  // the data reach 1: the upper half of the frame stays empty but for the legend
  const std::vector<std::uint8_t> img = render_line_plot({flat, rise}, o);
  auto is = [&](int x, int y, std::uint32_t rgb) {
    const std::uint8_t* p = &img[(static_cast<size_t>(y) * o.width + x) * 3];
    return p[0] == (rgb >> 16 & 255) && p[1] == (rgb >> 8 & 255) && p[2] == (rgb & 255);
  };
  auto count = [&](int x0, int x1, int y0, int y1, std::uint32_t rgb) {
    int n = 0;
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x) n += is(x, y, rgb);
    return n;
  };
  // The frame spans x 80 .. width-25 and y 40 .. height-55 (plot.cpp); the legend box sits at its top right.
  const int right = o.width - 25, top = 40, bottom = o.height - 55;
  CHECK(count(right - 120, right, top, top + 50, 0x00a000) > 20);  // the swatches
  CHECK(count(right - 120, right, top, top + 50, 0x0000ff) > 20);
  // With y fixed to 0..2, y = 1 lies half-way up: nothing of either line above a third of the height.
  CHECK(count(80, right - 130, top, top + (bottom - top) / 3, 0x0000ff) == 0);
  CHECK(count(80, right - 130, top, top + (bottom - top) / 3, 0x00a000) == 0);
  // The mark at x = 5 (the middle) is a dot: a ring of dark ink around the line's colour there.
  const int mx = (80 + right) / 2, my = bottom - (bottom - top) / 4;  // y = 0.5 of 0..2
  int ring = 0;
  for (int dy = -5; dy <= 5; ++dy)
    for (int dx = -5; dx <= 5; ++dx) ring += is(mx + dx, my + dy, 0x202020);
  CHECK(ring > 15);
}
