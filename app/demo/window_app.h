// What the window (windowed.cpp) and the headless runs drive: one frame at a time, and the input.
// Three applications implement it: DemoApp (the scenario demo, demo_app.h), ClipViewerApp (clips alone)
// and CrowdApp (the crowd, crowd_app.h).
#pragma once

#include <string>

#include <glm/vec2.hpp>

#include "app/demo/timings.h"

namespace prep::demo {

class WindowApp {
 public:
  virtual ~WindowApp() = default;

  // One frame of dt seconds into the context's framebuffer (the caller ends the frame).
  virtual void frame(float dt) = 0;
  // A key press (GLFW key codes; a held key repeats), from the window or from a --script.
  virtual void on_key(int key) = 0;
  // A key went down or came up (the press and the release only, no repeats): what is held, for input
  // that lasts while a key is held (the demo's steering).
  virtual void on_key_state(int key, bool down) { (void)key, (void)down; }
  // Mouse input already filtered by ImGui's capture: drag in pixels, scroll in steps, a click (press and
  // release without a drag) at a framebuffer pixel (x right, y down).
  virtual void on_drag(float dx, float dy, bool pan) = 0;
  virtual void on_scroll(float steps) = 0;
  virtual void on_click(glm::vec2 pixel, bool right) { (void)pixel, (void)right; }
  // One line printed when the window closes: the state the input left behind (the xvfb smoke test reads it).
  virtual std::string closing_report() const = 0;

  // Triangles drawn last frame (all passes).
  virtual int triangles() const = 0;

  bool quit_requested = false;
  bool sync_stages = false;  // glFinish after each GL stage, so each stage's ms is its own (costs fps)
  Timings timings;

 protected:
  // The applications' frame timing: start_frame_timing() closes the previous frame's time in `timings`
  // (from one start to the next, when both frames are measured), finish_stage() adds a stage's
  // milliseconds, after glFinish for a GL stage while sync_stages (so that each stage's time is its own).
  void start_frame_timing(bool measured = true);
  void finish_stage(int stage, Clock::time_point start, bool gl_stage, bool measured = true);

 private:
  Clock::time_point last_frame_start_{};
  bool measured_frame_before_ = false;
};

}  // namespace prep::demo
