#include "app/demo/windowed.h"

#include <unistd.h>

#include <GLFW/glfw3.h>
#include <imgui.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <functional>
#include <iostream>
#include <stdexcept>

#include "app/demo/clip_viewer_app.h"
#include "app/demo/crowd_app.h"
#include "app/demo/stress.h"
#include "app/demo/demo_app.h"
#include "app/render/gl_context.h"
#include "app/render/gl_loader.h"

namespace prep::demo {

std::vector<ScriptedKey> parse_key_script(const std::string& text) {
  std::vector<ScriptedKey> keys;
  size_t start = 0;
  while (start < text.size()) {
    size_t end = text.find(',', start);
    if (end == std::string::npos) end = text.size();
    const std::string item = text.substr(start, end - start);
    start = end + 1;
    const size_t colon = item.find(':');
    if (colon == std::string::npos || colon == 0) throw std::invalid_argument("--script: \"" + item + "\" is not FRAME:KEY");
    ScriptedKey k;
    const std::string frames = item.substr(0, colon);
    const size_t dash = frames.find('-');
    try {
      size_t used = 0;
      k.frame = std::stoi(frames.substr(0, dash), &used);
      if (used != std::min(dash, frames.size()) || k.frame < 0) throw std::invalid_argument("frame");
      k.release = k.frame + 1;
      if (dash != std::string::npos) {
        k.release = std::stoi(frames.substr(dash + 1), &used);
        if (used != frames.size() - dash - 1 || k.release <= k.frame) throw std::invalid_argument("frame");
      }
    } catch (const std::exception&) {
      throw std::invalid_argument("--script: \"" + item + "\": FRAME or FROM-TO must be numbers >= 0, TO after FROM");
    }
    std::string name = item.substr(colon + 1);
    for (char& c : name) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    if (name.size() == 1 && std::isalpha(static_cast<unsigned char>(name[0]))) k.key = GLFW_KEY_A + (name[0] - 'a');
    else if (name.size() == 1 && std::isdigit(static_cast<unsigned char>(name[0]))) k.key = GLFW_KEY_0 + (name[0] - '0');
    else if (name == "space") k.key = GLFW_KEY_SPACE;
    else if (name == "enter") k.key = GLFW_KEY_ENTER;
    else if (name == "period") k.key = GLFW_KEY_PERIOD;
    else if (name == "left") k.key = GLFW_KEY_LEFT;
    else if (name == "right") k.key = GLFW_KEY_RIGHT;
    else if (name == "up") k.key = GLFW_KEY_UP;
    else if (name == "down") k.key = GLFW_KEY_DOWN;
    else if (name == "escape") k.key = GLFW_KEY_ESCAPE;
    else throw std::invalid_argument("--script: \"" + item + "\": unknown key \"" + name + "\"");
    keys.push_back(k);
  }
  return keys;
}

namespace {

// Press and release within this many pixels is a click; farther is a drag.
constexpr double kClickSlop = 4.0;

struct WindowState {
  WindowApp* app = nullptr;
  int button = -1;           // held since a press ImGui did not take, else -1
  double press_x = 0.0, press_y = 0.0;
  double last_x = 0.0, last_y = 0.0;
  bool dragging = false;
};

WindowState& state(GLFWwindow* w) { return *static_cast<WindowState*>(glfwGetWindowUserPointer(w)); }

// Installed before ImGui's GLFW backend, which chains to them; each first asks whether ImGui wants the input.
// A release always reaches the app, so that a key held while ImGui took the keyboard does not stay held
// (GLFW also releases the keys held when the window loses the focus).
void on_key(GLFWwindow* w, int key, int, int action, int) {
  WindowApp& app = *state(w).app;
  if (action == GLFW_RELEASE) {
    app.on_key_state(key, false);
    return;
  }
  if (ImGui::GetCurrentContext() && ImGui::GetIO().WantCaptureKeyboard) return;
  if (action == GLFW_PRESS) app.on_key_state(key, true);
  app.on_key(key);  // the press and its repeats
}

void on_mouse_button(GLFWwindow* w, int button, int action, int) {
  WindowState& s = state(w);
  if (action == GLFW_RELEASE) {
    if (button == s.button && !s.dragging) {
      // Window coordinates -> framebuffer pixels (they differ on high-density displays).
      int ww = 1, wh = 1, fw = 1, fh = 1;
      glfwGetWindowSize(w, &ww, &wh);
      glfwGetFramebufferSize(w, &fw, &fh);
      const glm::vec2 pixel(static_cast<float>(s.press_x * fw / std::max(ww, 1)), static_cast<float>(s.press_y * fh / std::max(wh, 1)));
      s.app->on_click(pixel, button == GLFW_MOUSE_BUTTON_RIGHT);
    }
    if (button == s.button) s.button = -1, s.dragging = false;
    return;
  }
  if (ImGui::GetCurrentContext() && ImGui::GetIO().WantCaptureMouse) return;
  s.button = button;
  s.dragging = false;
  glfwGetCursorPos(w, &s.press_x, &s.press_y);
  s.last_x = s.press_x;
  s.last_y = s.press_y;
}

void on_cursor(GLFWwindow* w, double x, double y) {
  WindowState& s = state(w);
  if (s.button >= 0 && !s.dragging && std::hypot(x - s.press_x, y - s.press_y) > kClickSlop) s.dragging = true;
  if (s.dragging)
    s.app->on_drag(static_cast<float>(x - s.last_x), static_cast<float>(y - s.last_y), s.button != GLFW_MOUSE_BUTTON_LEFT);
  s.last_x = x;
  s.last_y = y;
}

void on_scroll(GLFWwindow* w, double, double dy) {
  if (ImGui::GetCurrentContext() && ImGui::GetIO().WantCaptureMouse) return;
  state(w).app->on_scroll(static_cast<float>(dy));
}

void install_input(render::GlfwContext& context, WindowState& window_state) {
  glfwSetWindowUserPointer(context.window(), &window_state);
  glfwSetKeyCallback(context.window(), on_key);
  glfwSetMouseButtonCallback(context.window(), on_mouse_button);
  glfwSetCursorPosCallback(context.window(), on_cursor);
  glfwSetScrollCallback(context.window(), on_scroll);
}

// The frame loop: events, scripted keys, a frame, the screenshot, the swap.
// `before_frame` (when given) runs before each frame with the seconds since the loop started.
void run_loop(render::GlfwContext& context, WindowApp& app, const WindowOptions& options,
              const std::function<void(double)>& before_frame = {}) {
  auto previous = Clock::now();
  const auto start = previous;
  for (int frame = 0; !context.should_close() && !app.quit_requested; ++frame) {
    glfwPollEvents();
    if (before_frame) before_frame(std::chrono::duration<double>(Clock::now() - start).count());
    for (const ScriptedKey& k : options.script) {
      if (k.frame == frame) {
        std::cout << "prep-demo: frame " << frame << ": scripted key " << k.key << " down\n";
        app.on_key_state(k.key, true);
        app.on_key(k.key);
      }
      if (k.release == frame) app.on_key_state(k.key, false);
    }
    const auto now = Clock::now();
    const float dt = std::min(static_cast<float>(std::chrono::duration<double>(now - previous).count()), 0.1f);
    previous = now;
    app.frame(dt);
    const bool quitting = app.quit_requested || context.should_close();
    if (!options.screenshot.empty() &&
        (frame == options.screenshot_after || (options.screenshot_after < 0 && quitting))) {
      render::write_png(context.read_pixels(), options.screenshot);
      std::cout << "prep-demo: wrote " << options.screenshot << " (frame " << frame << ")\n";
      app.quit_requested = true;
    }
    const auto t = Clock::now();
    context.end_frame();
    app.timings.add(kFinish, ms_since(t));
    if (options.quit_after >= 0 && frame >= options.quit_after) app.quit_requested = true;
  }
  // The state the input left behind (scripts/xvfb_smoke.sh checks that its keys arrived).
  std::cout << "prep-demo: closing: " << app.closing_report() << std::endl;
}

}  // namespace

void run_demo_window(const std::string& scenario, const std::optional<Params>& params, const WindowOptions& options,
                     std::shared_ptr<const MotionFolder> folder) {
  load_scenario(scenario);  // a bad file is named before a window opens
  render::GlfwContext context(options.width, options.height, "prep demo", options.vsync);
  WorldSession session;  // background loading and training: the window shows the scene at once
  session.open(scenario, params);
  WindowState window_state;
  install_input(context, window_state);
  DemoApp app(context, session, context.window());
  app.view.show_clearance = options.clearance;
  app.motion_folder = std::move(folder);
  window_state.app = &app;
  std::cout << "prep-demo: " << gl::describe_context() << "\n";
  std::cout << "prep-demo: scenario " << session.scenario().name << " (" << scenario << ")" << std::endl;
  if (options.stress_seconds <= 0.0) {
    run_loop(context, app, options);
    return;
  }
  const std::string broken = (std::filesystem::temp_directory_path() / ("prep-stress-broken-" + std::to_string(::getpid()) + ".json")).string();
  StressScript stress(options.stress_seed, options.stress_seconds, broken);
  run_loop(context, app, options, [&](double elapsed) {
    if (stress.done(elapsed)) {
      app.quit_requested = true;
      return;
    }
    stress.before_frame(app, elapsed);
  });
  std::cout << "prep-demo: " << stress.summary() << std::endl;
  if (!stress.report().ok()) throw std::runtime_error("the stress run failed: " + stress.summary());
}

void run_crowd_window(const CrowdRunOptions& crowd_options, const WindowOptions& options) {
  std::unique_ptr<Crowd> crowd = make_crowd(crowd_options);
  render::GlfwContext context(options.width, options.height, "prep demo: crowd", options.vsync);
  WindowState window_state;
  install_input(context, window_state);
  CrowdApp app(context, *crowd, context.window(), crowd_options.render);
  window_state.app = &app;
  std::cout << "prep-demo: " << gl::describe_context() << "\n";
  run_loop(context, app, options);
}

void run_clip_viewer_window(const DemoMotions& motions, const WindowOptions& options) {
  render::GlfwContext context(options.width, options.height, "prep demo", options.vsync);
  WindowState window_state;
  install_input(context, window_state);
  ClipViewerApp app(context, motions, context.window());
  window_state.app = &app;
  app.player.select(app.motions(), options.clip);
  std::cout << "prep-demo: " << gl::describe_context() << "\n";
  run_loop(context, app, options);
}

}  // namespace prep::demo
