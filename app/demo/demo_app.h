// The demo (Sec. 7): a scenario's world (WorldSession: fixed-step engine, background training) drawn by the
// renderer with the balance overlay and the ImGui panels of app/ui, and the input that drives it: keys
// steer the user's character and launch target motions, a left click on the floor sets the goal and on an
// object makes it the source of influence, a right click launches the action the source calls for. The
// same class runs in the GLFW window and headless through OSMesa (screenshots, videos, benchmarks).
//
// Keys: W A S D / arrows held steer as in a game (WorldSession::steer: the goal leads the character in
// the keys' direction; two keys: a diagonal; let go: it stops close by). The direction is relative to the
// camera's view on the floor -- W away from the camera, D to its right -- taken anew each frame: the
// followed camera slides along without turning, so a held key walks a straight line, and after an orbit
// W is again "into the screen". 1-6 launch kick, crawl, duck, jump, punch_left, punch_right; Space
// launches the prepared action; T toggles auto; P pauses; . steps one tick while paused; N restarts; B
// toggles the support polygon and COM; O the clearance view; H hides the panels; Q/E orbit, R/F tilt,
// Z/X zoom, C follow; Escape quits.
#pragma once

#include <map>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec4.hpp>

#include "app/demo/timings.h"
#include "app/demo/window_app.h"
#include "app/demo/world_session.h"
#include "app/render/camera.h"
#include "app/render/gl_context.h"
#include "app/render/imgui_layer.h"
#include "app/render/overlay.h"
#include "app/render/renderer.h"
#include "engine/world/clearance.h"

namespace prep::demo {

struct MotionFolder;

// What the panels toggle about the view.
struct DemoView {
  render::Camera camera;
  bool follow = true;         // the camera follows the user's character (looking a little ahead of it)
  bool show_panels = true;
  bool show_balance = true;   // the support polygon and COM on the floor
  // The clearance view: every frame the world's bodies are measured against the objects and each other
  // (ClearanceMeter), and each capsule deeper than the tolerance is drawn in red over its body.
  bool show_clearance = false;
  std::string caption;        // drawn at the top-left when not empty (strip tiles), caption_scale times the panel text
  float caption_scale = 1.0f;
};

// Per-frame engine stage times (World::StageTimes summed over the frame's ticks), averaged.
struct EngineTimings {
  RunningAverage control, motion, synthesis, balance, total, ticks;
};

class DemoApp final : public WindowApp {
 public:
  static constexpr float kLookAhead = 1.2f;       // m ahead of the character the followed camera aims at ...
  static constexpr float kSourceShare = 0.25f;     // ... or this share of the way to its source of influence,
  static constexpr float kMaxLookAhead = 1.8f;    // at most this far (m)

  // window: the GLFW window for ImGui's input, or nullptr headless. The session must outlive the app.
  DemoApp(render::GlContext& context, WorldSession& session, GLFWwindow* window, const render::RenderSettings& settings = {});
  ~DemoApp() override;

  void frame(float dt) override;  // advances the session by dt, then draws
  // A frame that is not drawn (headless runs draw only the frames they keep): the session advances and
  // the camera follows as in a drawn frame.
  void skip_frame(float dt);
  void on_key(int key) override;
  void on_key_state(int key, bool down) override;  // W A S D / arrows: steering while held
  void on_drag(float dx, float dy, bool pan) override;
  void on_scroll(float steps) override;
  void on_click(glm::vec2 pixel, bool right) override;
  std::string closing_report() const override;

  // Opens a scenario from the picker (keeps the edited Params when the new one names the same Params file);
  // a bad file leaves a message and the current scenario.
  void open_scenario(const std::string& path);
  // The Preparation panel's Load: the Params file's values in force, or, for a file that cannot be read,
  // its error (naming the file and the field) in `message` and the values in force kept.
  bool load_params_file(const std::string& path);
  // The camera placed behind the user's character, looking along its heading at the course ahead.
  void reset_camera();

  WorldSession& session() { return session_; }
  const WorldSession& session() const { return session_; }
  DemoView view;
  EngineTimings engine_timings;
  std::vector<ScenarioEntry> scenarios;  // the picker's list (default_scenarios_dir())
  std::string params_path;               // the Preparation panel's save/load file
  std::string message;                   // the last save/load/open outcome, shown in the panels
  std::shared_ptr<const MotionFolder> motion_folder;  // the user's folder of takes, when the demo opened one

  const render::Scene& scene() const { return scene_; }
  // This frame's clearance of the world's characters, while the clearance view is on and the world runs;
  // nullptr otherwise.
  const ClearanceMeter* clearance() const { return clearance_on_ ? clearance_.get() : nullptr; }
  const render::Renderer& renderer() const { return *renderer_; }
  int triangles() const override;
  const std::string& gl_description() const { return gl_description_; }
  int width() const { return context_.width(); }
  int height() const { return context_.height(); }
  bool headless() const { return context_.headless(); }
  // Screen rectangles (x, y, width, height; pixels from the top-left) of the panels drawn last frame.
  const std::map<std::string, glm::vec4>& panel_rects() const { return panel_rects_; }
  void remember_panel(const char* name);  // called by each panel between Begin and End
  int panel_frames() const { return panel_frames_; }  // frames drawn with panels so far
  glm::mat4 last_view_projection() const { return last_view_projection_; }

 private:
  void update_camera(float dt);
  // The clearance view: measures the world and marks the scene's flagged capsules.
  void measure_clearance();
  void draw_panels();
  glm::vec2 camera_forward() const;  // unit, on the floor
  // The direction the held steering keys ask for, on the floor (relative to the camera; zero: none).
  glm::vec2 steer_direction() const;
  glm::vec2 look_point() const;      // where the followed camera aims, on the floor
  // The panels' pixels, kept between their redraws (demo_app.cpp, the panels stage).
  struct PanelCache {
    unsigned int framebuffer = 0, texture = 0;  // GL names
    int width = 0, height = 0;
    std::vector<glm::vec4> rects;  // framebuffer pixels from the top-left, as the main pass was given them
    int frames_since_redraw = 0;
  };
  bool panels_need_redraw(const std::vector<glm::vec4>& covered, int width, int height) const;
  void store_panels(const std::vector<glm::vec4>& covered, int width, int height);
  void restore_panels(int width, int height);

  render::GlContext& context_;
  WorldSession& session_;
  std::unique_ptr<render::Renderer> renderer_;
  std::unique_ptr<render::Overlay> overlay_;
  std::unique_ptr<render::ImGuiLayer> ui_;
  render::Scene scene_;
  std::unique_ptr<ClearanceMeter> clearance_;  // made for the skeleton of the world it measures
  std::shared_ptr<const Skeleton> clearance_skeleton_;
  bool clearance_on_ = false;                  // clearance_ holds this frame's measure
  std::map<std::string, glm::vec4> panel_rects_;
  glm::mat4 last_view_projection_{1.0f};
  std::string gl_description_;
  int frames_drawn_ = 0;
  static constexpr int kUntimedFrames = 3;
  int panel_frames_ = 0;
  PanelCache panel_cache_;
  static constexpr int kPanelRedrawFrames = 6;  // at most this many frames between two redraws of idle panels
  const World* camera_world_ = nullptr;
  glm::vec2 initial_goal_{0.0f};
  std::set<int> steer_keys_;  // the steering keys held (GLFW key codes)
};

}  // namespace prep::demo
