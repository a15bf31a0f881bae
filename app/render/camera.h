// Orbit / follow camera and projection helpers shared by the renderer and the screenshot tests.
#pragma once

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace prep::render {

struct Camera {
  glm::vec3 target{0.0f, 0.9f, 0.0f};  // the point orbited (and followed)
  float yaw = 0.6f;          // radians about +Y; 0 looks along -Z from +Z (the eye is on the +Z side)
  float pitch = 0.30f;       // radians above the horizon
  float distance = 5.0f;     // m from the target
  float fov_y = 0.75f;       // radians (perspective)
  bool orthographic = false;
  float ortho_height = 2.4f; // m visible vertically (orthographic)
  float near_plane = 0.05f;
  float far_plane = 200.0f;

  glm::vec3 eye() const;
  glm::mat4 view() const;
  glm::mat4 projection(float aspect) const;
  glm::mat4 view_projection(float aspect) const { return projection(aspect) * view(); }

  // Orbit input: radians of yaw and pitch (pitch kept within (-1.5, 1.5)), zoom as a factor on distance.
  void orbit(float d_yaw, float d_pitch);
  void zoom(float factor);
  // Pans the target in the camera's screen plane by metres right/up.
  void pan(float right, float up);
  // Follow: moves the target toward `point` (horizontally, height kept) with time constant tau seconds.
  void follow(const glm::vec3& point, float dt, float tau = 0.35f);

  // The demos' camera input. Keys (GLFW key codes): Q/E orbit, R/F tilt (0.15 rad a press), Z/X zoom;
  // returns whether the key was one of them. A mouse drag of dx, dy pixels orbits, or with `pan` moves the
  // target in the view plane so that the floor under the cursor follows it (a viewport `height` pixels
  // high). A wheel step zooms by 10%.
  bool key(int glfw_key);
  void drag(float dx, float dy, bool pan, int height);
  void scroll(float steps);
};

// Pixel coordinates (x right, y down, origin at the image's top-left corner) of a world point, for an image
// of width x height drawn with `view_projection`. Returns false if the point is behind the camera.
bool project_to_pixel(const glm::mat4& view_projection, const glm::vec3& point, int width, int height, glm::vec2& pixel);

}  // namespace prep::render
