#include "engine/motion/support_polygon.h"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <random>

using namespace prep;

namespace {

float signed_area(const std::vector<glm::vec2>& h) {
  float a = 0;
  for (size_t i = 0; i < h.size(); ++i) {
    const glm::vec2 p = h[i], q = h[(i + 1) % h.size()];
    a += p.x * q.y - q.x * p.y;
  }
  return 0.5f * a;
}

}  // namespace

TEST_CASE("support polygon: convex hull drops interior and collinear points, counter-clockwise") {
  const std::vector<glm::vec2> pts = {{0, 0}, {1, 0}, {1, 1}, {0, 1}, {0.5f, 0.5f}, {0.5f, 0}, {1, 0.5f}, {0, 0}, {0.2f, 0.7f}};
  const auto hull = convex_hull(pts);
  CHECK(hull.size() == 4);
  CHECK(signed_area(hull) == doctest::Approx(1.0f));  // positive: counter-clockwise in (x, z)
}

TEST_CASE("support polygon: contains is inclusive on edges and vertices") {
  SupportPolygon sq;
  sq.hull = convex_hull({{0, 0}, {2, 0}, {2, 2}, {0, 2}});
  CHECK(sq.contains({1, 1}));
  CHECK(sq.contains({0, 1}));  // on an edge
  CHECK(sq.contains({2, 2}));  // a vertex
  CHECK_FALSE(sq.contains({2.01f, 1}));
  CHECK_FALSE(sq.contains({-0.5f, -0.5f}));
  CHECK(sq.distance_outside({1, 1}) == 0.0f);
  CHECK(sq.distance_outside({3, 1}) == doctest::Approx(1.0f));
  CHECK(sq.distance_outside({3, 3}) == doctest::Approx(std::sqrt(2.0f)));
}

TEST_CASE("support polygon: contains answers as distance_outside does, near edges too") {
  // contains takes a short cut for points inside; it must agree with the distance everywhere, on both
  // sides of an edge within its tolerance included.
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-0.3f, 0.3f);
  int inside = 0, near_edge = 0;
  for (int polygon = 0; polygon < 200; ++polygon) {
    std::vector<glm::vec2> points;
    for (int k = 0; k < 3 + polygon % 6; ++k) points.push_back({u(rng), u(rng)});
    SupportPolygon sp;
    sp.hull = convex_hull(points);
    for (int k = 0; k < 200; ++k) {
      glm::vec2 p(u(rng), u(rng));
      if (k % 4 == 0 && sp.hull.size() >= 2) {  // on an edge, nudged by up to 2e-6 or 2e-5 m either way
        const glm::vec2 a = sp.hull[static_cast<size_t>(k) % sp.hull.size()];
        const glm::vec2 b = sp.hull[(static_cast<size_t>(k) + 1) % sp.hull.size()];
        const float nudge = k % 8 == 0 ? 2e-6f : 2e-5f;
        p = a + 0.37f * (b - a) + glm::vec2(nudge * u(rng) / 0.3f, nudge * u(rng) / 0.3f);
        ++near_edge;
      }
      const bool by_distance = !sp.empty() && sp.distance_outside(p) <= 1e-6f;
      inside += by_distance;
      REQUIRE(sp.contains(p) == by_distance);
    }
  }
  CHECK(inside > 5000);
  CHECK(near_edge == 10000);
}

TEST_CASE("support polygon: the centre is the area centroid") {
  SupportPolygon sq;
  sq.hull = convex_hull({{0, 0}, {1, 0}, {1, 1}, {0, 1}});
  CHECK(sq.center().x == doctest::Approx(0.5f));
  CHECK(sq.center().y == doctest::Approx(0.5f));
  // A trapezoid with many vertices bunched on one side: the area centroid is not the vertex mean.
  SupportPolygon trap;
  trap.hull = convex_hull({{0, 0}, {4, 0}, {3, 1}, {1, 1}});
  // Bases 4 (at y = 0) and 2 (at y = 1): centroid height (4 + 2 * 2) / (3 * (4 + 2)) = 4/9.
  CHECK(trap.center().x == doctest::Approx(2.0f));
  CHECK(trap.center().y == doctest::Approx(4.0f / 9.0f));
  // Far from the origin the result stays exact (sums are taken about the mean).
  SupportPolygon far;
  far.hull = convex_hull({{1000, 1000}, {1001, 1000}, {1001, 1001}, {1000, 1001}});
  CHECK(far.center().x == doctest::Approx(1000.5f));
}

TEST_CASE("support polygon: degenerate inputs") {
  CHECK(convex_hull({}).empty());
  SupportPolygon none;
  CHECK(none.empty());
  CHECK_FALSE(none.contains({0, 0}));
  CHECK(std::isinf(none.distance_outside({0, 0})));
  SupportPolygon point;
  point.hull = convex_hull({{1, 1}, {1, 1}, {1, 1}});
  REQUIRE(point.hull.size() == 1);
  CHECK(point.contains({1, 1}));
  CHECK(point.center().x == doctest::Approx(1.0f));
  CHECK(point.distance_outside({4, 5}) == doctest::Approx(5.0f));
  SupportPolygon line;
  line.hull = convex_hull({{0, 0}, {1, 1}, {2, 2}, {0.5f, 0.5f}});
  REQUIRE(line.hull.size() == 2);
  CHECK(line.contains({1.5f, 1.5f}));
  CHECK_FALSE(line.contains({1, 0}));
  CHECK(line.center().x == doctest::Approx(1.0f));  // the mean of the two ends
}

