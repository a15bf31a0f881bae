// Balance overlays drawn over the scene (the demo's "support polygon and COM" toggle): per character the
// support polygon on the floor (translucent fill and an outline), the centre of mass projected onto the
// floor (a disc: white inside the polygon, red outside), a thin plumb line from the COM down to it, and
// the COM itself as a small diamond drawn on top of everything (it lies inside the body).
// Unlit and separate from Renderer: the same scene and camera, drawn after Renderer::main_pass.
#pragma once

#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec4.hpp>

#include "app/render/gl_api.h"
#include "app/render/scene.h"

namespace prep::render {

struct OverlayVertex {
  glm::vec3 position;
  glm::vec4 colour;
};

struct OverlayGeometry {
  std::vector<OverlayVertex> depth_tested;  // triangles hidden by what stands in front (floor shapes, line)
  std::vector<OverlayVertex> on_top;        // triangles drawn over everything (the COM diamond)
};

// Sizes (m): outline width, COM disc radius, plumb line width, diamond half-size; height above the floor.
constexpr float kSupportOutline = 0.018f;
constexpr float kComDiscRadius = 0.055f;
constexpr float kPlumbWidth = 0.010f;
constexpr float kComDiamond = 0.035f;
constexpr float kOverlayLift = 0.006f;

// The triangles for the scene's BalanceViews (no GL: tests check them directly).
OverlayGeometry build_overlay(const std::vector<BalanceView>& balance);

class Overlay {
 public:
  Overlay();  // needs a current context with gl::load() done
  ~Overlay();
  Overlay(const Overlay&) = delete;
  Overlay& operator=(const Overlay&) = delete;

  // Draws into the currently bound framebuffer's viewport (already set by Renderer::main_pass).
  void draw(const Scene& scene, const glm::mat4& view_projection);
  int triangles_last_frame() const { return triangles_; }

 private:
  void draw_batch(const std::vector<OverlayVertex>& vertices);
  GLuint program_ = 0, vao_ = 0, vbo_ = 0;
  int triangles_ = 0;
};

}  // namespace prep::render
