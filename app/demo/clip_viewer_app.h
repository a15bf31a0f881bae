// The clip viewer (prep-demo --viewer): one clip at a time with a player, the obstacle of its role, a
// camera and timings panels. Its frame: advance the clip player, build the scene, draw it (shadow map,
// main pass), draw the panels, all into the current context's framebuffer; the same code runs in the
// window and headless.
#pragma once

#include <map>
#include <memory>
#include <string>

#include <glm/vec4.hpp>

#include "app/demo/clip_view.h"
#include "app/demo/motions.h"
#include "app/demo/timings.h"
#include "app/demo/window_app.h"
#include "app/render/camera.h"
#include "app/render/gl_context.h"
#include "app/render/imgui_layer.h"
#include "app/render/renderer.h"

namespace prep::demo {

class ClipViewerApp final : public WindowApp {
 public:
  // window: the GLFW window for ImGui's input, or nullptr headless.
  ClipViewerApp(render::GlContext& context, DemoMotions motions, GLFWwindow* window, const render::RenderSettings& settings = {});

  void frame(float dt) override;
  void on_key(int key) override;
  void on_drag(float dx, float dy, bool pan) override;
  void on_scroll(float steps) override;
  std::string closing_report() const override;  // camera yaw, clip, playing or paused
  int triangles() const override { return renderer_->triangles_last_frame(); }

  ClipPlayer player;
  render::Camera camera;
  bool follow = true;          // the camera's target follows the character
  bool show_panels = true;
  bool show_props = true;

  const DemoMotions& motions() const { return motions_; }
  const render::Scene& scene() const { return scene_; }
  const render::Renderer& renderer() const { return *renderer_; }
  // Screen rectangles (x, y, width, height; pixels from the top-left) of the panels drawn last frame.
  const std::map<std::string, glm::vec4>& panel_rects() const { return panel_rects_; }
  // The camera used for the last frame (after following).
  glm::mat4 last_view_projection() const { return last_view_projection_; }

 private:
  void draw_panels();
  void clip_player_panel();
  void camera_panel();
  void timings_panel();
  void remember_panel(const char* name);

  render::GlContext& context_;
  DemoMotions motions_;
  std::unique_ptr<render::Renderer> renderer_;
  std::unique_ptr<render::ImGuiLayer> ui_;
  render::Scene scene_;
  std::map<std::string, glm::vec4> panel_rects_;
  glm::mat4 last_view_projection_{1.0f};
  std::string gl_description_;
};

// The camera that frames a clip's character from its front-right, at the usual distance.
render::Camera default_camera(const render::Scene& scene);

}  // namespace prep::demo
