#include "app/render/camera.h"

#include <GLFW/glfw3.h>

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

namespace prep::render {

glm::vec3 Camera::eye() const {
  const glm::vec3 offset(std::cos(pitch) * std::sin(yaw), std::sin(pitch), std::cos(pitch) * std::cos(yaw));
  return target + distance * offset;
}

glm::mat4 Camera::view() const { return glm::lookAt(eye(), target, glm::vec3(0, 1, 0)); }

glm::mat4 Camera::projection(float aspect) const {
  if (orthographic) {
    const float h = 0.5f * ortho_height, w = h * aspect;
    return glm::ortho(-w, w, -h, h, near_plane, far_plane);
  }
  return glm::perspective(fov_y, aspect, near_plane, far_plane);
}

void Camera::orbit(float d_yaw, float d_pitch) {
  yaw = std::remainder(yaw + d_yaw, 2.0f * 3.14159265f);
  pitch = std::clamp(pitch + d_pitch, -1.5f, 1.5f);
}

void Camera::zoom(float factor) {
  distance = std::clamp(distance * factor, 0.5f, 80.0f);
  ortho_height = std::clamp(ortho_height * factor, 0.2f, 80.0f);
}

void Camera::pan(float right, float up) {
  const glm::vec3 forward = glm::normalize(target - eye());
  const glm::vec3 r = glm::normalize(glm::cross(forward, glm::vec3(0, 1, 0)));
  const glm::vec3 u = glm::cross(r, forward);
  target += r * right + u * up;
}

void Camera::follow(const glm::vec3& point, float dt, float tau) {
  const float k = 1.0f - std::exp(-std::max(dt, 0.0f) / tau);
  target.x += (point.x - target.x) * k;
  target.z += (point.z - target.z) * k;
}

bool project_to_pixel(const glm::mat4& view_projection, const glm::vec3& point, int width, int height, glm::vec2& pixel) {
  const glm::vec4 clip = view_projection * glm::vec4(point, 1.0f);
  if (clip.w <= 1e-6f) return false;
  const glm::vec3 ndc = glm::vec3(clip) / clip.w;
  pixel.x = (ndc.x * 0.5f + 0.5f) * width;
  pixel.y = (1.0f - (ndc.y * 0.5f + 0.5f)) * height;
  return true;
}

bool Camera::key(int glfw_key) {
  constexpr float kStep = 0.15f;
  switch (glfw_key) {
    case GLFW_KEY_Q: orbit(-kStep, 0.0f); return true;
    case GLFW_KEY_E: orbit(kStep, 0.0f); return true;
    case GLFW_KEY_R: orbit(0.0f, kStep); return true;
    case GLFW_KEY_F: orbit(0.0f, -kStep); return true;
    case GLFW_KEY_Z: zoom(1.0f / 1.15f); return true;
    case GLFW_KEY_X: zoom(1.15f); return true;
    default: return false;
  }
}

void Camera::drag(float dx, float dy, bool pan_view, int height) {
  if (pan_view) {
    const float metres_per_pixel = 2.0f * distance * std::tan(0.5f * fov_y) / std::max(height, 1);
    pan(-dx * metres_per_pixel, dy * metres_per_pixel);
  } else {
    orbit(-dx * 0.008f, dy * 0.008f);
  }
}

void Camera::scroll(float steps) { zoom(std::pow(0.9f, steps)); }

}  // namespace prep::render
