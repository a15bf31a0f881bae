// The windowed demo: a GLFW window driving a WindowApp (the scenario demo, or the clip viewer) with the
// keyboard and the mouse (drag: orbit; right-drag: pan; wheel: zoom; a click: DemoApp::on_click).
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "app/demo/crowd_run.h"
#include "app/demo/motion_folder.h"
#include "app/demo/motions.h"
#include "engine/params/params.h"

namespace prep::demo {

// One scripted key: pressed at frame `frame` (GLFW key code), as if typed, and released at `release`.
struct ScriptedKey {
  int frame = 0;
  int key = 0;
  int release = 1;  // after frame
};

// Parses "ITEM,ITEM,..." with ITEM either FRAME:KEY (a press released the next frame) or FROM-TO:KEY (held
// from frame FROM, released at frame TO), KEY a letter, a digit, or one of space, enter, period, left,
// right, up, down, escape (e.g. "20:e,40:space,60-120:w"). Throws std::invalid_argument naming the bad item.
std::vector<ScriptedKey> parse_key_script(const std::string& text);

struct WindowOptions {
  int width = 1280;
  int height = 720;
  int clip = 0;                 // the clip viewer's first clip
  bool vsync = true;
  std::vector<ScriptedKey> script;
  std::string screenshot;       // written after frame `screenshot_after` (from the back buffer), then quit;
  int screenshot_after = 60;    // -1: when the demo is closed (Escape or the window's close button)
  int quit_after = -1;          // frames; -1 runs until the window closes
  double stress_seconds = 0.0;  // > 0: a stress run of that many seconds (stress.h), then close
  std::uint64_t stress_seed = 1;
  bool clearance = false;       // the scenario demo starts with its clearance view on
};

// Run the window until closed. Throw render::NoDisplayError when no window can be opened.
// The scenario demo: the scenario opens at once (its motions load and its policy trains in the background).
// `folder`: the user's folder of takes the scenario was made for (its panel is shown), or nullptr.
void run_demo_window(const std::string& scenario, const std::optional<Params>& params, const WindowOptions& options,
                     std::shared_ptr<const MotionFolder> folder = nullptr);
// The crowd demo (crowd_app.h).
void run_crowd_window(const CrowdRunOptions& crowd_options, const WindowOptions& options);
// The clip viewer.
void run_clip_viewer_window(const DemoMotions& motions, const WindowOptions& options);

}  // namespace prep::demo
