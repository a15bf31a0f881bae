#include "engine/motion/support_polygon.h"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>

namespace prep {
namespace {

// Points closer than this (metres) count as one, and a point this close to an edge is on it.
constexpr float kEpsilon = 1e-6f;

float cross(glm::vec2 o, glm::vec2 a, glm::vec2 b) { return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x); }

float distance_to_segment(glm::vec2 p, glm::vec2 a, glm::vec2 b) {
  const glm::vec2 ab = b - a;
  const float len2 = glm::dot(ab, ab);
  const float t = len2 > 0.0f ? std::clamp(glm::dot(p - a, ab) / len2, 0.0f, 1.0f) : 0.0f;
  return glm::length(p - (a + ab * t));
}

// Four points that are, in the order given or its reverse, the corners of a convex quadrilateral with
// every corner's turn far from straight (a foot's sole alone: a rectangle): its hull is the four of them
// counter-clockwise from the lowest (x, then y), which is what the monotone chain gives. Each of the chain's
// cross products is that of three of the corners, and any three of four corners in a cycle are three
// consecutive ones; at 1e-4 m^2 or more none can change sign by rounding (the corners lie within a foot of
// each other, so their differences are exact or nearly so, and a product of two is off by far less than
// 1e-6 m^2). Returns false, touching nothing, for any other four points.
bool convex_quadrilateral_into(const glm::vec2* points, std::vector<glm::vec2>& hull) {
  constexpr float kClearTurn = 1e-4f;
  float turn[4];
  for (size_t i = 0; i < 4; ++i) turn[i] = cross(points[i], points[(i + 1) % 4], points[(i + 2) % 4]);
  const bool counter_clockwise = turn[0] >= kClearTurn && turn[1] >= kClearTurn && turn[2] >= kClearTurn && turn[3] >= kClearTurn;
  const bool clockwise = turn[0] <= -kClearTurn && turn[1] <= -kClearTurn && turn[2] <= -kClearTurn && turn[3] <= -kClearTurn;
  if (!counter_clockwise && !clockwise) return false;
  size_t lowest = 0;
  for (size_t i = 1; i < 4; ++i) {
    const glm::vec2 p = points[i], q = points[lowest];
    if (p.x < q.x || (p.x == q.x && p.y < q.y)) lowest = i;
  }
  hull.resize(4);
  for (size_t k = 0; k < 4; ++k) hull[k] = points[(counter_clockwise ? lowest + k : lowest + 4 - k) % 4];
  return true;
}

// Andrew's monotone chain over points[0, n) (sorted in place) into `hull` (resized; no allocation once it
// has the capacity).
void hull_into(glm::vec2* points, size_t n, std::vector<glm::vec2>& hull) {
  if (n == 4 && convex_quadrilateral_into(points, hull)) return;
  std::sort(points, points + n, [](glm::vec2 a, glm::vec2 b) { return a.x < b.x || (a.x == b.x && a.y < b.y); });
  n = static_cast<size_t>(std::unique(points, points + n, [](glm::vec2 a, glm::vec2 b) { return glm::length(a - b) <= kEpsilon; }) - points);
  if (n < 3) {
    hull.assign(points, points + n);
    return;
  }
  // Lower hull left to right, then upper hull right to left; collinear points are dropped (cross <= 0
  // pops), which keeps the hull strictly convex.
  hull.resize(2 * n);
  size_t k = 0;
  for (size_t i = 0; i < n; ++i) {
    while (k >= 2 && cross(hull[k - 2], hull[k - 1], points[i]) <= 0.0f) --k;
    hull[k++] = points[i];
  }
  for (size_t i = n - 1, lower = k + 1; i-- > 0;) {
    while (k >= lower && cross(hull[k - 2], hull[k - 1], points[i]) <= 0.0f) --k;
    hull[k++] = points[i];
  }
  hull.resize(k - 1);  // the last point repeats the first
}

}  // namespace

std::vector<glm::vec2> convex_hull(std::vector<glm::vec2> points) {
  std::vector<glm::vec2> hull;
  hull_into(points.data(), points.size(), hull);
  return hull;
}

