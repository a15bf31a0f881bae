// Pixel checks shared by the screenshot tests: what a projected world point shows, and panel rectangles.
#pragma once

#include <doctest/doctest.h>

#include <map>
#include <string>

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec4.hpp>

#include "app/render/camera.h"
#include "app/render/image.h"
#include "app/render/palette.h"

namespace prep::test {

inline bool in_image(const render::Image& image, const glm::vec2& p) {
  return p.x >= 0.0f && p.y >= 0.0f && p.x < image.width && p.y < image.height;
}

inline render::palette::PixelClass class_at(const render::Image& image, const glm::vec2& p) {
  REQUIRE(in_image(image, p));
  const std::uint8_t* c = image.pixel(static_cast<int>(p.x), static_cast<int>(p.y));
  return render::palette::classify(c[0], c[1], c[2]);
}

// The pixel a world point projects to; REQUIREs that it lies in front of the camera and in the image.
inline glm::vec2 pixel_of(const render::Image& image, const glm::mat4& view_proj, const glm::vec3& world) {
  glm::vec2 pixel;
  REQUIRE(render::project_to_pixel(view_proj, world, image.width, image.height, pixel));
  REQUIRE(in_image(image, pixel));
  return pixel;
}

inline render::palette::PixelClass class_of_point(const render::Image& image, const glm::mat4& view_proj, const glm::vec3& world) {
  return class_at(image, pixel_of(image, view_proj, world));
}

// Whether any pixel within `radius` pixels of p shows class c (thin or small things: a ball far away).
inline bool class_near(const render::Image& image, const glm::vec2& p, int radius, render::palette::PixelClass c) {
  for (int dy = -radius; dy <= radius; ++dy)
    for (int dx = -radius; dx <= radius; ++dx) {
      const glm::vec2 q(p.x + dx, p.y + dy);
      if (in_image(image, q) && class_at(image, q) == c) return true;
    }
  return false;
}

inline bool inside_rect(const glm::vec4& r, const glm::vec2& p) {
  return p.x >= r.x && p.y >= r.y && p.x < r.x + r.z && p.y < r.y + r.w;
}

inline bool inside_any(const std::map<std::string, glm::vec4>& rects, const glm::vec2& p) {
  for (const auto& [name, r] : rects)
    if (inside_rect(r, p)) return true;
  return false;
}

}  // namespace prep::test
