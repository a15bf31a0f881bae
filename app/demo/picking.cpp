#include "app/demo/picking.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/gtc/matrix_inverse.hpp>
#include <glm/mat4x4.hpp>

namespace prep::demo {

Ray pixel_ray(const glm::mat4& view_projection, glm::vec2 pixel, int width, int height) {
  const glm::mat4 inverse = glm::inverse(view_projection);
  const float x = 2.0f * pixel.x / static_cast<float>(std::max(width, 1)) - 1.0f;
  const float y = 1.0f - 2.0f * pixel.y / static_cast<float>(std::max(height, 1));
  const glm::vec4 near_h = inverse * glm::vec4(x, y, -1.0f, 1.0f);
  const glm::vec4 far_h = inverse * glm::vec4(x, y, 1.0f, 1.0f);
  Ray ray;
  ray.origin = glm::vec3(near_h) / near_h.w;
  const glm::vec3 far_point = glm::vec3(far_h) / far_h.w;
  ray.direction = glm::normalize(far_point - ray.origin);
  return ray;
}

std::optional<glm::vec2> ray_floor(const Ray& ray) {
  if (std::fabs(ray.direction.y) < 1e-6f) return std::nullopt;
  const float t = -ray.origin.y / ray.direction.y;
  if (t <= 0.0f) return std::nullopt;
  const glm::vec3 p = ray.origin + t * ray.direction;
  return glm::vec2(p.x, p.z);
}

std::optional<float> ray_box(const Ray& ray, const glm::vec3& lo, const glm::vec3& hi) {
  float enter = 0.0f, leave = std::numeric_limits<float>::infinity();
  for (int axis = 0; axis < 3; ++axis) {
    const float o = ray.origin[axis], d = ray.direction[axis];
    if (std::fabs(d) < 1e-9f) {
      if (o < lo[axis] || o > hi[axis]) return std::nullopt;
      continue;
    }
    float t0 = (lo[axis] - o) / d, t1 = (hi[axis] - o) / d;
    if (t0 > t1) std::swap(t0, t1);
    enter = std::max(enter, t0);
    leave = std::min(leave, t1);
    if (enter > leave) return std::nullopt;
  }
  return enter;
}

namespace {

// The ray in an object's own frame: origin at its footprint centre, turned by -heading about +Y.
Ray to_local(const Ray& ray, const glm::vec3& position, float heading) {
  const float c = std::cos(heading), s = std::sin(heading);
  // Object -> world turns local (x, z) by heading: x' = c x + s z, z' = -s x + c z. Inverse below.
  auto inverse_turn = [&](const glm::vec3& v) { return glm::vec3(c * v.x - s * v.z, v.y, s * v.x + c * v.z); };
  return {inverse_turn(ray.origin - position), inverse_turn(ray.direction)};
}

std::optional<float> ray_sphere(const Ray& ray, const glm::vec3& centre, float radius) {
  const glm::vec3 oc = ray.origin - centre;
  const float b = glm::dot(oc, ray.direction), c = glm::dot(oc, oc) - radius * radius;
  const float disc = b * b - c;
  if (disc < 0.0f) return std::nullopt;
  const float t = -b - std::sqrt(disc);
  if (t >= 0.0f) return t;
  return c <= 0.0f ? std::optional<float>(0.0f) : std::nullopt;  // inside: hit at once
}

// An upright cylinder from the floor to `height`, around `base` (x, z).
std::optional<float> ray_cylinder(const Ray& ray, glm::vec2 base, float radius, float height) {
  const glm::vec2 o(ray.origin.x - base.x, ray.origin.z - base.y), d(ray.direction.x, ray.direction.z);
  const float a = glm::dot(d, d);
  float t = -1.0f;
  if (a > 1e-9f) {
    const float b = glm::dot(o, d), c = glm::dot(o, o) - radius * radius;
    const float disc = b * b - a * c;
    if (disc < 0.0f) return std::nullopt;
    t = (-b - std::sqrt(disc)) / a;
    if (t < 0.0f) t = (-b + std::sqrt(disc)) / a;
    if (t < 0.0f) return std::nullopt;
  } else if (glm::dot(o, o) <= radius * radius) {
    t = 0.0f;  // looking straight down onto it
  } else {
    return std::nullopt;
  }
  const float y = ray.origin.y + t * ray.direction.y;
  if (y >= 0.0f && y <= height) return t;
  // Straight down through the top cap.
  if (std::fabs(ray.direction.y) > 1e-6f) {
    const float tc = (height - ray.origin.y) / ray.direction.y;
    const glm::vec2 p = o + tc * d;
    if (tc >= 0.0f && glm::dot(p, p) <= radius * radius) return tc;
  }
  return std::nullopt;
}

}  // namespace

std::optional<int> pick_object(const World& world, const Ray& ray) {
  std::optional<int> best;
  float best_t = std::numeric_limits<float>::infinity();
  const auto& objects = world.objects();
  for (int k = 0; k < static_cast<int>(objects.size()); ++k) {
    const WorldObject& o = objects[static_cast<size_t>(k)];
    std::optional<float> t;
    if (o.spec.type == ObjectType::Opponent) {
      if (o.character < 0) continue;
      const WorldCharacter& c = world.characters()[static_cast<size_t>(o.character)];
      if (c.defeated) continue;
      t = ray_cylinder(ray, c.position, kOpponentPickRadius + kPickMargin, kOpponentPickHeight);
    } else if (o.used) {
      continue;
    } else if (o.spec.type == ObjectType::Ball) {
      const float r = 0.5f * o.spec.size.x;
      t = ray_sphere(ray, o.position + glm::vec3(0.0f, r, 0.0f), r + kPickMargin);
    } else {
      // Bar and beam: posts to the top of the bar (the underside height plus its thickness); hurdle: to its top.
      const glm::vec3 s = o.spec.size;
      const float top = o.spec.type == ObjectType::Hurdle ? s.y : s.y + std::max(s.z, 0.08f);
      const float half_depth = 0.5f * std::max(s.z, 0.05f) + kPickMargin;
      const glm::vec3 lo(-0.5f * s.x - kPickMargin, 0.0f, -half_depth), hi(0.5f * s.x + kPickMargin, top + kPickMargin, half_depth);
      t = ray_box(to_local(ray, o.position, o.spec.heading), lo, hi);
    }
    if (t && *t < best_t) {
      best_t = *t;
      best = k;
    }
  }
  return best;
}

}  // namespace prep::demo
