// Mouse picking for the demo: the ray under a pixel, where it meets the floor, and which object (or
// opponent) it hits first. Pure geometry on the engine's read-only scene; no GL.
#pragma once

#include <optional>

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "engine/world/world.h"

namespace prep::demo {

struct Ray {
  glm::vec3 origin{0.0f};
  glm::vec3 direction{0.0f, 0.0f, -1.0f};  // unit
};

// The ray through pixel (x right, y down from the top-left) of a width x height image drawn with
// view_projection (the inverse of camera.h's project_to_pixel): from the near plane, through the far plane.
Ray pixel_ray(const glm::mat4& view_projection, glm::vec2 pixel, int width, int height);

// Where the ray meets the floor (y = 0), on the floor as (x, z); none when it runs parallel to or away from it.
std::optional<glm::vec2> ray_floor(const Ray& ray);

// Distance along the ray to an axis-aligned box [lo, hi]; none when it misses (slab test).
std::optional<float> ray_box(const Ray& ray, const glm::vec3& lo, const glm::vec3& hi);

// What the ray hits first among the world's objects: obstacles by their box (turned by their heading; the
// space under a bar or beam counts too, so a click between the posts picks it), balls by their sphere,
// opponents by an upright cylinder around the character. Returns the index into World::objects(), or
// none. Used objects (a kicked ball, a passed bar) and defeated opponents are not picked.
std::optional<int> pick_object(const World& world, const Ray& ray);

// Picking slack: a ball or a thin bar is hard to hit exactly; every shape is grown by this much (m).
constexpr float kPickMargin = 0.12f;
// The cylinder picked for an opponent (m): about a person's shoulders and height.
constexpr float kOpponentPickRadius = 0.35f;
constexpr float kOpponentPickHeight = 1.85f;

}  // namespace prep::demo
