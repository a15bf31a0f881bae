// The crowd demo (prep-demo --crowd N): a Crowd of N lanes (engine/world/crowd.h), every character
// preparing for its own hurdle and ball, stepped at the engine's fixed tick and drawn by the renderer: the
// characters nearest the camera as skinned bodies, every other one as a light body (low-poly capsules, one
// instanced draw for all of them). A small panel gives the crowd's size, the engine's milliseconds per
// tick and the frame rate.
//
// Keys: Q/E orbit, R/F tilt, Z/X zoom, W A S D / arrows move the camera over the floor, P pauses, H hides
// the panel, Escape quits. Mouse: a drag orbits (with the right button or Shift it pans), the wheel zooms.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "app/demo/window_app.h"
#include "app/render/camera.h"
#include "app/render/gl_context.h"
#include "app/render/imgui_layer.h"
#include "app/render/renderer.h"
#include "engine/world/crowd.h"

namespace prep::demo {

class CrowdApp final : public WindowApp {
 public:
  static constexpr int kDetailedBodies = 4;          // the characters in view nearest the camera drawn skinned
  static constexpr float kDetailedDistance = 20.0f;  // m: balls farther from the eye are drawn light
  static constexpr int kMaxTicksPerFrame = 4;    // a slow frame does not make the next slower still

  // window: the GLFW window for ImGui's input, or nullptr headless. The crowd must outlive the app.
  CrowdApp(render::GlContext& context, Crowd& crowd, GLFWwindow* window, const render::RenderSettings& settings = {});
  ~CrowdApp() override;

  void frame(float dt) override;  // steps the crowd by dt (at its fixed tick), then draws
  // Steps the crowd by dt without drawing (headless runs to a later moment).
  void skip_frame(float dt);
  void on_key(int key) override;
  void on_drag(float dx, float dy, bool pan) override;
  void on_scroll(float steps) override;
  std::string closing_report() const override;
  int triangles() const override;

  render::Camera camera;
  bool show_panel = true;
  bool paused = false;
  const render::Scene& scene() const { return scene_; }
  double engine_ms_per_tick() const { return engine_ms_.value(); }

 private:
  int advance(float dt);  // ticks run
  void build_scene();
  void draw_panel();

  render::GlContext& context_;
  Crowd& crowd_;
  std::unique_ptr<render::Renderer> renderer_;
  std::unique_ptr<render::ImGuiLayer> ui_;
  render::Scene scene_;
  std::vector<std::pair<float, size_t>> by_distance_;  // (distance to the eye, character) for the detailed bodies
  float pending_ = 0.0f;                                // s of simulation owed to the crowd
  RunningAverage engine_ms_{60};
};

// The camera at the crowd's near edge (where the lanes' balls are), looking back across the lanes toward
// the characters coming at it.
render::Camera crowd_camera(const Crowd& crowd);

}  // namespace prep::demo