bool SupportPolygon::contains(glm::vec2 p) const {
  if (hull.size() >= 3) {
    // Short cuts that give what distance_outside would, without its distances to every edge: left of (or
    // on) every counter-clockwise edge is inside (distance 0); more than ten times the tolerance right of
    // an edge's line is further than that from the whole polygon (rounding is far below the margin).
    bool left_of_all = true;
    for (size_t i = 0; i < hull.size(); ++i) {
      const glm::vec2 a = hull[i], b = i + 1 < hull.size() ? hull[i + 1] : hull[0];
      const float c = cross(a, b, p);
      if (c >= 0.0f) continue;
      const glm::vec2 ab = b - a;
      if (c * c > 100.0f * kEpsilon * kEpsilon * glm::dot(ab, ab)) return false;
      left_of_all = false;
    }
    if (left_of_all) return true;
  }
  return !empty() && distance_outside(p) <= kEpsilon;
}

float SupportPolygon::distance_outside(glm::vec2 p) const {
  if (hull.empty()) return INFINITY;
  if (hull.size() == 1) return glm::length(p - hull[0]);
  if (hull.size() == 2) return distance_to_segment(p, hull[0], hull[1]);
  bool inside = true;
  float nearest = INFINITY;
  for (size_t i = 0; i < hull.size(); ++i) {
    const glm::vec2 a = hull[i], b = i + 1 < hull.size() ? hull[i + 1] : hull[0];
    if (cross(a, b, p) < 0.0f) inside = false;  // right of a counter-clockwise edge: outside
    nearest = std::min(nearest, distance_to_segment(p, a, b));
  }
  return inside ? 0.0f : nearest;
}

glm::vec2 SupportPolygon::center() const {
  if (hull.empty()) return glm::vec2(0.0f);
  glm::vec2 mean(0.0f);
  for (glm::vec2 p : hull) mean += p;
  mean /= static_cast<float>(hull.size());
  // Area centroid by the shoelace formula, taken about the mean to keep the sums well conditioned.
  float area2 = 0.0f;
  glm::vec2 sum(0.0f);
  for (size_t i = 0; i < hull.size(); ++i) {
    const glm::vec2 a = hull[i] - mean, b = hull[i + 1 < hull.size() ? i + 1 : 0] - mean;
    const float c = a.x * b.y - b.x * a.y;
    area2 += c;
    sum += (a + b) * c;
  }
  if (std::abs(area2) <= kEpsilon * kEpsilon) return mean;
  return mean + sum / (3.0f * area2);
}

void support_polygon(const FootPoints& feet, const FrameContacts& contacts, const ContactParams& params,
                     SupportPolygon& polygon) {
  glm::vec2 points[8];
  size_t n = 0;
  const float half = 0.5f * params.foot_width;
  for (size_t s = 0; s < 2; ++s) {
    const FootContact& c = contacts[s];
    if (!c.any()) continue;
    const glm::vec2 heel(feet.heel[s].x, feet.heel[s].z), toe(feet.toe[s].x, feet.toe[s].z);
    const float length = glm::length(toe - heel);
    const glm::vec2 along = length > kEpsilon ? (toe - heel) / length : glm::vec2(0.0f, 1.0f);
    const glm::vec2 side(along.y, -along.x);
    // A heel-only contact is a patch reaching half a foot width toward the toe; a toe-only contact one
    // reaching back toward the heel; both give the whole sole.
    const glm::vec2 back = c.heel ? heel : toe - along * half;
    const glm::vec2 front = c.toe ? toe : heel + along * half;
    // Round the sole: back left and right, then front right and left (one foot alone is a rectangle).
    points[n++] = back + side * half;
    points[n++] = back - side * half;
    points[n++] = front - side * half;
    points[n++] = front + side * half;
  }
  hull_into(points, n, polygon.hull);
}

SupportPolygon support_polygon(const FootPoints& feet, const FrameContacts& contacts, const ContactParams& params) {
  SupportPolygon polygon;
  support_polygon(feet, contacts, params, polygon);
  return polygon;
}

}  // namespace prep
