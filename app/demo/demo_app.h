// The demo's frame: advance the clip player, build the scene, draw it (shadow map, main pass), draw the
// panels, all into the current context's framebuffer; the same code runs in the window and headless.
#pragma once

#include <map>
#include <memory>
#include <string>

#include <glm/vec4.hpp>

#include "app/demo/clip_view.h"
#include "app/demo/motions.h"
#include "app/demo/timings.h"
#include "app/render/camera.h"
#include "app/render/gl_context.h"
#include "app/render/imgui_layer.h"
#include "app/render/renderer.h"

namespace prep::demo {

class DemoApp {
 public:
  // window: the GLFW window for ImGui's input, or nullptr headless.
  DemoApp(render::GlContext& context, DemoMotions motions, GLFWwindow* window, const render::RenderSettings& settings = {});

  // One frame of dt seconds into the context's framebuffer (the caller ends the frame).
  void frame(float dt);

  // A key press (GLFW key codes), from the window or from a --script.
  void on_key(int key);
  // Mouse input already filtered by ImGui's capture: drag in pixels, scroll in steps.
  void on_drag(float dx, float dy, bool pan);
  void on_scroll(float steps);

  ClipPlayer player;
  render::Camera camera;
  bool follow = true;          // the camera's target follows the character
  bool show_panels = true;
  bool show_props = true;
  bool sync_stages = false;    // glFinish after each GL stage, so each stage's ms is its own (costs fps)
  bool quit_requested = false;
  Timings timings;

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
  Clock::time_point last_frame_start_;
  bool first_frame_ = true;
};

// The camera that frames a clip's character from its front-right, at the usual distance.
render::Camera default_camera(const render::Scene& scene);

}  // namespace prep::demo