namespace {

FootPoints feet_at(float left_x, float right_x) {
  FootPoints f;
  f.heel[kLeft] = {left_x, 0.08f, 0};
  f.toe[kLeft] = {left_x, 0.0f, 0.2f};
  f.heel[kRight] = {right_x, 0.08f, 0};
  f.toe[kRight] = {right_x, 0.0f, 0.2f};
  return f;
}

float area(const SupportPolygon& p) { return std::abs(signed_area(p.hull)); }

}  // namespace

TEST_CASE("support polygon: from footprints") {
  ContactParams params;
  const FootPoints feet = feet_at(0.1f, -0.1f);
  FrameContacts c;
  CHECK(support_polygon(feet, c, params).empty());  // flight

  c[kLeft] = {true, true};  // single support: the whole sole, foot_width wide
  const SupportPolygon single = support_polygon(feet, c, params);
  CHECK(area(single) == doctest::Approx(0.2f * params.foot_width));
  CHECK(single.contains({0.1f, 0.1f}));
  CHECK_FALSE(single.contains({0.0f, 0.1f}));
  CHECK(single.center().x == doctest::Approx(0.1f));
  CHECK(single.center().y == doctest::Approx(0.1f));

  c[kLeft] = {true, false};  // heel only: a small patch, never a line
  const SupportPolygon heel = support_polygon(feet, c, params);
  CHECK(area(heel) > 0.25f * params.foot_width * params.foot_width);
  CHECK(heel.contains({0.1f, 0.0f}));
  CHECK_FALSE(heel.contains({0.1f, 0.15f}));

  c[kLeft] = {false, true};  // toe only
  const SupportPolygon toe = support_polygon(feet, c, params);
  CHECK(area(toe) > 0.25f * params.foot_width * params.foot_width);
  CHECK(toe.contains({0.1f, 0.2f}));
  CHECK_FALSE(toe.contains({0.1f, 0.0f}));

  c[kLeft] = {true, true};  // double support: the midpoint between the feet is inside
  c[kRight] = {true, true};
  const SupportPolygon both = support_polygon(feet, c, params);
  CHECK(both.contains({0.0f, 0.1f}));
  CHECK(area(both) == doctest::Approx((0.2f + params.foot_width) * 0.2f));
  CHECK(both.center().x == doctest::Approx(0.0f).epsilon(1e-6));
}

TEST_CASE("support polygon: points added inside a hull leave it as it was, vertex for vertex") {
  // A support polygon has at most eight points; the same hull must come from many more.
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(-0.3f, 0.3f);
  int checked = 0;
  for (int trial = 0; trial < 500; ++trial) {
    std::vector<glm::vec2> few(3 + static_cast<size_t>(trial % 6));
    for (glm::vec2& p : few) p = {u(rng), u(rng)};
    const std::vector<glm::vec2> hull = convex_hull(few);
    if (hull.size() < 3) continue;
    std::vector<glm::vec2> many = few;
    glm::vec2 mean(0.0f);
    for (glm::vec2 p : hull) mean += p;
    mean /= static_cast<float>(hull.size());
    for (float scale : {0.2f, 0.5f, 0.8f})
      for (glm::vec2 p : hull) many.push_back(mean + scale * (p - mean));  // inside
    REQUIRE(many.size() > 8);
    CHECK(convex_hull(many) == hull);
    ++checked;
  }
  CHECK(checked > 400);
}

TEST_CASE("support polygon: a foot's four corners give the hull the monotone chain gives, to the bit") {
  // Four corners of a clearly convex quadrilateral, in either turning order, are taken as they stand;
  // any other four points go through the monotone chain. A fifth point repeating one of the four sends
  // the same four through the chain: both must give the same vertices in the same order.
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> where(-500.0f, 500.0f), size(0.002f, 0.3f), turn(-3.14159f, 3.14159f),
      jitter(-0.05f, 0.05f), unit(0.0f, 1.0f);
  int quadrilaterals = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    const glm::vec2 centre(where(rng), where(rng));
    const float a = turn(rng), length = size(rng), width = size(rng);
    const glm::vec2 along(std::sin(a), std::cos(a)), side(along.y, -along.x);
    std::vector<glm::vec2> corners = {centre - along * length + side * width, centre - along * length - side * width,
                                      centre + along * length - side * width, centre + along * length + side * width};
    if (trial % 3 == 1)
      for (glm::vec2& c : corners) c += glm::vec2(jitter(rng), jitter(rng));  // any quadrilateral, convex or not
    if (trial % 5 == 2) std::swap(corners[1], corners[2]);                      // the corners out of turn
    if (trial % 7 == 3) corners[3] = corners[0] + 0.5f * unit(rng) * (corners[1] - corners[0]);  // one on a side
    if (trial % 2) std::reverse(corners.begin(), corners.end());
    std::vector<glm::vec2> repeated = corners;
    repeated.push_back(corners[trial % 4]);
    const std::vector<glm::vec2> hull = convex_hull(corners);
    CAPTURE(trial);
    REQUIRE(hull == convex_hull(repeated));
    quadrilaterals += hull.size() == 4;
  }
  CHECK(quadrilaterals > 10000);
}
